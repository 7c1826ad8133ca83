"""What the document writers need of the splines they write (``dxf.py``, ``svg_document.py``,
``drawing_preview.py``): their extents, and that every number of them is finite."""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from arcspline.geometry import GeometryError
from arcspline.geometry.spline import ArcSpline, FloatArray


def extents(splines: Sequence[ArcSpline]) -> tuple[FloatArray, FloatArray]:
    """The bounding box ``(low, high)`` of the splines: every end point, and each arc's
    extreme points along the axes where the arc passes them (zeros when there are none)."""
    lows, highs = [], []
    for spline in splines:
        c = spline.columns
        ends = np.concatenate([c.start, c.end])
        lows.append(ends.min(axis=0))
        highs.append(ends.max(axis=0))
        arcs = c.is_arc
        a0, sweep = c.start_angle_rad[arcs], c.sweep_rad[arcs]
        lo_rad, hi_rad = np.minimum(a0, a0 + sweep), np.maximum(a0, a0 + sweep)
        for k in range(4):  # the axis directions 0, π/2, π, 3π/2
            phi = k * math.pi / 2
            # The arc passes phi + 2πn for some n when it lies within [lo, hi].
            n = np.ceil((lo_rad - phi) / (2 * math.pi))
            passes = phi + 2 * math.pi * n <= hi_rad
            extreme = c.center[arcs][passes] + c.radius[arcs][passes, None] * np.array(
                [round(math.cos(phi)), round(math.sin(phi))], dtype=np.float64
            )
            if len(extreme):
                lows.append(extreme.min(axis=0))
                highs.append(extreme.max(axis=0))
    if not lows:
        return np.zeros(2), np.zeros(2)
    return np.min(lows, axis=0), np.max(highs, axis=0)


def check_finite(splines: Sequence[ArcSpline], document: str) -> None:
    """Raises a ``precision`` :class:`GeometryError` when a spline's end points, centres,
    radii or sweeps are not finite (no ``document``, DXF or SVG, can hold them)."""
    for spline in splines:
        c = spline.columns
        arcs = c.is_arc
        numbers = (c.start, c.end, c.center[arcs], c.radius[arcs], c.sweep_rad)
        if not all(bool(np.isfinite(a).all()) for a in numbers):
            raise GeometryError(
                "parts",
                f"the spline's coordinates are not finite; no {document} can hold them",
                kind="precision",
            )
