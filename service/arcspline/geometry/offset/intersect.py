"""Exact intersections of lines and arcs, pair by pair, vectorised (docs/offsets.md §4).

``hits(a, b, tol)`` intersects row ``k`` of ``a`` with row ``k`` of ``b``: line-line by
Cramer's rule, line-circle from the foot of the centre on the line, circle-circle from the
radical line. A point counts on an element within ``tol`` (a length) of its ends; a line
passing within ``tol`` of a circle touches it once (at the foot), as do two circles whose
two points are closer than the rounding of their computation. Parallel lines
and concentric circles of one radius (within ``tol``) that overlap meet at the ends of the
overlap.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from ..path_spline import IntArray
from ..spline import BoolArray, FloatArray
from .table import Table, fraction, parameters

#: Lines whose direction cross product is below this fraction of their lengths' product are
#: parallel (about 1e-13 rad apart).
_PARALLEL = 1e-13
#: Circles whose crossing angle ``ψ`` (seen from the smaller one) has ``sin² ψ`` within this
#: many ulps (times ``R/r``) of 0 touch once: the rounding of ``cos ψ``.
_TANGENT_EPS = 16 * 2.0**-52


class Hits(NamedTuple):
    """Intersection points: the pair (row of ``a`` and ``b``), the point, its parameter on
    ``a``'s and on ``b``'s element (clipped to ``[0, 1]``)."""

    pair: IntArray
    point: FloatArray
    ta: FloatArray
    tb: FloatArray


def _cross(u: FloatArray, v: FloatArray) -> FloatArray:
    return np.asarray(u[:, 0] * v[:, 1] - u[:, 1] * v[:, 0])


def _dot(u: FloatArray, v: FloatArray) -> FloatArray:
    return np.asarray(np.einsum("ij,ij->i", u, v))


def hits(a: Table, b: Table, tol: float) -> Hits:
    """Every intersection of ``a[k]`` with ``b[k]`` for each ``k`` (see the module)."""
    candidates: list[tuple[IntArray, FloatArray]] = []
    for mask_a, mask_b, finder, swap in (
        (~a.is_arc, ~b.is_arc, _line_line, False),
        (~a.is_arc, b.is_arc, _line_circle, False),
        (a.is_arc, ~b.is_arc, _line_circle, True),
        (a.is_arc, b.is_arc, _circle_circle, False),
    ):
        rows = np.flatnonzero(mask_a & mask_b)
        if not len(rows):
            continue
        first, second = a.take(rows), b.take(rows)
        if swap:
            first, second = second, first
        with np.errstate(all="ignore"):  # degenerate (point-like) elements: dropped below
            local, points = finder(first, second, tol)
        finite = np.isfinite(points).all(axis=1)
        candidates.append((rows[local[finite]], points[finite]))
    if not candidates:
        return Hits(np.zeros(0, np.int64), np.zeros((0, 2)), np.zeros(0), np.zeros(0))
    pair = np.concatenate([c[0] for c in candidates])
    point = np.concatenate([c[1] for c in candidates])
    ta, ok_a = _on(a.take(pair), point, tol)
    tb, ok_b = _on(b.take(pair), point, tol)
    ok = ok_a & ok_b
    return Hits(pair[ok], point[ok], np.clip(ta[ok], 0.0, 1.0), np.clip(tb[ok], 0.0, 1.0))


def _on(table: Table, points: FloatArray, tol: float) -> tuple[FloatArray, BoolArray]:
    """Each point's parameter on its element and whether it lies within ``tol`` of it
    (within its ends' reach; its distance across is the finder's business)."""
    t = parameters(table, points)
    size = np.where(
        table.is_arc,
        table.radius * np.abs(table.sweep),
        np.hypot(*(table.end - table.start).T),
    )
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        slack = np.where(size > 0.0, tol / size, np.inf)
    if table.is_arc.any():
        arcs = np.flatnonzero(table.is_arc)
        rel = points[arcs] - table.center[arcs]
        t[arcs] = fraction(
            table.take(arcs), np.arctan2(rel[:, 1], rel[:, 0]), tol / table.radius[arcs]
        )
    return t, (t >= -slack) & (t <= 1.0 + slack)


def _line_line(a: Table, b: Table, tol: float) -> tuple[IntArray, FloatArray]:
    u, v = a.end - a.start, b.end - b.start
    w = b.start - a.start
    den = _cross(u, v)
    lu, lv = np.hypot(*u.T), np.hypot(*v.T)
    parallel = np.abs(den) <= _PARALLEL * lu * lv
    rows = np.flatnonzero(~parallel)
    t = _cross(w[rows], v[rows]) / den[rows]
    found = [(rows, a.start[rows] + t[:, None] * u[rows])]
    # Parallel and on one line (within tol): the ends of each that lie on the other.
    with np.errstate(divide="ignore", invalid="ignore"):
        apart = np.abs(_cross(w, u)) / lu
    near = np.flatnonzero(parallel & (lu > 0.0) & (lv > 0.0) & (apart <= tol))
    for ends in (b.start, b.end, a.start, a.end):
        found.append((near, ends[near]))
    return np.concatenate([f[0] for f in found]), np.concatenate([f[1] for f in found])


def _line_circle(line: Table, arc: Table, tol: float) -> tuple[IntArray, FloatArray]:
    u = line.end - line.start
    uu = _dot(u, u)
    rows = np.flatnonzero(uu > 0.0)
    u, uu, p, c, r = u[rows], uu[rows], line.start[rows], arc.center[rows], arc.radius[rows]
    foot = p + (_dot(c - p, u) / uu)[:, None] * u
    h = np.hypot(*(foot - c).T)
    touch = (h >= r - tol) & (h <= r + tol)
    cross = h < r - tol
    half = np.sqrt(np.maximum((r - h) * (r + h), 0.0))[cross] / np.sqrt(uu[cross])
    step = half[:, None] * u[cross]
    found = [
        (rows[touch], foot[touch]),
        (rows[cross], foot[cross] - step),
        (rows[cross], foot[cross] + step),
    ]
    return np.concatenate([f[0] for f in found]), np.concatenate([f[1] for f in found])


def _circle_circle(a: Table, b: Table, tol: float) -> tuple[IntArray, FloatArray]:
    """Circle-circle, seen from the smaller circle (radius ``r``, the other ``R``, centres
    ``w`` apart): its points ``u`` (unit) with ``u·w = (r² + (|w| − R)(|w| + R)) / 2r`` lie at
    ``angle(w) ± ψ``, ``cos ψ = u·w / |w|``. Unlike the radical line of the two circles, this
    keeps a nearly flat arc (a huge circle) as well conditioned as the crossing itself:
    ``cos ψ`` is known to about ``ε·R/r``."""
    small = a.radius <= b.radius
    c_small = np.where(small[:, None], a.center, b.center)
    c_big = np.where(small[:, None], b.center, a.center)
    r = np.minimum(a.radius, b.radius)
    big = np.maximum(a.radius, b.radius)
    w = c_big - c_small
    dist = np.hypot(*w.T)
    same = (dist <= tol) & (big - r <= tol)
    with np.errstate(divide="ignore", invalid="ignore"):
        cos = (r * r + (dist - big) * (dist + big)) / (2.0 * r * dist)
        # Rounding of cos ψ (relative ε·R/r) and the tolerance across, as a bound on sin² ψ.
        slack = _TANGENT_EPS * np.maximum(1.0, big / r) + (tol / r) ** 2
    sin2 = (1.0 - cos) * (1.0 + cos)
    valid = (dist > tol) & (r > 0.0) & np.isfinite(cos)
    touch = valid & (np.abs(sin2) <= slack) & (np.abs(cos) <= 1.0 + slack)
    two = valid & (sin2 > slack)
    unit = np.where(valid[:, None], w / np.where(dist > 0.0, dist, 1.0)[:, None], 0.0)
    normal = np.column_stack([-unit[:, 1], unit[:, 0]])
    along = (r * np.clip(cos, -1.0, 1.0))[:, None] * unit
    across = (r * np.sqrt(np.maximum(sin2, 0.0)))[:, None] * normal
    base = c_small + along
    found = [
        (np.flatnonzero(touch), base[touch]),
        (np.flatnonzero(two), (base + across)[two]),
        (np.flatnonzero(two), (base - across)[two]),
    ]
    near = np.flatnonzero(same)
    for ends in (b.start, b.end, a.start, a.end):
        found.append((near, ends[near]))
    return np.concatenate([f[0] for f in found]), np.concatenate([f[1] for f in found])
