"""From kept canonical biarcs to world-coordinate segments and statistics.

A canonical point ``p`` maps to ``B0 + a·R(φ)·(p_x, σ·p_y)``, with ``φ`` the direction of the
start tangent and ``σ = ±1`` the turning direction (the mirror for clockwise spirals);
angles map to ``φ + σ·angle``, sweeps to ``σ·sweep``, lengths and deviations scale by ``a``.
"""

from __future__ import annotations

import itertools
from collections.abc import Sequence
from dataclasses import dataclass, fields

import numpy as np
import numpy.typing as npt

from . import canonical
from .arclength import canonical_lengths
from .spiral import Spiral
from .subdivide import IntArray, Kept
from .types import ArcSpline, FloatArray, SegmentColumns, SplineStats

#: Below this sweep an arc is numerically flat: its centre and radius (≈ length / sweep) carry
#: no information and a controller may read it as a full circle. It becomes its chord; the
#: tangent then turns by at most half of this at each end, far below anything measurable.
FLAT_SWEEP_RAD = 1e-10

#: Index of every row (a view, no gather), for frames already taken per row.
ALL = slice(None)


@dataclass(frozen=True, slots=True)
class Frames:
    """The similarity of each spiral of a batch (origin, scale, start direction, mirror), its
    stored end point ``B3``, and what the core checks and scales by: turn angle, chord and
    coordinate scale. One row per spiral."""

    origin: FloatArray
    scale: FloatArray
    cos_phi: FloatArray
    sin_phi: FloatArray
    phi_rad: FloatArray
    mirror: FloatArray
    end_point: FloatArray
    turn_angle_rad: FloatArray
    chord: FloatArray
    coordinate_scale: FloatArray

    @classmethod
    def of(cls, spirals: Sequence[Spiral]) -> Frames:
        # One pass over the spirals, one array: (B0, T0, a, σ, θ, chord, scale, B3) per row.
        table = np.array(
            [
                (
                    *s.start,
                    *s.start_tangent,
                    s.a,
                    s.turn_direction,
                    s.turn_angle_rad,
                    s.chord,
                    s.coordinate_scale,
                    *s.end_point,
                )
                for s in spirals
            ],
            dtype=np.float64,
        ).reshape(-1, 11)
        return cls(
            origin=table[:, 0:2],
            scale=table[:, 4],
            cos_phi=table[:, 2],
            sin_phi=table[:, 3],
            phi_rad=np.arctan2(table[:, 3], table[:, 2]),
            mirror=table[:, 5],
            end_point=table[:, 9:11],
            turn_angle_rad=table[:, 6],
            chord=table[:, 7],
            coordinate_scale=table[:, 8],
        )

    def take(self, i: IntArray) -> Frames:
        """The frames of spirals ``i``, one row each: gathered once, then indexed by ``ALL``."""
        return Frames(*(getattr(self, f.name)[i] for f in fields(self)))

    def point(self, i: IntArray | slice, x: FloatArray, y: FloatArray) -> FloatArray:
        """World points of canonical points ``(x, y)`` of spirals ``i``."""
        return self.origin[i] + self.vector(i, x, y)

    def vector(self, i: IntArray | slice, x: FloatArray, y: FloatArray) -> FloatArray:
        """World vectors of canonical vectors ``(x, y)`` of spirals ``i``."""
        s, c, sn = self.scale[i], self.cos_phi[i], self.sin_phi[i]
        y = self.mirror[i] * y
        # Two column writes: several times cheaper than np.stack on small arrays.
        out = np.empty((*np.shape(x), 2))
        out[..., 0] = s * (c * x - sn * y)
        out[..., 1] = s * (sn * x + c * y)
        return out

    def angle(self, i: IntArray | slice, angle_rad: FloatArray) -> FloatArray:
        """World polar angles of canonical angles, in ``(−π, π]``."""
        world = self.phi_rad[i] + self.mirror[i] * angle_rad
        return np.asarray(np.arctan2(np.sin(world), np.cos(world)))

    def direction_rad(self, i: IntArray | slice, x: FloatArray, y: FloatArray) -> FloatArray:
        """World polar angles, in ``(−π, π]``, of canonical directions ``(x, y)``."""
        c, sn = self.cos_phi[i], self.sin_phi[i]
        y = self.mirror[i] * y
        return np.asarray(np.arctan2(sn * x + c * y, c * x - sn * y))


def segment_columns(kept: Kept, k: FloatArray, m: FloatArray, frames: Frames) -> SegmentColumns:
    """Two rows per kept biarc (arc 0, then arc 1), in the order of ``kept``."""
    b, d, i = kept.biarcs, kept.deviation, kept.spiral
    n = i.shape[0]
    # A batch gathers one frame per row, once for all the mappings below; one spiral's frame
    # (arrays of one element) broadcasts over its rows: elementwise the same arithmetic.
    one = frames.scale.shape[0] == 1
    kk, mm = (k, m) if one else (k[i], m[i])
    rows = frames if one else frames.take(i)
    scale = rows.scale
    # The five canonical vectors Q(u0), Q(u1), G − A0 and the two radius vectors r·N mapped
    # in one stacked call (elementwise the same arithmetic as five separate mappings).
    q0x, q0y = canonical.point(kk, mm, b.u0)
    q1x, q1y = canonical.point(kk, mm, b.u1)
    r0, r1 = b.radius0, b.radius1
    # r·N with N = (−e_y, e_x), the unit normal at each arc's tangent point.
    world = rows.vector(
        ALL,
        np.array([q0x, q1x, b.join_dx, -(r0 * b.e0y), -(r1 * b.e1y)]),
        np.array([q0y, q1y, b.join_dy, r0 * b.e0x, r1 * b.e1x]),
    )
    a0 = rows.origin + world[0]
    a1 = rows.origin + world[1]
    join = a0 + world[2]
    # Pin the spiral's own end points: u = 0 maps to B0 exactly, u = 1 to the stored B3.
    at_end = b.u1 == 1.0
    a1[at_end] = rows.end_point if one else rows.end_point[at_end]
    centre0 = a0 + world[3]
    centre1 = a1 + world[4]

    def interleave(first: FloatArray, second: FloatArray) -> FloatArray:
        out = np.empty((2 * first.shape[0], *first.shape[1:]))
        out[0::2], out[1::2] = first, second
        return out

    # Every per-arc column pair (arc 0, arc 1) interleaved by one copy: shape (columns, 2n).
    # Each arc starts at −N of its tangent direction from the centre: (e_y, −e_x).
    angles = rows.direction_rad(ALL, np.array([b.e0y, b.ecy]), -np.array([b.e0x, b.ecx]))
    alpha, beta = b.sweeps_rad()
    pairs = (
        np.array(
            [
                [alpha, beta],
                [scale * r0, scale * r1],
                [angles[0], angles[1]],
                [scale * d.arc0, scale * d.arc1],
                [b.u0, d.split],
                [d.split, b.u1],
                [d.u_arc0, d.u_arc1],
            ]
        )
        .transpose(0, 2, 1)
        .reshape(7, 2 * n)
    )
    sweep, radius, start_angle, max_dev = pairs[0], pairs[1], pairs[2], pairs[3]
    mirror = rows.mirror if one else np.repeat(rows.mirror, 2)
    scale_per_row = scale if one else np.repeat(scale, 2)
    start = interleave(a0, join)
    end = interleave(join, a1)
    is_arc = sweep > FLAT_SWEEP_RAD
    length = radius * sweep
    signed_sweep = mirror * sweep
    all_arcs = np.count_nonzero(is_arc) == is_arc.size
    centre = interleave(centre0, centre1)
    if not all_arcs:
        chord = end - start
        length = np.where(is_arc, length, np.hypot(chord[:, 0], chord[:, 1]))
        centre = np.where(is_arc[:, None], centre, 0.5 * (start + end))
        flat = _flat_deviation(kept, k, m, is_arc) * scale_per_row
        max_dev = np.where(is_arc, max_dev, flat)
        radius = np.where(is_arc, radius, np.inf)
        start_angle = np.where(is_arc, start_angle, 0.0)
        signed_sweep = np.where(is_arc, signed_sweep, 0.0)
    return SegmentColumns(
        is_arc=is_arc,
        start=start,
        end=end,
        center=centre,
        radius=radius,
        start_angle_rad=start_angle,
        sweep_rad=signed_sweep,
        length=length,
        u_start=pairs[4],
        u_end=pairs[5],
        max_deviation=max_dev,
        u_at_max_deviation=pairs[6],
    )


def _flat_deviation(
    kept: Kept, k: FloatArray, m: FloatArray, is_arc: npt.NDArray[np.bool_]
) -> FloatArray:
    """Largest distance from each segment's spiral piece to its chord, canonical units.

    The distance to the chord's line, ``(Q(u) − A)×ĉ``, has its one interior extremum where
    ``Q'(u)×ĉ = 0``, i.e. ``u² = ĉ_y / (m·ĉ_x − k·ĉ_y)``.
    """
    b, d, i = kept.biarcs, kept.deviation, kept.spiral
    kk, mm = np.repeat(k[i], 2), np.repeat(m[i], 2)
    ax = np.repeat(b.u0, 2)
    lo = np.ravel(np.column_stack([b.u0, d.split]))
    hi = np.ravel(np.column_stack([d.split, b.u1]))
    gx0, gy0 = canonical.offset(k[i], m[i], b.u0, b.u1)
    cx = np.ravel(np.column_stack([b.join_dx, gx0 - b.join_dx]))
    cy = np.ravel(np.column_stack([b.join_dy, gy0 - b.join_dy]))
    norm = np.hypot(cx, cy)
    cx, cy = cx / norm, cy / norm
    with np.errstate(divide="ignore", invalid="ignore"):
        critical = np.sqrt(cy / (mm * cx - kk * cy))
    candidates = [lo, hi, np.where((critical > lo) & (critical < hi), critical, lo)]
    # Measure from the segment's start: A0 for arc 0, G (= A0 + join) for arc 1.
    sx = np.ravel(np.column_stack([np.zeros_like(b.join_dx), b.join_dx]))
    sy = np.ravel(np.column_stack([np.zeros_like(b.join_dy), b.join_dy]))
    worst = np.zeros_like(lo)
    for u in candidates:
        px, py = canonical.offset(kk, mm, ax, u)
        worst = np.maximum(worst, np.abs((px - sx) * cy - (py - sy) * cx))
    # The arc's own deviation covers the end point gap ‖Q(t) − G‖; the chord differs from the
    # arc by less than its sagitta (< length·FLAT_SWEEP_RAD/8), so this is exact to that level.
    arc_deviation = np.ravel(np.column_stack([d.arc0, d.arc1]))
    return np.where(is_arc, 0.0, np.maximum(worst, arc_deviation))


def splines(
    columns: SegmentColumns,
    spiral_of_row: IntArray,
    spiral_length: FloatArray,
    tolerances: FloatArray,
    strategy: str,
) -> list[ArcSpline]:
    """Cut batch columns into one :class:`ArcSpline` per spiral (row views, no copies);
    ``spiral_length`` is each spiral's arc length (:func:`spiral_lengths`)."""
    n = spiral_length.shape[0]
    if n == 1 and len(columns):
        one = stats_one(columns, float(spiral_length[0]), float(tolerances[0]))
        return [ArcSpline(columns, one, float(tolerances[0]), strategy)]
    counts = np.bincount(spiral_of_row, minlength=n)
    bounds = np.concatenate(([0], np.cumsum(counts))).tolist()
    stats = _stats(columns, counts, np.asarray(bounds), spiral_length, tolerances)
    return [
        ArcSpline(columns, st, tol, strategy, rows)
        for rows, st, tol in zip(
            itertools.pairwise(bounds), stats, tolerances.tolist(), strict=True
        )
    ]


def _stats(
    columns: SegmentColumns,
    counts: IntArray,
    bounds: IntArray,
    spiral_length: FloatArray,
    tolerances: FloatArray,
) -> list[SplineStats]:
    """Per-spline statistics by segmented reductions over the batch columns."""
    nonempty = counts > 0
    # reduceat over the splines that have rows: their starts increase strictly, so each
    # reduction covers exactly its spline's rows. (With an empty spline's start in between,
    # reduceat would give the spline before it its first row alone.)
    at = bounds[:-1][nonempty]

    def reduce(ufunc: np.ufunc, values: FloatArray, empty: float) -> FloatArray:
        out = np.full(counts.shape, empty)
        if at.size:
            out[nonempty] = ufunc.reduceat(values, at)
        return out

    arcs = reduce(np.add, columns.is_arc.astype(np.float64), 0.0).astype(np.intp)
    dev = columns.max_deviation
    max_dev = reduce(np.maximum, dev, 0.0)
    mean_dev = reduce(np.add, dev, 0.0) / np.maximum(counts, 1)
    total = reduce(np.add, columns.length, 0.0)
    arc_r = np.where(columns.is_arc, columns.radius, np.nan)
    min_r = reduce(np.fmin, arc_r, np.nan)
    max_r = reduce(np.fmax, arc_r, np.nan)
    # The first row reaching the spline's maximum names where it occurs.
    is_max = dev == np.repeat(max_dev, counts)
    first_max = np.full(counts.shape, -1)
    rows = np.flatnonzero(is_max)
    owner = np.repeat(np.arange(counts.size), counts)[rows]
    first_max[owner[::-1]] = rows[::-1]
    u_max = columns.u_at_max_deviation
    u_at = np.where(first_max >= 0, u_max[first_max] if u_max.size else 0.0, 0.0)
    # Plain Python numbers, converted once per column rather than once per value.
    arc_counts = arcs.tolist()
    min_r_list = [None if n == 0 else r for n, r in zip(arc_counts, min_r.tolist(), strict=True)]
    max_r_list = [None if n == 0 else r for n, r in zip(arc_counts, max_r.tolist(), strict=True)]
    # Positional, in SplineStats' field order: keywords cost a third more per spline.
    return [
        SplineStats(n_arc, n_seg - n_arc, *rest)
        for n_arc, n_seg, *rest in zip(
            arc_counts,
            counts.tolist(),
            max_dev.tolist(),  # max_deviation
            u_at.tolist(),  # u_at_max_deviation
            (max_dev / tolerances).tolist(),  # deviation_ratio
            mean_dev.tolist(),  # mean_segment_deviation
            spiral_length.tolist(),
            total.tolist(),  # spline_length
            min_r_list,
            max_r_list,
            strict=True,
        )
    ]


_FIRST_ROW = np.zeros(1, dtype=np.intp)


def stats_one(columns: SegmentColumns, spiral_length: float, tolerance: float) -> SplineStats:
    """:func:`_stats` for a batch of one non-empty spline, with whole-array reductions: the
    same numbers (sums by the same ``reduceat``; maxima, minima and the first maximum are
    exact) at a fraction of the calls."""
    dev = columns.max_deviation
    segments = dev.size
    arcs = int(np.count_nonzero(columns.is_arc))
    max_dev = float(np.maximum.reduce(dev))
    radius = columns.radius if arcs == segments else columns.radius[columns.is_arc]
    return SplineStats(
        arc_count=arcs,
        line_count=segments - arcs,
        max_deviation=max_dev,
        u_at_max_deviation=float(columns.u_at_max_deviation[int(np.argmax(dev))]),
        deviation_ratio=max_dev / tolerance,
        mean_segment_deviation=float(np.add.reduceat(dev, _FIRST_ROW)[0]) / segments,
        spiral_length=spiral_length,
        spline_length=float(np.add.reduceat(columns.length, _FIRST_ROW)[0]),
        min_radius=float(np.minimum.reduce(radius)) if arcs else None,
        max_radius=float(np.maximum.reduce(radius)) if arcs else None,
    )


#: Spirals per block, so that a block's (rows × nodes) temporaries stay in cache.
_LENGTH_BLOCK = 1024


def spiral_lengths(k: FloatArray, m: FloatArray, scale: FloatArray) -> FloatArray:
    """Arc lengths of spirals ``(k, m)`` of sizes ``scale`` (``arcspline.geometry.arclength``)."""
    lengths = np.empty(k.shape[0])
    for begin in range(0, k.shape[0], _LENGTH_BLOCK):
        block = slice(begin, begin + _LENGTH_BLOCK)
        lengths[block] = canonical_lengths(k[block], m[block])
    return np.asarray(scale * lengths)
