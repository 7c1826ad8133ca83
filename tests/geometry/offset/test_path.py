"""offset_path: every subpath of a fitted path offset and fitted again."""

from __future__ import annotations

import math

import pytest

from arcspline.geometry import DEFAULT_LIMITS
from arcspline.geometry.curves.segments import CircularArc, Line, Path, Subpath
from arcspline.geometry.errors import GeometryError
from arcspline.geometry.offset import OffsetOptions, elements_of, offset_path
from arcspline.geometry.paths import approximate_path
from arcspline.geometry.spline import ArcSegment, Point
from tests.geometry.offset import shapes
from tests.geometry.offset.checks import assert_offset


def _fitted(*subpaths: Subpath, tolerance: float = 0.01):  # type: ignore[no-untyped-def]
    return approximate_path(Path(subpaths), tolerance)


def test_circles_come_back_as_the_concentric_circles() -> None:
    ccw = Subpath(tuple(shapes.circle((0.0, 0.0), 5.0)), True)
    cw = Subpath(tuple(shapes.reversed_chain(shapes.circle((20.0, 0.0), 5.0))), True)
    spline = _fitted(ccw, cw)
    for side, radius in (("outside", 6.0), ("inside", 4.0)):
        out = offset_path(spline, OffsetOptions(1.0, side), DEFAULT_LIMITS)  # type: ignore[arg-type]
        assert out.spline is not None
        assert out.origin == (0, 1)
        assert out.notes == ()
        assert out.source_max_deviation == spline.stats.max_deviation
        for sub in out.spline.subpaths:
            segments = sub.spline.segments
            assert all(isinstance(s, ArcSegment) and s.radius == radius for s in segments)


def test_a_square_with_holes_outside_and_inside() -> None:
    outer = shapes.polygon([(0, 0), (30, 0), (30, 20), (0, 20)])
    holes = [shapes.reversed_chain(shapes.polygon([(x, 5), (x + 6, 5), (x + 6, 15), (x, 15)]))
             for x in (4.0, 18.0)]  # fmt: skip
    spline = _fitted(*(Subpath(tuple(c), True) for c in [outer, *holes]))
    contours = [elements_of(s.spline) for s in spline.subpaths]
    for side in ("outside", "inside"):
        out = offset_path(spline, OffsetOptions(1.0, side), DEFAULT_LIMITS)  # type: ignore[arg-type]
        assert out.spline is not None
        assert out.origin == (0, 1, 2)
        for k, sub in enumerate(out.spline.subpaths):
            path = Subpath(elements_of(sub.spline), True)
            assert_offset([contours[k]], [path], 1.0, side)  # type: ignore[arg-type]


def test_open_paths_take_left_and_right_but_not_inside() -> None:
    zig = Subpath((Line(Point(0, 0), Point(5, 3)), Line(Point(5, 3), Point(10, 0))))
    spline = _fitted(zig)
    out = offset_path(spline, OffsetOptions(0.5, "left"), DEFAULT_LIMITS)
    assert out.spline is not None
    assert not out.spline.subpaths[0].closed
    with pytest.raises(GeometryError) as caught:
        offset_path(spline, OffsetOptions(0.5, "inside"), DEFAULT_LIMITS)
    assert caught.value.field == "offset.side"
    assert "path.subpaths[0]" in caught.value.message


def test_a_figure_eight_has_no_inside() -> None:
    eight = Subpath(tuple(shapes.polygon([(0, 0), (4, 4), (4, 0), (0, 4)])), True)
    spline = _fitted(Subpath(tuple(shapes.circle((20, 0), 1.0)), True), eight)
    with pytest.raises(GeometryError) as caught:
        offset_path(spline, OffsetOptions(0.5, "outside"), DEFAULT_LIMITS)
    assert caught.value.field == "path.subpaths[1]"
    assert caught.value.kind == "crossing"
    assert "(2, 2)" in caught.value.message
    # left/right of a crossing contour is well defined
    offset_path(spline, OffsetOptions(0.5, "left"), DEFAULT_LIMITS)


def test_an_open_contour_beside_closed_ones_is_left_out_with_a_note() -> None:
    zig = Subpath((Line(Point(0, 0), Point(5, 3)), Line(Point(5, 3), Point(10, 0))))
    spline = _fitted(zig, Subpath(tuple(shapes.circle((20, 0), 1.0)), True))
    out = offset_path(spline, OffsetOptions(0.5, "inside"), DEFAULT_LIMITS)
    assert out.origin == (1,)
    assert [(i, n.kind) for i, n in out.notes] == [(0, "open")]


def test_a_tool_larger_than_everything_is_refused() -> None:
    spline = _fitted(Subpath(tuple(shapes.circle((0, 0), 1.0)), True))
    with pytest.raises(GeometryError) as caught:
        offset_path(spline, OffsetOptions(1.5, "inside"), DEFAULT_LIMITS)
    assert caught.value.field == "offset.distance"
    assert caught.value.kind == "tool_too_large"


def test_notes_name_their_source_subpath() -> None:
    spline = _fitted(
        Subpath(tuple(shapes.circle((0, 0), 5.0)), True),
        Subpath(tuple(shapes.circle((20, 0), 0.5)), True),
    )
    out = offset_path(spline, OffsetOptions(1.0, "inside"), DEFAULT_LIMITS)
    assert out.origin == (0,)
    assert [(i, n.kind) for i, n in out.notes] == [(1, "vanished")]


def test_input_arcs_and_lines_come_back_as_themselves() -> None:
    part = shapes.rounded_rectangle(10.0, 6.0, 2.0)
    spline = _fitted(Subpath(tuple(part), True))
    out = offset_path(spline, OffsetOptions(0.5, "outside"), DEFAULT_LIMITS)
    assert out.spline is not None
    segments = out.spline.subpaths[0].spline.segments
    arcs = [s for s in segments if isinstance(s, ArcSegment)]
    assert len(segments) == 8
    assert len(arcs) == 4
    assert all(a.radius == 2.5 and abs(a.sweep_rad) == pytest.approx(math.pi / 2) for a in arcs)
    assert isinstance(part[1], CircularArc)
