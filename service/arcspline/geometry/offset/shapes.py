"""Small exact operations on single lines and arcs: moving an end along the element, taking
a sub-range, and how far an arc's stored ends may move (docs/offsets.md §2)."""

from __future__ import annotations

import math

from ..curves.segments import CircularArc, Line
from ..spline import Point
from .table import TAU
from .types import Element

#: An arc's stored end may be moved onto a neighbour's end by at most this fraction of the
#: arc's own coordinate scale: a tenth of what the core's input check allows
#: (segment_table.ARC_RTOL).
ARC_MOVE_RTOL = 1e-10


def arc_scale(arc: CircularArc) -> float:
    """The arc's coordinate scale as the core's input check measures it."""
    (cx, cy), r = arc.center, arc.radius
    return max(abs(arc.start[0]), abs(arc.start[1]), abs(arc.end[0]), abs(arc.end[1]),
               abs(cx) + r, abs(cy) + r)  # fmt: skip


def movable(element: Element, by: float) -> bool:
    """Whether an end of ``element`` may be moved by ``by`` without leaving it: any line;
    an arc by a tiny fraction of its scale."""
    return isinstance(element, Line) or by <= ARC_MOVE_RTOL * arc_scale(element)


def polar(center: Point | tuple[float, float], point: Point | tuple[float, float]) -> float:
    return math.atan2(point[1] - center[1], point[0] - center[0])


def _near(angle: float, target: float) -> float:
    """``angle`` plus the multiple of 2π that brings it nearest ``target``."""
    return angle + TAU * round((target - angle) / TAU)


def with_start(element: Element, point: Point, t: float | None = None) -> Element:
    """``element`` from ``point`` (on it, at parameter ``t`` if known) to its end. An arc keeps
    its end angle; its start angle is the point's polar angle (nearest the old one moved by
    ``t`` of the sweep)."""
    if isinstance(element, Line):
        return Line(point, element.end)
    a0, s = element.start_angle_rad, element.sweep_rad
    guess = a0 + (0.0 if t is None else t) * s
    new = _near(polar(element.center, point), guess)
    return element._replace(start=point, start_angle_rad=new, sweep_rad=a0 + s - new)


def with_end(element: Element, point: Point, t: float | None = None) -> Element:
    """``element`` from its start to ``point`` (on it, at parameter ``t`` if known)."""
    if isinstance(element, Line):
        return Line(element.start, point)
    a0, s = element.start_angle_rad, element.sweep_rad
    guess = a0 + (1.0 if t is None else t) * s
    end = _near(polar(element.center, point), guess)
    return element._replace(end=point, sweep_rad=end - a0)


def piece(element: Element, t0: float, t1: float, start: Point, end: Point) -> Element:
    """The part of ``element`` from parameter ``t0`` (at ``start``) to ``t1`` (at ``end``);
    the element's own stored ends where ``t0 == 0`` or ``t1 == 1``."""
    if isinstance(element, Line):
        return Line(start, end)
    out: Element = element
    if t1 < 1.0:
        out = with_end(out, end, t1)
    if t0 > 0.0:
        out = with_start(out, start, t0 / t1 if t1 > 0.0 else 0.0)
    return out._replace(start=start, end=end)
