"""Lines and arcs as columns of arrays, the form every offset kernel works on
(docs/offsets.md §2).

Row ``i`` is one element: ``is_arc``; ``start``/``end`` ``(n, 2)``; for arcs ``center``
``(n, 2)``, ``radius``, ``angle`` (of the start, radians) and signed ``sweep`` (zeros for
lines). A point's parameter ``t ∈ [0, 1]`` is the fraction of a line's length, or of an
arc's sweep.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import NamedTuple

import numpy as np

from ..curves.segments import CircularArc, Line
from ..spline import BoolArray, FloatArray, Point
from .types import Element

TAU = 2.0 * math.pi


class Table(NamedTuple):
    """Elements by column (see the module docstring)."""

    is_arc: BoolArray
    start: FloatArray
    end: FloatArray
    center: FloatArray
    radius: FloatArray
    angle: FloatArray
    sweep: FloatArray

    def __len__(self) -> int:
        return int(self.is_arc.shape[0])

    def take(self, index: np.ndarray) -> Table:
        """The rows ``index`` (an integer array), in that order."""
        return Table(*(column[index] for column in self))


def table_of(elements: Sequence[Element]) -> Table:
    """The elements as a :class:`Table`."""
    n = len(elements)
    rows = np.zeros((n, 9))
    is_arc = np.zeros(n, dtype=bool)
    for i, e in enumerate(elements):
        if isinstance(e, CircularArc):
            is_arc[i] = True
            rows[i] = (*e.start, *e.end, *e.center, e.radius, e.start_angle_rad, e.sweep_rad)
        else:
            rows[i, :4] = (*e.start, *e.end)
    return Table(
        is_arc, rows[:, 0:2], rows[:, 2:4], rows[:, 4:6], rows[:, 6], rows[:, 7], rows[:, 8]
    )


def boxes(table: Table) -> FloatArray:
    """Each element's exact bounding box ``(n, 4)``: x_min, y_min, x_max, y_max (an arc's
    ends and the axis points of its circle that its sweep passes)."""
    lo = np.minimum(table.start, table.end)
    hi = np.maximum(table.start, table.end)
    arcs = np.flatnonzero(table.is_arc)
    if len(arcs):
        c, r = table.center[arcs], table.radius[arcs]
        for k, (dx, dy) in enumerate(((1.0, 0.0), (0.0, 1.0), (-1.0, 0.0), (0.0, -1.0))):
            inside = fraction(table.take(arcs), np.full(len(arcs), k * 0.5 * math.pi), 0.0)
            hit = (inside >= 0.0) & (inside <= 1.0)
            axis = c + r[:, None] * np.array([dx, dy])
            lo[arcs] = np.where(hit[:, None], np.minimum(lo[arcs], axis), lo[arcs])
            hi[arcs] = np.where(hit[:, None], np.maximum(hi[arcs], axis), hi[arcs])
    return np.hstack([lo, hi])


def fraction(arcs: Table, polar_rad: FloatArray, slack_rad: FloatArray | float) -> FloatArray:
    """The parameter ``t`` on each arc of the polar angle ``polar_rad`` about its centre:
    the turn from the arc's start in its own sense over its sweep. An angle within
    ``slack_rad`` before the start reads as slightly negative rather than nearly a full turn,
    so that callers can accept ``t ∈ [-slack, 1 + slack]``."""
    sense = np.where(arcs.sweep < 0.0, -1.0, 1.0)
    turn = np.mod(sense * (polar_rad - arcs.angle), TAU)
    turn = np.where(turn > TAU - np.maximum(slack_rad, 0.0) - 1e-15, turn - TAU, turn)
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.asarray(turn / np.abs(arcs.sweep), dtype=np.float64)


def parameters(table: Table, points: FloatArray) -> FloatArray:
    """The parameter of each point on its row's element (lines: projection; arcs: turn)."""
    t = np.zeros(len(table))
    lines = ~table.is_arc
    if lines.any():
        u = table.end[lines] - table.start[lines]
        uu = np.einsum("ij,ij->i", u, u)
        with np.errstate(divide="ignore", invalid="ignore"):
            t[lines] = np.einsum("ij,ij->i", points[lines] - table.start[lines], u) / uu
    if table.is_arc.any():
        a = table.is_arc
        rel = points[a] - table.center[a]
        t[a] = fraction(table.take(np.flatnonzero(a)), np.arctan2(rel[:, 1], rel[:, 0]), 1e-9)
    return np.nan_to_num(t)


def element_lengths(table: Table) -> FloatArray:
    """Each element's length."""
    return np.asarray(
        np.where(
            table.is_arc,
            table.radius * np.abs(table.sweep),
            np.hypot(*(table.end - table.start).T),
        )
    )


def point_at(element: Element, t: float) -> Point:
    """The point of ``element`` at parameter ``t`` (its stored ends at 0 and 1)."""
    if t == 0.0:
        return Point(*element.start)
    if t == 1.0:
        return Point(*element.end)
    if isinstance(element, Line):
        (x0, y0), (x1, y1) = element.start, element.end
        return Point(x0 + t * (x1 - x0), y0 + t * (y1 - y0))
    a = element.start_angle_rad + t * element.sweep_rad
    cx, cy = element.center
    return Point(cx + element.radius * math.cos(a), cy + element.radius * math.sin(a))


def length(element: Element) -> float:
    """The element's length."""
    if isinstance(element, Line):
        return math.dist(element.start, element.end)
    return element.radius * abs(element.sweep_rad)


def coordinate_scale(table: Table) -> float:
    """The largest magnitude among the elements' end points: what rounding is relative to
    (not an arc's centre, which for a nearly flat arc lies far away)."""
    if not len(table):
        return 0.0
    return float(max(np.abs(table.start).max(), np.abs(table.end).max()))
