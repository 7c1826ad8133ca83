"""Which closed contour lies inside which (docs/machining.md §3).

The winding number of a point about a closed chain of lines and arcs is the sum of the
angles its elements subtend, over 2π. A line from ``a`` to ``b`` subtends
``atan2((a−p)×(b−p), (a−p)·(b−p))``. An arc subtends the angle of its chord, plus
``2π·sign(sweep)`` where the point lies in the circular segment between the chord and the
arc: the arc and its chord travelled back bound that segment once, in the sense of the
sweep. The segment is the part of the disc on the side of the chord the arc bulges to: the
right of ``a → b`` for an anticlockwise arc, the left for a clockwise one.

A contour's *depth* is the number of other closed contours around it (a point of it, the
midpoint of its longest element, has a non-zero winding number about them); its *parent* is
the deepest of those. Open contours have no inside: they enclose nothing, but may lie inside
closed ones (and are then cut before them).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import NamedTuple

import numpy as np

from arcspline.geometry import Line, Point

from .chains import Element, length, point_at


def subtended_rad(point: Point, element: Element) -> float:
    """The signed angle ``element`` subtends at ``point`` (not on it)."""
    px, py = point
    ax, ay = element.start[0] - px, element.start[1] - py
    bx, by = element.end[0] - px, element.end[1] - py
    chord = math.atan2(ax * by - ay * bx, ax * bx + ay * by)
    if isinstance(element, Line):
        return chord
    cx, cy = element.center
    inside_disc = math.hypot(px - cx, py - cy) < element.radius
    (sx, sy), (ex, ey) = element.start, element.end
    side = (ex - sx) * (py - sy) - (ey - sy) * (px - sx)  # > 0: left of the chord
    bulge = side * element.sweep_rad < 0.0
    if inside_disc and bulge:
        return chord + math.copysign(2.0 * math.pi, element.sweep_rad)
    return chord


def winding_number(point: Point, chain: Sequence[Element]) -> int:
    """How many times the closed ``chain`` winds about ``point`` (anticlockwise positive)."""
    total = math.fsum(subtended_rad(point, e) for e in chain)
    return round(total / (2.0 * math.pi))


def probe(chain: Sequence[Element]) -> Point:
    """A point of the chain away from its joints: the midpoint of its longest element."""
    longest = max(chain, key=length)
    return point_at(longest, 0.5)


def _box(chain: Sequence[Element]) -> tuple[float, float, float, float]:
    """A box holding the chain (an arc's whole circle: enough to prune)."""
    xs, ys = [], []
    for e in chain:
        if isinstance(e, Line):
            xs += [e.start[0], e.end[0]]
            ys += [e.start[1], e.end[1]]
        else:
            xs += [e.center[0] - e.radius, e.center[0] + e.radius]
            ys += [e.center[1] - e.radius, e.center[1] + e.radius]
    return min(xs), min(ys), max(xs), max(ys)


class Nesting(NamedTuple):
    """Per contour: how many closed contours enclose it, and the innermost of them."""

    depth: tuple[int, ...]
    parent: tuple[int | None, ...]


def nesting(contours: Sequence[Sequence[Element]], closed: Sequence[bool]) -> Nesting:
    """The depth and parent of every contour (open contours enclose nothing)."""
    probes = [probe(chain) for chain in contours]
    xy = np.array(probes, dtype=np.float64).reshape(-1, 2)
    inside: list[list[int]] = [[] for _ in contours]
    for j, outer in enumerate(contours):
        if not closed[j]:
            continue
        x0, y0, x1, y1 = _box(outer)
        # Outside a contour's box its winding number is 0.
        near = (xy[:, 0] >= x0) & (xy[:, 0] <= x1) & (xy[:, 1] >= y0) & (xy[:, 1] <= y1)
        for i in np.flatnonzero(near).tolist():
            if i != j and winding_number(probes[i], outer):
                inside[i].append(j)
    depth = tuple(len(around) for around in inside)
    parent = tuple(max(around, key=lambda j: depth[j]) if around else None for around in inside)
    return Nesting(depth, parent)
