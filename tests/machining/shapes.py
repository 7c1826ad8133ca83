"""Hand-made drawings for the machining tests, as exact lines and arcs."""

from __future__ import annotations

import math
from collections.abc import Sequence

from arcspline.geometry import CircularArc, Line, Path, PathSpline, Point, Subpath, approximate_path

Element = Line | CircularArc


def polygon(points: Sequence[tuple[float, float]]) -> tuple[Line, ...]:
    """A closed polygon, its corners shared bit for bit."""
    pts = [Point(float(x), float(y)) for x, y in points]
    return tuple(Line(pts[k], pts[(k + 1) % len(pts)]) for k in range(len(pts)))


def rectangle(x0: float, y0: float, x1: float, y1: float) -> tuple[Line, ...]:
    """Anticlockwise."""
    return polygon([(x0, y0), (x1, y0), (x1, y1), (x0, y1)])


def circle(
    cx: float, cy: float, r: float, ccw: bool = True, parts: int = 4
) -> tuple[CircularArc, ...]:
    """A full circle as ``parts`` arcs from angle 0."""
    sweep = (1.0 if ccw else -1.0) * 2.0 * math.pi / parts
    angles = [k * sweep for k in range(parts)]
    pts = [Point(cx + r * math.cos(a), cy + r * math.sin(a)) for a in angles]
    return tuple(
        CircularArc(pts[k], pts[(k + 1) % parts], Point(cx, cy), r, angles[k], sweep)
        for k in range(parts)
    )


def star(cx: float, cy: float, outer: float, inner: float, points: int = 5) -> tuple[Line, ...]:
    """A star with sharp tips and sharp concave notches, anticlockwise."""
    corners = []
    for k in range(2 * points):
        r = outer if k % 2 == 0 else inner
        a = math.pi / 2 + k * math.pi / points
        corners.append((cx + r * math.cos(a), cy + r * math.sin(a)))
    return polygon(corners)


def stadium(x0: float, x1: float, y: float, half_width: float) -> tuple[Element, ...]:
    """A slot: two straights and two half circles, anticlockwise."""
    h = half_width
    a, b = Point(x0, y - h), Point(x1, y - h)
    c, d = Point(x1, y + h), Point(x0, y + h)
    return (
        Line(a, b),
        CircularArc(b, c, Point(x1, y), h, -math.pi / 2, math.pi),
        Line(c, d),
        CircularArc(d, a, Point(x0, y), h, math.pi / 2, math.pi),
    )


def fitted(
    *contours: Sequence[Element], closed: Sequence[bool] | None = None, tolerance: float = 0.001
) -> PathSpline:
    """The contours as the fitted drawing ``machine`` takes."""
    flags = [True] * len(contours) if closed is None else list(closed)
    path = Path(tuple(Subpath(tuple(c), f) for c, f in zip(contours, flags, strict=True)))
    return approximate_path(path, tolerance)


def square_with_two_holes() -> PathSpline:
    """A 60 × 40 plate with a round hole (r 6) and a rectangular one (the outline drawn
    first, the holes after it)."""
    return fitted(rectangle(0, 0, 60, 40), circle(15, 20, 6), rectangle(35, 12, 50, 28))


def dumbbell(x0: float, x1: float, y: float, radius: float, neck: float) -> tuple[Element, ...]:
    """Two round ends of ``radius`` about ``(x0, y)`` and ``(x1, y)`` joined by a neck of
    half-width ``neck``, anticlockwise; the lines end where the arcs put their ends."""
    half = math.asin(neck / radius)
    sweep = 2.0 * math.pi - 2.0 * half
    left = CircularArc(
        Point(x0 + radius * math.cos(half), y + radius * math.sin(half)),
        Point(x0 + radius * math.cos(half + sweep), y + radius * math.sin(half + sweep)),
        Point(x0, y), radius, half, sweep,
    )  # fmt: skip
    start = math.pi + half
    right = CircularArc(
        Point(x1 + radius * math.cos(start), y + radius * math.sin(start)),
        Point(x1 + radius * math.cos(start + sweep), y + radius * math.sin(start + sweep)),
        Point(x1, y), radius, start, sweep,
    )  # fmt: skip
    return (
        Line(left.end, right.start),
        right,
        Line(right.end, left.start),
        left,
    )
