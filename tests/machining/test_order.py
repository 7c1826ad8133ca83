"""The cutting order: inner contours first, then the nearest; the rapid length."""

from __future__ import annotations

import itertools
import math

from arcspline.geometry import Point
from arcspline.machining.order import cutting_order


def _rapids(order: tuple[int, ...], entries: list[Point], exits: list[Point]) -> float:
    here, total = (0.0, 0.0), 0.0
    for k in order:
        total += math.hypot(entries[k][0] - here[0], entries[k][1] - here[1])
        here = exits[k]
    return total


def test_nearest_next_without_constraints() -> None:
    entries = [Point(10.0, 0.0), Point(1.0, 0.0), Point(5.0, 0.0)]
    exits = list(entries)
    found = cutting_order(entries, exits, [[], [], []])
    assert found.order == (1, 2, 0)
    assert found.rapid_length == _rapids(found.order, entries, exits) == 10.0


def test_a_contour_waits_for_the_contours_inside_it() -> None:
    entries = [Point(0.0, 0.0), Point(3.0, 3.0), Point(50.0, 50.0), Point(4.0, 4.0)]
    exits = [Point(0.0, 1.0), Point(3.0, 4.0), Point(50.0, 51.0), Point(4.0, 5.0)]
    waits = [[1, 2], [], [], [0]]  # 0 encloses 1 and 2; 3 encloses 0
    found = cutting_order(entries, exits, waits)
    position = {k: n for n, k in enumerate(found.order)}
    for k, ws in enumerate(waits):
        assert all(position[w] < position[k] for w in ws)
    assert sorted(found.order) == [0, 1, 2, 3]
    assert found.order == (1, 2, 0, 3)
    assert math.isclose(found.rapid_length, _rapids(found.order, entries, exits))


def test_the_greedy_order_is_as_short_as_the_best_on_a_line() -> None:
    entries = [Point(float(x), 0.0) for x in (7, 2, 9, 4, 1)]
    found = cutting_order(entries, entries, [[]] * 5)
    best = min(_rapids(p, entries, entries) for p in itertools.permutations(range(5)))
    assert math.isclose(found.rapid_length, best)
