"""Chains are cut and reversed exactly: shared points bit for bit, lengths kept."""

from __future__ import annotations

import math

import numpy as np
import pytest

from arcspline.geometry import CircularArc, Line, Path, Point, Subpath, approximate_path
from arcspline.machining.chains import (
    chain_length,
    reversed_chain,
    rotated,
    split,
    split_at_lengths,
)

from .shapes import circle, polygon, stadium

ARC = CircularArc(Point(2.0, 0.0), Point(0.0, 2.0), Point(0.0, 0.0), 2.0, 0.0, 0.5 * math.pi)


def _sampled_length(element: Line | CircularArc, n: int = 20001) -> float:
    """The length as a fine polyline of points from the element's own definition."""
    if isinstance(element, Line):
        return math.dist(element.start, element.end)
    a = element.start_angle_rad + np.linspace(0.0, element.sweep_rad, n)
    x = element.center[0] + element.radius * np.cos(a)
    y = element.center[1] + element.radius * np.sin(a)
    return float(np.hypot(np.diff(x), np.diff(y)).sum())


def _accepted(chain: tuple[Line | CircularArc, ...], closed: bool) -> None:
    """The core takes the chain (chained bit for bit, arcs consistent)."""
    approximate_path(Path((Subpath(chain, closed),)), 0.01)


@pytest.mark.parametrize("element", [Line(Point(1.0, 1.0), Point(4.0, 5.0)), ARC])
def test_split_shares_its_point_and_keeps_the_length(element: Line | CircularArc) -> None:
    head, tail = split(element, 0.3)
    assert head.end is tail.start or head.end == tail.start
    assert head.start == element.start
    assert tail.end == element.end
    whole = _sampled_length(element)
    assert _sampled_length(head) / whole == pytest.approx(0.3, abs=1e-6)
    assert _sampled_length(head) + _sampled_length(tail) == pytest.approx(whole, rel=1e-7)
    _accepted((head, tail), False)


def test_reversing_twice_gives_the_chain_back_and_the_core_takes_it() -> None:
    chain = stadium(0.0, 10.0, 0.0, 2.0)
    back = reversed_chain(chain)
    assert back[0].start == chain[-1].end
    assert back[-1].end == chain[0].start
    _accepted(back, True)
    again = reversed_chain(back)
    for a, b in zip(again, chain, strict=True):
        assert a.start == b.start
        assert a.end == b.end
        if isinstance(a, CircularArc):
            assert isinstance(b, CircularArc)
            assert a.sweep_rad == pytest.approx(b.sweep_rad)
            assert math.cos(a.start_angle_rad - b.start_angle_rad) == pytest.approx(1.0)


def test_split_at_lengths_cuts_where_asked() -> None:
    loop = rotated((*circle(0.0, 0.0, 5.0),), 1)
    total = 2.0 * math.pi * 5.0
    assert chain_length(loop) == pytest.approx(total)
    positions = [1.0, 7.0, 7.5, 20.0]
    pieces, starts = split_at_lengths(loop, positions, 1e-9)
    _accepted(pieces, True)
    for where, k in zip(positions, starts, strict=True):
        before = sum(_sampled_length(p) for p in pieces[:k])
        assert before == pytest.approx(where, abs=1e-6)


def test_a_cut_near_a_joint_uses_the_joint() -> None:
    square = polygon([(0, 0), (10, 0), (10, 10), (0, 10)])
    pieces, starts = split_at_lengths(square, [10.0 + 1e-12, 25.0], 1e-9)
    assert len(pieces) == 5
    assert starts[0] == 1
    assert pieces[1].start == (10.0, 0.0)
    assert pieces[starts[1]].start == (5.0, 10.0)
