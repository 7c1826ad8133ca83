"""Contours for the offset tests, built from exact lines and arcs (with their end points
computed from centre, radius and angles, chained bit for bit)."""

from __future__ import annotations

import math
from collections.abc import Sequence

from arcspline.geometry.curves.segments import CircularArc, Line
from arcspline.geometry.offset import Element
from arcspline.geometry.spline import Point


def arc(centre: Sequence[float], radius: float, start_rad: float, sweep_rad: float) -> CircularArc:
    cx, cy = centre
    a1 = start_rad + sweep_rad
    return CircularArc(
        Point(cx + radius * math.cos(start_rad), cy + radius * math.sin(start_rad)),
        Point(cx + radius * math.cos(a1), cy + radius * math.sin(a1)),
        Point(cx, cy),
        radius,
        start_rad,
        sweep_rad,
    )


def chained(elements: Sequence[Element], closed: bool = True) -> list[Element]:
    """The elements with each start set to the end before it (and the first to the last's
    end when ``closed``): exact chaining, moving ends by rounding only."""
    out: list[Element] = []
    for e in elements:
        if out:
            e = e._replace(start=out[-1].end)
        out.append(e)
    if closed:
        out[0] = out[0]._replace(start=out[-1].end)
    return out


def polygon(points: Sequence[Sequence[float]]) -> list[Element]:
    pts = [Point(float(x), float(y)) for x, y in points]
    return [Line(pts[i], pts[(i + 1) % len(pts)]) for i in range(len(pts))]


def circle(centre: Sequence[float], radius: float, anticlockwise: bool = True) -> list[Element]:
    sense = 1.0 if anticlockwise else -1.0
    return chained([arc(centre, radius, 0.0, sense * math.pi),
                    arc(centre, radius, sense * math.pi, sense * math.pi)])  # fmt: skip


def rounded_rectangle(width: float, height: float, radius: float) -> list[Element]:
    """Anticlockwise, lower left corner at the origin, corners rounded with ``radius``."""
    w, h, r = width, height, radius
    half = 0.5 * math.pi
    return chained([
        Line(Point(r, 0.0), Point(w - r, 0.0)),
        arc((w - r, r), r, -half, half),
        Line(Point(w, r), Point(w, h - r)),
        arc((w - r, h - r), r, 0.0, half),
        Line(Point(w - r, h), Point(r, h)),
        arc((r, h - r), r, half, half),
        Line(Point(0.0, h - r), Point(0.0, r)),
        arc((r, r), r, math.pi, half),
    ])  # fmt: skip


def reversed_chain(elements: Sequence[Element]) -> list[Element]:
    """The chain run backwards."""
    out: list[Element] = []
    for e in reversed(elements):
        if isinstance(e, Line):
            out.append(Line(e.end, e.start))
        else:
            out.append(CircularArc(e.end, e.start, e.center, e.radius,
                                   e.start_angle_rad + e.sweep_rad, -e.sweep_rad))  # fmt: skip
    return out


def star(points: int, outer: float, inner: float) -> list[Element]:
    """An anticlockwise star polygon: sharp convex tips and sharp concave corners."""
    corners = []
    for k in range(2 * points):
        r = outer if k % 2 == 0 else inner
        a = math.pi * k / points
        corners.append((r * math.cos(a), r * math.sin(a)))
    return polygon(corners)


def slotted_square(size: float, slot_width: float, slot_depth: float) -> list[Element]:
    """An anticlockwise square with a slot cut into its top side, centred."""
    s, w, dep = size, slot_width, slot_depth
    left, right = 0.5 * (s - w), 0.5 * (s + w)
    return polygon([(0, 0), (s, 0), (s, s), (right, s), (right, s - dep), (left, s - dep),
                    (left, s), (0, s)])  # fmt: skip


def dumbbell(radius: float, gap: float, neck: float) -> list[Element]:
    """Two discs of ``radius`` whose centres are ``gap`` apart on the x axis, joined by a neck
    of width ``neck`` (two lines), anticlockwise."""
    a = math.asin(0.5 * neck / radius)
    right = arc((gap, 0.0), radius, math.pi + a, 2 * math.pi - 2 * a)
    left = arc((0.0, 0.0), radius, a, 2 * math.pi - 2 * a)
    return chained([right, Line(right.end, left.start), left, Line(left.end, right.start)])
