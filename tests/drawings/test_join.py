"""Joining elements into toolpaths (``arcspline.drawings.join``): hand-made cases checked
against hand-computed coordinates, a property test that every element survives (maybe
reversed, its joined ends moved by at most the reported gap) in bit-exact chains, and 100,000
random segments."""

from __future__ import annotations

import itertools
import math
import random

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from arcspline.drawings.join import JoinError, Toolpath, join, reversed_segment
from arcspline.drawings.model import Element
from arcspline.geometry import approximate_path
from arcspline.geometry.curves.segments import (
    CircularArc,
    Cubic,
    EllipticalArc,
    Line,
    Path,
    Quadratic,
    Segment,
    Subpath,
)


def _line(a: tuple[float, float], b: tuple[float, float], name: str) -> Element:
    return Element(Subpath((Line(a, b),)), name)


def _arc(cx: float, cy: float, r: float, a0: float, sweep: float) -> CircularArc:
    """An arc with its end points as the test computes them."""
    a1 = a0 + sweep
    return CircularArc(
        (cx + r * math.cos(a0), cy + r * math.sin(a0)),
        (cx + r * math.cos(a1), cy + r * math.sin(a1)),
        (cx, cy),
        r,
        a0,
        sweep,
    )


def _assert_chained(toolpath: Toolpath) -> None:
    segs = toolpath.subpath.segments
    for a, b in itertools.pairwise(segs):
        assert a.end == b.start  # bit for bit
    if toolpath.subpath.closed:
        assert segs[-1].end == segs[0].start


def test_two_lines_end_to_end_become_one_open_subpath() -> None:
    joined = join([_line((0, 0), (1, 0), "a"), _line((1, 0), (3, 2), "b")], 0.001)
    (toolpath,) = joined.toolpaths
    assert toolpath.sources == ("a", "b")
    assert toolpath.subpath == Subpath((Line((0, 0), (1, 0)), Line((1, 0), (3, 2))), False)
    assert (joined.largest_gap, joined.joins, joined.bridges) == (0.0, 1, 0)


def test_a_neighbour_drawn_the_other_way_is_reversed() -> None:
    joined = join([_line((0, 0), (1, 0), "a"), _line((2, 5), (1, 0), "b")], 0.001)
    (toolpath,) = joined.toolpaths
    assert toolpath.subpath.segments == (Line((0, 0), (1, 0)), Line((1, 0), (2, 5)))
    assert toolpath.sources == ("a", "b")


def test_the_first_element_in_input_order_keeps_its_direction() -> None:
    # b's end meets a's start: the chain runs b then a, a forward.
    joined = join([_line((1, 0), (2, 0), "a"), _line((0, 0), (1, 0), "b")], 0.0)
    (toolpath,) = joined.toolpaths
    assert toolpath.sources == ("b", "a")
    assert toolpath.subpath.segments == (Line((0, 0), (1, 0)), Line((1, 0), (2, 0)))


def test_a_gap_within_the_tolerance_is_closed_by_moving_a_line_end() -> None:
    joined = join([_line((0, 0), (1, 0), "a"), _line((1.0003, 0.0004), (2, 0), "b")], 0.001)
    (toolpath,) = joined.toolpaths
    assert toolpath.subpath.segments == (Line((0, 0), (1, 0)), Line((1, 0), (2, 0)))
    assert joined.largest_gap == pytest.approx(0.0005, rel=1e-9)  # a 3-4-5 triangle
    assert joined.joins == 1


def test_a_gap_over_the_tolerance_is_left_open() -> None:
    elements = [_line((0, 0), (1, 0), "a"), _line((1.0003, 0.0004), (2, 0), "b")]
    joined = join(elements, 0.0004)
    assert [t.sources for t in joined.toolpaths] == [("a",), ("b",)]
    assert [t.subpath for t in joined.toolpaths] == [e.subpath for e in elements]
    assert (joined.largest_gap, joined.joins) == (0.0, 0)


def test_a_bezier_end_is_moved_onto_the_neighbour() -> None:
    cubic = Cubic((1.0002, 0), (2, 1), (3, 1), (4, 0))
    joined = join([_line((0, 0), (1, 0), "a"), Element(Subpath((cubic,)), "c")], 0.001)
    (toolpath,) = joined.toolpaths
    assert toolpath.subpath.segments[1] == Cubic((1, 0), (2, 1), (3, 1), (4, 0))


def test_arcs_meeting_within_rounding_are_snapped_not_bridged() -> None:
    first = _arc(0, 0, 1, 0.0, math.pi / 2)  # ends at (6.1e-17, 1)
    second = _arc(0, 2, 1, -math.pi / 2, -math.pi / 2)._replace(start=(0.0, 1.0))
    assert first.end != second.start
    joined = join([Element(Subpath((first,)), "p"), Element(Subpath((second,)), "q")], 0.001)
    (toolpath,) = joined.toolpaths
    assert joined.bridges == 0
    assert len(toolpath.subpath.segments) == 2
    _assert_chained(toolpath)
    # The core takes it: its arcs' end points agree with their centres and angles.
    approximate_path(Path((toolpath.subpath,)), 0.01, "subdivide")


def test_arcs_apart_by_more_than_rounding_are_bridged_by_a_line() -> None:
    first = _arc(0, 0, 1, 0.0, math.pi / 2)
    second = _arc(1e-4, 2, 1, -math.pi / 2, -math.pi / 2)
    joined = join([Element(Subpath((first,)), "p"), Element(Subpath((second,)), "q")], 0.001)
    (toolpath,) = joined.toolpaths
    assert joined.bridges == 1
    segs = toolpath.subpath.segments
    assert segs[0] == first
    assert segs[2] == second
    assert segs[1] == Line(first.end, second.start)
    assert joined.largest_gap == pytest.approx(1e-4, rel=1e-6)
    approximate_path(Path((toolpath.subpath,)), 0.01, "subdivide")


def test_a_square_of_four_lines_in_any_direction_becomes_one_closed_subpath() -> None:
    elements = [
        _line((0, 0), (10, 0), "bottom"),
        _line((10, 10), (10, 0), "right"),  # drawn downwards
        _line((0, 10), (10, 10), "top"),  # drawn left to right
        _line((0, 10), (0, 0), "left"),
    ]
    joined = join(elements, 1e-6)
    (toolpath,) = joined.toolpaths
    assert toolpath.subpath.closed
    assert toolpath.sources == ("bottom", "right", "top", "left")
    assert [s.start for s in toolpath.subpath.segments] == [(0, 0), (10, 0), (10, 10), (0, 10)]
    _assert_chained(toolpath)
    assert joined.joins == 4


def test_a_closed_element_is_left_alone_and_an_arc_closing_on_itself_closes() -> None:
    square = Subpath(tuple(Line(a, b) for a, b in [((0, 0), (1, 0)), ((1, 0), (0, 0))]), True)
    nearly = _arc(5, 5, 2, 0.0, 2 * math.pi - 1e-12)  # ends 2e-12 from its start
    joined = join([Element(square, "s"), Element(Subpath((nearly,)), "c")], 1e-6)
    assert joined.toolpaths[0] == Toolpath(square, ("s",))
    circle = joined.toolpaths[1]
    assert circle.subpath.closed
    _assert_chained(circle)


def test_a_single_short_line_does_not_close_on_itself() -> None:
    joined = join([_line((0, 0), (1e-7, 0), "speck")], 1e-6)
    assert not joined.toolpaths[0].subpath.closed


def test_three_ends_at_one_point_join_the_first_two_in_input_order() -> None:
    elements = [
        _line((0, 0), (1, 0), "a"),
        _line((0, 0), (0, 1), "b"),
        _line((0, 0), (-1, 0), "c"),
    ]
    for _ in range(2):
        joined = join(elements, 0.01)
        assert [t.sources for t in joined.toolpaths] == [("b", "a"), ("c",)]
        assert joined.toolpaths[0].subpath.segments == (
            Line((0, 1), (0, 0)),
            Line((0, 0), (1, 0)),
        )


def test_three_ends_near_one_point_join_the_closest_two() -> None:
    elements = [
        _line((0, 0), (1, 0), "a"),
        _line((-1, 0), (0.0003, 0.0), "b"),
        _line((0, 1), (0.0, 0.0001), "c"),  # nearest a's start
    ]
    joined = join(elements, 0.01)
    assert [t.sources for t in joined.toolpaths] == [("c", "a"), ("b",)]
    assert joined.largest_gap == pytest.approx(0.0001)


def test_reversing_an_arc_keeps_its_points_and_flips_its_sweep() -> None:
    arc = _arc(1, 2, 3, 0.25, 1.5)
    back = reversed_segment(arc)
    assert isinstance(back, CircularArc)
    assert (back.start, back.end, back.center, back.radius) == (arc.end, arc.start, (1, 2), 3)
    assert back.sweep_rad == -1.5
    assert back.start_angle_rad == 1.75
    ellipse = EllipticalArc((1, 0), (0, 2), (0, 0), 1, 2, 0.0, 0.0, math.pi / 2)
    back_e = reversed_segment(ellipse)
    assert isinstance(back_e, EllipticalArc)
    assert (back_e.start, back_e.end, back_e.start_angle_rad, back_e.sweep_rad) == (
        (0, 2),
        (1, 0),
        math.pi / 2,
        -math.pi / 2,
    )
    quad = Quadratic((0, 0), (1, 1), (2, 0))
    assert reversed_segment(quad) == Quadratic((2, 0), (1, 1), (0, 0))


@pytest.mark.parametrize("bad", [-0.1, math.nan, math.inf])
def test_a_bad_join_tolerance_is_refused(bad: float) -> None:
    with pytest.raises(JoinError, match="join tolerance"):
        join([_line((0, 0), (1, 0), "a")], bad)


def _same_within(a: Segment, b: Segment, gap: float) -> bool:
    """Same kind, every point within ``gap`` (end points may have moved) and arc parameters
    equal."""
    if type(a) is not type(b):
        return False
    for p, q in zip(a, b, strict=True):
        if isinstance(p, tuple):
            if math.dist(p, q) > gap * (1 + 1e-9) + 1e-12:
                return False
        elif p != q:
            return False
    return True


def _check_conservation(elements: list[Element], tolerance: float) -> None:
    joined = join(elements, tolerance)
    by_name = {e.source: e for e in elements}
    assert sorted(s for t in joined.toolpaths for s in t.sources) == sorted(by_name)
    total_in = sum(len(e.subpath.segments) for e in elements)
    total_out = sum(len(t.subpath.segments) for t in joined.toolpaths)
    assert total_out == total_in + joined.bridges
    assert joined.largest_gap <= tolerance
    closed = sum(t.subpath.closed for t in joined.toolpaths)
    assert len(joined.toolpaths) == len(elements) - joined.joins + closed
    bridges = 0
    for toolpath in joined.toolpaths:
        _assert_chained(toolpath)
        segs = toolpath.subpath.segments
        # A bridge is a line between two arcs (the only place the join adds one).
        arcs = [isinstance(s, CircularArc | EllipticalArc) for s in segs]
        bridge = [
            isinstance(s, Line) and arcs[i - 1] and arcs[(i + 1) % len(segs)] and len(segs) > 1
            for i, s in enumerate(segs)
        ]
        bridges += sum(bridge)
        out = [s for s, b in zip(segs, bridge, strict=True) if not b]
        k = 0
        for name in toolpath.sources:
            source = by_name[name].subpath.segments
            mine = out[k : k + len(source)]
            back = [reversed_segment(s) for s in reversed(source)]
            gap = joined.largest_gap
            assert all(_same_within(a, b, gap) for a, b in zip(mine, source, strict=True)) or all(
                _same_within(a, b, gap) for a, b in zip(mine, back, strict=True)
            ), name
            k += len(source)
        assert k == len(out)
    assert bridges == joined.bridges


_coord = st.integers(0, 4).map(float)
_jitter = st.floats(-4e-4, 4e-4)


@st.composite
def _elements(draw: st.DrawFn) -> list[Element]:
    """Lines and polylines between the points of a 5 × 5 grid, their ends moved by up to
    0.0006 (within a 0.001 join tolerance, far below the grid's spacing)."""
    n = draw(st.integers(1, 12))
    out = []
    for k in range(n):
        count = draw(st.integers(1, 3))
        pts = [
            (draw(_coord) + draw(_jitter), draw(_coord) + draw(_jitter)) for _ in range(count + 1)
        ]
        if any(a == b for a, b in itertools.pairwise(pts)):
            continue
        segs = tuple(Line(a, b) for a, b in itertools.pairwise(pts))
        out.append(Element(Subpath(segs), f"e{k}"))
    return out


@settings(max_examples=200, deadline=None)
@given(_elements())
def test_joining_keeps_every_segment_within_the_gap(elements: list[Element]) -> None:
    _check_conservation(elements, 0.001)


def test_quarter_arcs_on_a_grid_are_snapped_or_bridged_and_all_kept() -> None:
    rnd = random.Random(7)
    elements = []
    for k in range(300):
        # Every third arc's centre is 1e-5 off the grid: its ends meet others with gaps of
        # 1e-5, too far to move an arc's end, so a line bridges them.
        shift = 1e-5 if k % 3 == 0 else 0.0
        a0 = rnd.choice([0.0, math.pi / 2, math.pi, -math.pi / 2])
        arc = _arc(rnd.randint(0, 6) + shift, rnd.randint(0, 6), 1.0, a0, math.pi / 2)
        elements.append(Element(Subpath((arc,)), f"e{k}"))
    joined = join(elements, 1e-3)
    assert joined.bridges > 0
    assert joined.joins > 100
    _check_conservation(elements, 1e-3)


def test_one_hundred_thousand_random_segments_are_joined() -> None:
    rnd = random.Random(17)
    elements = []
    for k in range(100_000):
        x, y = rnd.randint(0, 300), rnd.randint(0, 300)
        dx, dy = rnd.choice([(1, 0), (0, 1), (-1, 0), (0, -1)])
        jitter = rnd.uniform(-1e-4, 1e-4)
        elements.append(_line((x + jitter, y), (x + dx, y + dy), f"e{k}"))
    joined = join(elements, 1e-3)
    assert joined.joins > 10_000
    assert sum(len(t.subpath.segments) for t in joined.toolpaths) == 100_000
    for toolpath in joined.toolpaths:
        _assert_chained(toolpath)
    assert sorted(s for t in joined.toolpaths for s in t.sources) == sorted(
        e.source for e in elements
    )
