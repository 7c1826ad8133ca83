"""Ordering toolpaths (``arcspline.drawings.order``): the rapids never get longer than in the
input order (a property test, with the rapid lengths recomputed here), a case whose optimal
order is known, and the choice of a closed contour's start."""

from __future__ import annotations

import itertools
import math
import random

from hypothesis import given, settings
from hypothesis import strategies as st

from arcspline.drawings.join import Toolpath
from arcspline.drawings.order import order
from arcspline.geometry.curves.segments import Line, Subpath
from arcspline.geometry.spline import Point


def _open(a: tuple[float, float], b: tuple[float, float], name: str) -> Toolpath:
    return Toolpath(Subpath((Line(a, b),)), (name,))


def _square(x: float, y: float, side: float, name: str) -> Toolpath:
    corners = [(x, y), (x + side, y), (x + side, y + side), (x, y + side)]
    lines = tuple(Line(a, b) for a, b in zip(corners, corners[1:] + corners[:1], strict=True))
    return Toolpath(Subpath(lines, True), (name,))


def _rapids(toolpaths: tuple[Toolpath, ...] | list[Toolpath], start: Point) -> float:
    """Sum of the straight moves from ``start`` to each start, from each end on."""
    here, total = start, 0.0
    for t in toolpaths:
        total += math.hypot(t.subpath.segments[0].start[0] - here[0],
                            t.subpath.segments[0].start[1] - here[1])  # fmt: skip
        here = t.subpath.segments[-1].end
    return total


def _cyclic_shifts(segments: tuple[Line, ...]) -> list[tuple[Line, ...]]:
    return [segments[k:] + segments[:k] for k in range(len(segments))]


def _is_same_toolpath(out: Toolpath, original: Toolpath) -> bool:
    """The same cut: an open toolpath as it was or reversed; a closed one rotated only."""
    segs = original.subpath.segments
    if original.subpath.closed:
        return out.subpath.closed and out.subpath.segments in _cyclic_shifts(segs)  # type: ignore[operator]
    back = tuple(Line(s.end, s.start) for s in reversed(segs))  # type: ignore[union-attr]
    return out.subpath.segments in (segs, back) and not out.subpath.closed


_xy = st.floats(-100, 100, allow_nan=False)


@st.composite
def _toolpaths(draw: st.DrawFn) -> list[Toolpath]:
    n = draw(st.integers(1, 40))
    out = []
    for k in range(n):
        x, y = draw(_xy), draw(_xy)
        if draw(st.booleans()):
            out.append(_square(x, y, draw(st.floats(0.5, 10)), f"s{k}"))
        else:
            x2, y2 = draw(_xy), draw(_xy)
            if (x, y) != (x2, y2):
                out.append(_open((x, y), (x2, y2), f"o{k}"))
    return out or [_open((0, 0), (1, 1), "only")]


@settings(max_examples=200, deadline=None)
@given(_toolpaths(), _xy, _xy, st.booleans())
def test_rapids_after_ordering_are_never_longer_and_every_toolpath_is_kept(
    toolpaths: list[Toolpath], x: float, y: float, choose_start: bool
) -> None:
    start = Point(x, y)
    ordered = order(toolpaths, start, choose_start)
    before = _rapids(toolpaths, start)
    after = _rapids(ordered.toolpaths, start)
    assert math.isclose(ordered.rapid_before, before, rel_tol=1e-12, abs_tol=1e-9)
    assert math.isclose(ordered.rapid_after, after, rel_tol=1e-12, abs_tol=1e-9)
    assert after <= before + 1e-9
    assert sorted(ordered.order) == list(range(len(toolpaths)))
    for out, k in zip(ordered.toolpaths, ordered.order, strict=True):
        assert _is_same_toolpath(out, toolpaths[k])
        assert sorted(out.sources) == sorted(toolpaths[k].sources)


def test_shuffled_dashes_on_a_line_are_put_in_order_and_direction() -> None:
    # Ten unit dashes along the x axis, 10 apart, shuffled and half drawn backwards: the
    # shortest rapids visit them left to right, each forward: 9 gaps of 9.
    rnd = random.Random(3)
    dashes = []
    for k in range(10):
        a, b = (10.0 * k, 0.0), (10.0 * k + 1.0, 0.0)
        dashes.append(_open(b, a, f"d{k}") if k % 2 else _open(a, b, f"d{k}"))
    rnd.shuffle(dashes)
    ordered = order(dashes)
    assert [t.sources[0] for t in ordered.toolpaths] == [f"d{k}" for k in range(10)]
    assert [t.subpath.segments[0].start for t in ordered.toolpaths] == [
        (10.0 * k, 0.0) for k in range(10)
    ]
    assert ordered.rapid_after == 81.0
    assert ordered.rapid_before == _rapids(dashes, Point(0.0, 0.0))


def test_a_small_case_reaches_the_optimum_found_by_trying_every_order() -> None:
    # Nearest neighbour from the origin takes the near dash (2, 0.7) first and must cross
    # back later; 2-opt with direction flips reaches the best of all 6!·2^6 orders.
    spots = [(0.0, 0.0), (4.0, 0.0), (8.0, 0.0), (8.0, 1.5), (4.0, 1.5), (2.0, 0.7)]
    dashes = [_open(p, (p[0] + 0.1, p[1]), f"p{k}") for k, p in enumerate(spots)]
    best = math.inf
    for perm in itertools.permutations(dashes):
        for flips in itertools.product((False, True), repeat=len(perm)):
            tour = [_reversed(t) if f else t for t, f in zip(perm, flips, strict=True)]
            best = min(best, _rapids(tour, Point(0.0, 0.0)))
    ordered = order(list(reversed(dashes)))
    assert math.isclose(ordered.rapid_after, best, rel_tol=1e-12)


def _reversed(t: Toolpath) -> Toolpath:
    (line,) = t.subpath.segments
    return Toolpath(Subpath((Line(line.end, line.start),)), t.sources)


def test_a_closed_contour_starts_at_the_vertex_nearest_the_tool_when_asked() -> None:
    square = _square(0.0, 0.0, 10.0, "sq")
    start = Point(9.0, 11.0)
    kept = order([square], start)
    assert kept.toolpaths[0].subpath.segments[0].start == (0.0, 0.0)
    chosen = order([square], start, choose_start=True)
    segs = chosen.toolpaths[0].subpath.segments
    assert segs[0].start == (10.0, 10.0)
    assert segs == square.subpath.segments[2:] + square.subpath.segments[:2]
    assert chosen.toolpaths[0].subpath.closed
    assert math.isclose(chosen.rapid_after, math.sqrt(2.0), rel_tol=1e-15)
    assert math.isclose(chosen.rapid_before, math.hypot(9.0, 11.0), rel_tol=1e-15)


def test_closed_contours_are_never_reversed() -> None:
    squares = [_square(20.0 * k, 0.0, 5.0, f"s{k}") for k in range(6)][::-1]
    ordered = order(squares, choose_start=True)
    for out, k in zip(ordered.toolpaths, ordered.order, strict=True):
        assert out.subpath.segments in _cyclic_shifts(squares[k].subpath.segments)  # type: ignore[arg-type]
    assert [t.sources[0] for t in ordered.toolpaths] == [f"s{k}" for k in range(6)]


def test_an_input_order_already_best_is_kept() -> None:
    dashes = [_open((3.0 * k, 0.0), (3.0 * k + 1.0, 0.0), f"d{k}") for k in range(5)]
    ordered = order(dashes)
    assert ordered.order == (0, 1, 2, 3, 4)
    assert ordered.rapid_after == ordered.rapid_before == 8.0


def test_twenty_thousand_toolpaths_are_ordered_shorter() -> None:
    rnd = random.Random(5)
    toolpaths = []
    for k in range(20_000):
        x, y = rnd.uniform(0, 1000), rnd.uniform(0, 1000)
        toolpaths.append(_open((x, y), (x + rnd.uniform(-2, 2), y + 1.0), f"t{k}"))
    ordered = order(toolpaths)
    assert ordered.rapid_after < 0.05 * ordered.rapid_before
    assert sorted(ordered.order) == list(range(20_000))
    assert math.isclose(ordered.rapid_after, _rapids(ordered.toolpaths, Point(0, 0)))
