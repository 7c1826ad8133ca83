"""The machining results as the independent offset oracle's segments (read by value)."""

from __future__ import annotations

from typing import Any

import numpy as np

from arcspline.geometry import ArcSpline, PathSpline
from tests.support import offset_oracle as oracle


def segments(spline: ArcSpline) -> list[oracle.OSeg]:
    """A fitted spline's rows as oracle segments, via the JSON form the API writes."""
    rows: list[dict[str, Any]] = []
    for seg in spline.segments:
        row: dict[str, Any] = {"type": seg.type, "start": list(seg.start), "end": list(seg.end)}
        if seg.type == "arc":
            row |= {"center": list(seg.center), "radius": seg.radius, "sweep_rad": seg.sweep_rad}
        rows.append(row)
    return oracle.from_json(rows)


def contours(spline: PathSpline) -> list[list[oracle.OSeg]]:
    return [segments(sub.spline) for sub in spline.subpaths]


def _cross(u: np.ndarray, v: np.ndarray) -> np.ndarray:
    """The z component of the cross product of rows (or a row against rows)."""
    return np.asarray(u[..., 0] * v[..., 1] - u[..., 1] * v[..., 0])


def crosses_itself(contour: list[oracle.OSeg], per_arc: int = 32) -> bool:
    """Whether a closed contour's fine polygon (each arc sampled by its own parameter) has
    two non-neighbouring edges that cross properly (orientation tests), comparing only edges
    that share a cell of a grid of a few edge lengths."""
    pts = np.array(
        [
            s.point(float(t))
            for s in contour
            for t in np.linspace(0.0, 1.0, per_arc if s.kind == "arc" else 1, endpoint=False)
        ]
    )
    a, b = pts, np.roll(pts, -1, axis=0)
    n = len(pts)
    cell = 4.0 * float(np.median(np.hypot(*(b - a).T))) or 1.0
    lo = np.floor(np.minimum(a, b) / cell).astype(int)
    hi = np.floor(np.maximum(a, b) / cell).astype(int)
    cells: dict[tuple[int, int], list[int]] = {}
    for k in range(n):
        for cx in range(lo[k, 0], hi[k, 0] + 1):
            for cy in range(lo[k, 1], hi[k, 1] + 1):
                cells.setdefault((cx, cy), []).append(k)
    for members in cells.values():
        for k in members:
            others = np.array([j for j in members if (j - k) % n not in (0, 1, n - 1)], dtype=int)
            if not len(others):
                continue
            p, q = a[k], b[k]
            c, d = a[others], b[others]
            d1, d2 = _cross(q - p, c - p), _cross(q - p, d - p)
            d3, d4 = _cross(d - c, p - c), _cross(d - c, q - c)
            if np.any((d1 * d2 < 0) & (d3 * d4 < 0)):
                return True
    return False
