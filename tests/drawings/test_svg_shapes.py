"""SVG's shapes as subpaths: through documents (tests/data/svg/, y flipped into millimetres,
values by hand) and directly in the element's own numbers, curves sampled from their own
parameters and checked against the implicit equation of the shape (SVG 2 §10)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from arcspline.drawings.model import DocumentError
from arcspline.drawings.svg import read_svg
from arcspline.drawings.svg_shapes import ellipse, polyline, rounded_rect
from arcspline.geometry.curves.segments import CircularArc, EllipticalArc, Line
from arcspline.geometry.spline import Point
from tests.drawings.svg_support import SVG_OPEN, assert_checked, ends, read, sample

# ---- read from documents ------------------------------------------------------------------------


def test_rounded_rect_corners_are_quarter_arcs() -> None:
    round_, clamped = read("rounded_rect.svg").elements
    segments = round_.subpath.segments
    # x 10..50, y 20..50 (y down) -> y up 80..50; rx = ry = 5.
    assert [type(s).__name__ for s in segments] == ["Line", "CircularArc"] * 4
    assert ends(read("rounded_rect.svg"))[0] == (
        (15.0, 80.0), (45.0, 80.0), (45.0, 80.0), (50.0, 75.0), (50.0, 75.0), (50.0, 55.0),
        (50.0, 55.0), (45.0, 50.0), (45.0, 50.0), (15.0, 50.0), (15.0, 50.0), (10.0, 55.0),
        (10.0, 55.0), (10.0, 75.0), (10.0, 75.0), (15.0, 80.0),
    )  # fmt: skip
    corner = segments[1]
    assert isinstance(corner, CircularArc)
    assert (corner.center, corner.radius) == ((45.0, 75.0), 5.0)
    assert corner.sweep_rad == pytest.approx(-math.pi / 2)  # clockwise in y up, as drawn
    # rx = 30, ry auto = 30, clamped to 20 (w/2) and 15 (h/2): four elliptical quarters, no
    # straight edge; x 10..50, y 60..90 y down -> 40..10 y up, centre (30, 25).
    arcs = clamped.subpath.segments
    assert all(isinstance(a, EllipticalArc) for a in arcs)
    assert [a.start for a in arcs] == [(30, 40), (50, 25), (30, 10), (10, 25)]
    for arc in arcs:
        pts = sample(arc)  # type: ignore[arg-type]
        assert np.abs(((pts[:, 0] - 30) / 20) ** 2 + ((pts[:, 1] - 25) / 15) ** 2 - 1).max() < 1e-12
    assert_checked(list(segments))
    assert_checked(list(arcs))


def test_circle_is_two_half_arcs() -> None:
    drawing = read_svg(
        '<svg xmlns="http://www.w3.org/2000/svg" width="10" height="10">'
        '<circle cx="5" cy="5" r="2"/></svg>'
    )
    (element,) = drawing.elements
    first, second = element.subpath.segments
    k = 25.4 / 96  # px in mm; y up: 10 px - y
    assert isinstance(first, CircularArc)
    assert first.start == pytest.approx((7 * k, 5 * k))
    assert second.end == first.start
    assert first.radius == pytest.approx(2 * k)
    assert abs(first.sweep_rad) == pytest.approx(math.pi)
    assert_checked([first, second])


def test_shapes_of_zero_size_and_bad_shapes() -> None:
    drawing = read_svg(
        SVG_OPEN + '<rect width="0" height="5"/><circle r="0"/><ellipse rx="2" ry="0"/>'
        '<line x1="1" y1="1" x2="1" y2="1"/><polyline points="3 3 3 3"/><path d=" "/></svg>'
    )
    assert drawing.elements == ()
    assert sorted((w.element.split(" ")[0], w.occurrences) for w in drawing.warnings) == [
        ("circle", 1), ("ellipse", 1), ("line", 1), ("path", 1), ("polyline", 1), ("rect", 1)
    ]  # fmt: skip
    for bad, words in (
        ('<rect id="r" width="-1" height="1"/>', "width and height must be >= 0"),
        ('<rect id="r" width="2" height="1" rx="-1"/>', "rx must be >= 0"),
        (
            '<polygon id="r" points="0 0,"/>',  # the end: offset 4
            "at character 4: expected a number after ','",
        ),
        ('<polygon id="r" points="0 0 x"/>', "at character 4: expected a finite number"),
    ):
        with pytest.raises(DocumentError) as caught:
            read_svg(SVG_OPEN + bad + "</svg>")
        assert caught.value.where.split("#")[1] == "r"
        assert words in caught.value.reason


def test_ellipse_radius_auto_takes_the_other() -> None:
    # ellipse rx 3, ry auto -> 3: a circle, two CircularArcs of radius 3 px.
    drawing = read_svg(SVG_OPEN + '<ellipse cx="5" cy="5" rx="3"/></svg>')
    (element,) = drawing.elements
    assert all(isinstance(s, CircularArc) for s in element.subpath.segments)
    assert element.subpath.segments[0].radius == pytest.approx(3 * 25.4 / 96)  # type: ignore[union-attr]


# ---- in the element's numbers -------------------------------------------------------------


def test_rounded_rect_sharp_when_a_radius_is_zero() -> None:
    sub = rounded_rect(1.0, 2.0, 4.0, 3.0, 0.0, 1.0)
    assert sub.closed
    assert [(s.start, s.end) for s in sub.segments] == [
        ((1, 2), (5, 2)), ((5, 2), (5, 5)), ((5, 5), (1, 5)), ((1, 5), (1, 2))
    ]  # fmt: skip
    assert all(isinstance(s, Line) for s in sub.segments)


def test_rounded_rect_corners_lie_on_their_ellipses() -> None:
    # x 0..10, y 0..6, rx 2, ry 1 (y down): corner centres (8,1), (8,5), (2,5), (2,1).
    sub = rounded_rect(0.0, 0.0, 10.0, 6.0, 2.0, 1.0)
    arcs = [s for s in sub.segments if isinstance(s, EllipticalArc)]
    assert [a.center for a in arcs] == [(8, 1), (8, 5), (2, 5), (2, 1)]
    for arc in arcs:
        pts = sample(arc)
        cx, cy = arc.center
        assert np.abs(((pts[:, 0] - cx) / 2) ** 2 + ((pts[:, 1] - cy) / 1) ** 2 - 1).max() < 1e-12
        # each corner is the quarter outside the inner rectangle 2..8 x 1..5
        assert np.all(np.abs(pts[:, 0] - 5) >= 3 - 1e-12)
        assert np.all(np.abs(pts[:, 1] - 3) >= 2 - 1e-12)
    assert_checked(list(sub.segments))
    assert sub.segments[-1].end == sub.segments[0].start == (2, 0)


def test_ellipse_is_two_halves_through_the_axis_ends() -> None:
    sub = ellipse(1.0, -2.0, 4.0, 1.5)
    first, second = sub.segments
    assert (first.start, first.end, second.end) == ((5, -2), (-3, -2), (5, -2))
    for half in (first, second):
        assert isinstance(half, EllipticalArc)
        pts = sample(half)
        assert np.abs(((pts[:, 0] - 1) / 4) ** 2 + ((pts[:, 1] + 2) / 1.5) ** 2 - 1).max() < 1e-12
        assert half.sweep_rad == math.pi
    assert_checked([first, second])


def test_polyline_and_polygon() -> None:
    a, b, c = Point(0.0, 0.0), Point(3.0, 0.0), Point(3.0, 4.0)
    open_ = polyline([a, b, c], closed=False)
    closed = polyline([a, b, c], closed=True)
    assert open_ is not None
    assert closed is not None
    assert [(s.start, s.end) for s in open_.segments] == [(a, b), (b, c)]
    assert [(s.start, s.end) for s in closed.segments] == [(a, b), (b, c), (c, a)]
    assert (open_.closed, closed.closed) == (False, True)
    # already closed by its points: no extra edge
    again = polyline([a, b, c, a], closed=True)
    assert again is not None
    assert len(again.segments) == 3
    assert polyline([a, a], closed=True) is None
    assert polyline([], closed=False) is None


def test_points_may_run_together_as_in_path_data() -> None:
    # "0-1.5.5 1e1,2 3": 0, -1.5, .5, 10, 2, 3: the points (0,-1.5), (.5,10), (2,3).
    drawing = read_svg(SVG_OPEN + '<polyline points="0-1.5.5 1e1,2 3"/></svg>')
    (element,) = drawing.elements
    k = 25.4 / 96
    starts = [s.start for s in element.subpath.segments]
    assert starts == [
        pytest.approx((0.0, (10 + 1.5) * k)), pytest.approx((0.5 * k, (10 - 10) * k))
    ]  # fmt: skip
