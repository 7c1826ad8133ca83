"""The cutting order (docs/machining.md §7): a contour after every contour inside it (a
hole is cut while the part around it still holds), and otherwise the nearest next.

Greedy nearest neighbour over the contours whose inner contours are all done, from the
origin: the rapid from where the last cut ended (its lead-out) to the nearest lead-in start
among them. ``rapid_length`` is the length of all the rapids in the XY plane.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import NamedTuple

import numpy as np

from arcspline.geometry import Point

#: Where the rapids start.
ORIGIN = Point(0.0, 0.0)


class Order(NamedTuple):
    """The order (indices into the input) and the rapid length through it."""

    order: tuple[int, ...]
    rapid_length: float


def cutting_order(
    entries: Sequence[Point],
    exits: Sequence[Point],
    waits_for: Sequence[Sequence[int]],
    start: Point = ORIGIN,
) -> Order:
    """Visit every item once: item ``i`` only after every item of ``waits_for[i]``, and of
    the items free to go, the one whose entry is nearest the current position (ties: the
    lowest index)."""
    n = len(entries)
    blocked = [len(set(w)) for w in waits_for]
    unlocks: list[list[int]] = [[] for _ in range(n)]
    for i, waits in enumerate(waits_for):
        for j in set(waits):
            unlocks[j].append(i)
    entry = np.array(entries, dtype=np.float64).reshape(-1, 2)
    free = np.array([b == 0 for b in blocked], dtype=np.bool_)
    here = (float(start[0]), float(start[1]))
    order: list[int] = []
    total = 0.0
    for _ in range(n):
        candidates = np.flatnonzero(free)
        if not len(candidates):
            raise ValueError("the contours wait for each other in a cycle")
        gaps = np.hypot(entry[candidates, 0] - here[0], entry[candidates, 1] - here[1])
        k = int(candidates[int(np.argmin(gaps))])
        total += math.dist(here, entries[k])
        order.append(k)
        free[k] = False
        here = (float(exits[k][0]), float(exits[k][1]))
        for i in unlocks[k]:
            blocked[i] -= 1
            if blocked[i] == 0:
                free[i] = True
    return Order(tuple(order), total)
