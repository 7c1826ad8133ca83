"""From one spiral's kept biarcs (rows of floats) to its world-coordinate arc spline.

:func:`arcspline.geometry.assemble.segment_columns` maps a whole batch with numpy, about fifty
array operations whatever the batch's size; for the few dozen arcs of one spiral the same
arithmetic in floats costs a fraction of that. It is written operation for operation as
there (``canonical.point``, ``Frames.vector``, the pinned end point, ``r·N``), so the segments
are bit-identical; the angles (``arctan2``) are taken with numpy over all arcs at once, as
there. The spline keeps its segments as plain values (``SegmentValues``, what the JSON
encoder takes) and its statistics are computed in floats with numpy's own order of additions
(:func:`numpy_sum`); its numpy columns are made only if someone asks for them. The common
case only: a spline with a numerically flat arc, a non-finite number or an arc whose
placement needs measuring (``approximate._unplaceable_rows``), or with many arcs, returns
``None``, and the batch path assembles it.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from .assemble import FLAT_SWEEP_RAD
from .spiral import Spiral
from .subdivide_one import Row
from .types import ArcSpline, SegmentValues, SplineStats

_EPS = float(np.finfo(np.float64).eps)

#: Biarcs assembled here at most: each costs about as much as half a numpy operation, and the
#: batch assembly's fifty operations do any number at once.
MAX_BIARCS = 48

#: numpy's pairwise summation: accumulators, and the block beyond which it halves.
_PAIRWISE_LANES = 8
_PAIRWISE_BLOCK = 128


def assemble_one(
    rows: list[Row],
    spiral: Spiral,
    k: float,
    m: float,
    tolerance: float,
    spiral_length: float,
    strategy: str,
    placement_screen_ulps: float,
) -> ArcSpline | None:
    """The arc spline of ``spiral`` from its kept biarcs ``rows`` (``subdivide_one``), or
    ``None`` where the batch path must assemble it (or is faster: beyond ``MAX_BIARCS``)."""
    if len(rows) > MAX_BIARCS:
        return None
    ox, oy = spiral.start
    c, sn = spiral.start_tangent
    s, mirror = spiral.a, float(spiral.turn_direction)
    end_x, end_y = spiral.end_point
    screen = placement_screen_ulps * _EPS
    # Per arc: start, end, centre, radius, u_start, u_end, deviation and its u; and apart,
    # the arctan2 arguments of its start direction and of its half sweep.
    arcs: list[tuple[float, ...]] = []
    atan_y: list[float] = []
    atan_x: list[float] = []
    # Any NaN or infinity among the numbers makes this sum non-finite (an overflow of the sum
    # itself only sends a spline to the batch path, which decides it the same way).
    total = 0.0
    for (
        u0,
        u1,
        e0x,
        e0y,
        ecx,
        ecy,
        e1x,
        e1y,
        cos_half_a,
        sin_half_a,
        cos_half_b,
        sin_half_b,
        _chord_length,
        _join_distance,
        join_dx,
        join_dy,
        radius0,
        radius1,
        t,
        arc0,
        u_arc0,
        arc1,
        u_arc1,
        _value,
        _at,
    ) in rows:
        # canonical.point at u0 and u1, then Frames.vector (y mirrored first) and the origin.
        w = u0 * u0
        x, y = u0 * (3.0 + k * w), mirror * (m * w * u0)
        a0x, a0y = ox + s * (c * x - sn * y), oy + s * (sn * x + c * y)
        if u1 == 1.0:  # the spiral's own end point, as stored
            a1x, a1y = end_x, end_y
        else:
            w = u1 * u1
            x, y = u1 * (3.0 + k * w), mirror * (m * w * u1)
            a1x, a1y = ox + s * (c * x - sn * y), oy + s * (sn * x + c * y)
        y = mirror * join_dy
        gx, gy = a0x + s * (c * join_dx - sn * y), a0y + s * (sn * join_dx + c * y)
        # The centres: r·N from each arc's tangent point, N = (−e_y, e_x).
        x, y = -(radius0 * e0y), mirror * (radius0 * e0x)
        c0x, c0y = a0x + s * (c * x - sn * y), a0y + s * (sn * x + c * y)
        x, y = -(radius1 * e1y), mirror * (radius1 * e1x)
        c1x, c1y = a1x + s * (c * x - sn * y), a1y + s * (sn * x + c * y)
        # Frames.direction_rad of (e_y, −e_x): the start direction from each centre.
        y0, yc = mirror * -e0x, mirror * -ecx
        r0, r1 = s * radius0, s * radius1
        dev0, dev1 = s * arc0, s * arc1
        # approximate._unplaceable_rows: an arc whose rounding could matter is measured there.
        size0 = (abs(c0x) if abs(c0x) >= abs(c0y) else abs(c0y)) + r0
        size1 = (abs(c1x) if abs(c1x) >= abs(c1y) else abs(c1y)) + r1
        if dev0 + screen * size0 > tolerance or dev1 + screen * size1 > tolerance:
            return None
        atan_y += (sn * e0y + c * y0, sin_half_a, sn * ecy + c * yc, sin_half_b)
        atan_x += (c * e0y - sn * y0, cos_half_a, c * ecy - sn * yc, cos_half_b)
        arcs += (
            (a0x, a0y, gx, gy, c0x, c0y, r0, u0, t, dev0, u_arc0),
            (gx, gy, a1x, a1y, c1x, c1y, r1, t, u1, dev1, u_arc1),
        )
        total += a0x + a0y + gx + gy + a1x + a1y + c0x + c0y + c1x + c1y + size0 + size1
        total += u0 + t + u1 + dev0 + dev1 + u_arc0 + u_arc1
    total += sum(atan_y) + sum(atan_x)
    if not math.isfinite(total):
        return None
    angles = np.arctan2(atan_y, atan_x).tolist()
    values: list[SegmentValues] = []
    radii: list[float] = []
    lengths: list[float] = []
    deviations: list[float] = []
    for i, (sx, sy, ex, ey, cx, cy, r, u_start, u_end, dev, u_dev) in enumerate(arcs):
        sweep = 2.0 * angles[2 * i + 1]
        if not sweep > FLAT_SWEEP_RAD:
            return None
        length = r * sweep
        values.append(
            (
                True,
                [sx, sy],
                [ex, ey],
                [cx, cy],
                r,
                angles[2 * i],
                mirror * sweep,
                length,
                u_start,
                u_end,
                dev,
                u_dev,
            )
        )
        radii.append(r)
        lengths.append(length)
        deviations.append(dev)
    # assemble.stats_one's numbers: maxima, minima and the first maximum are exact, and the
    # sums add in numpy's order.
    max_dev = max(deviations)
    stats = SplineStats(
        arc_count=len(values),
        line_count=0,
        max_deviation=max_dev,
        u_at_max_deviation=arcs[deviations.index(max_dev)][-1],
        deviation_ratio=max_dev / tolerance,
        mean_segment_deviation=numpy_sum(deviations) / len(values),
        spiral_length=spiral_length,
        spline_length=numpy_sum(lengths),
        min_radius=min(radii),
        max_radius=max(radii),
    )
    return ArcSpline(values, stats, tolerance, strategy)


def numpy_sum(values: Sequence[float]) -> float:
    """``np.add.reduceat`` of contiguous float64 ``values`` over one segment (the statistics'
    sums), bit for bit, in floats: the first value, plus the rest summed as numpy's
    ``pairwise_sum`` does (numpy/_core/src/umath/loops_utils.h.src) — fewer than 8 in turn,
    up to 128 in 8 interleaved accumulators, more by halves. (``np.add.reduce`` may add in
    another order.)"""
    if len(values) == 1:
        return values[0]
    return values[0] + _pairwise_sum(values, 1, len(values) - 1)


def _pairwise_sum(a: Sequence[float], begin: int, n: int) -> float:
    if n < _PAIRWISE_LANES:
        total = 0.0
        for i in range(begin, begin + n):
            total += a[i]
        return total
    if n <= _PAIRWISE_BLOCK:
        r = list(a[begin : begin + _PAIRWISE_LANES])
        i = _PAIRWISE_LANES
        while i < n - n % _PAIRWISE_LANES:
            for lane in range(_PAIRWISE_LANES):
                r[lane] += a[begin + i + lane]
            i += _PAIRWISE_LANES
        total = ((r[0] + r[1]) + (r[2] + r[3])) + ((r[4] + r[5]) + (r[6] + r[7]))
        for j in range(begin + i, begin + n):
            total += a[j]
        return total
    half = n // 2
    half -= half % _PAIRWISE_LANES
    return _pairwise_sum(a, begin, half) + _pairwise_sum(a, begin + half, n - half)
