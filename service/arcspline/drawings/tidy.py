"""Drawn elements made fit to cut (docs/drawings.md §6): a Bézier control point that lies
within ``snap`` of its end point is put on it, Béziers that are straight as drawn become
lines, and elements with no length at all are left out with a warning.

Drawing programs write cusps with control points a rounding apart from the end point
(Inkscape's 1e-6 of a user unit): a curve that turns through a cusp within a few nanometres,
which no double-precision fit can follow, where the drawing meant the exact cusp the core
takes. Putting the control point on the end point moves the curve by at most
``max_t 3t(1 − t)² · |Δ| = 4/9 · |Δ|`` (cubic, ``4/9 · (|Δ₁| + |Δ₂|)`` when both inner points
move; ``1/2 · |Δ|`` quadratic, whose control point moves to the nearer end only: the
Bernstein weight of the moved point), reported as the largest move; the fit keeps the rest of the
tolerance. A cubic whose inner control points both sit on its ends (or both on one end), and
a quadratic whose control point sits on an end, trace the straight segment between their
ends exactly: they become that line.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import NamedTuple

from arcspline.geometry.curves.segments import Cubic, Line, Quadratic, Segment, Subpath

from .model import DrawingWarning, Element

#: Largest Bernstein weight of a cubic's inner control point (at t = 1/3 or 2/3), and of a
#: quadratic's control point (at t = 1/2).
CUBIC_WEIGHT = 4.0 / 9.0
QUADRATIC_WEIGHT = 0.5


class Tidied(NamedTuple):
    """The elements to cut, the largest distance any was moved, and the warnings for the
    elements left out (no length)."""

    elements: tuple[Element, ...]
    largest_move: float
    warnings: tuple[DrawingWarning, ...]


def _snapped(point: tuple[float, float], end: tuple[float, float], snap: float) -> bool:
    return point != end and math.dist(point, end) <= snap


def _tidy_segment(segment: Segment, snap: float) -> tuple[Segment, float]:
    """The segment with near-coincident control points put on their ends, and how far that
    moved the curve."""
    match segment:
        case Cubic(start, c1, c2, end):
            moved = 0.0  # |Δ1| + |Δ2|: each weight is at most 4/9, so the sum bounds the move
            if _snapped(c1, start, snap):
                moved += math.dist(c1, start)
                c1 = start
            if _snapped(c2, end, snap):
                moved += math.dist(c2, end)
                c2 = end
            straight = c1 in (start, end) and c2 in (start, end)
            curve = Line(start, end) if straight else Cubic(start, c1, c2, end)
            return curve, CUBIC_WEIGHT * moved
        case Quadratic(start, control, end):
            nearer = min((start, end), key=lambda p: math.dist(control, p))
            move = 0.0
            if _snapped(control, nearer, snap):
                move = QUADRATIC_WEIGHT * math.dist(control, nearer)
                control = nearer
            straight = control in (start, end)
            return (Line(start, end) if straight else Quadratic(start, control, end)), move
    return segment, 0.0


def _has_length(subpath: Subpath) -> bool:
    first = subpath.segments[0].start
    return any(
        any(point != first for point in segment if isinstance(point, tuple))
        for segment in subpath.segments
    )


def tidy(elements: Sequence[Element], snap: float) -> Tidied:
    """Each element with its control points within ``snap`` of their ends put on them and
    its straight Béziers as lines; elements without length left out (module docstring)."""
    kept: list[Element] = []
    empty: list[str] = []
    largest = 0.0
    for element in elements:
        if not element.subpath.segments or not _has_length(element.subpath):
            empty.append(element.source)
            continue
        segments = []
        for segment in element.subpath.segments:
            tidied, move = _tidy_segment(segment, snap)
            segments.append(tidied)
            largest = max(largest, move)
        kept.append(Element(Subpath(tuple(segments), element.subpath.closed), element.source))
    warnings = (
        (DrawingWarning(empty[0], "has no length (all its points coincide)", len(empty)),)
        if empty
        else ()
    )
    return Tidied(tuple(kept), largest, warnings)
