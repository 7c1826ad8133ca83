"""From one spiral's kept biarcs (rows of floats) to its world-coordinate arc spline.

:func:`service.geometry.assemble.segment_columns` maps a whole batch with numpy, about fifty
array operations whatever the batch's size; for the few dozen arcs of one spiral the same
arithmetic in floats costs a fraction of that. It is written operation for operation as
there (``canonical.point``, ``Frames.vector``, the pinned end point, ``r·N``), so the segments
are bit-identical; the angles (``arctan2``) are taken with numpy over all arcs at once, as
there. The common case only: a spline with a numerically flat arc, a non-finite number or an
arc whose placement needs measuring (``approximate._unplaceable_rows``), or with many arcs,
returns ``None``, and the batch path assembles it.
"""

from __future__ import annotations

import numpy as np

from .assemble import FLAT_SWEEP_RAD, stats_one
from .spiral import Spiral
from .subdivide_one import Row
from .types import ArcSpline, SegmentColumns

_EPS = float(np.finfo(np.float64).eps)

#: Biarcs assembled here at most: each costs about as much as half a numpy operation, and the
#: batch assembly's fifty operations do any number at once.
MAX_BIARCS = 48


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
    table: list[tuple[float, ...]] = []
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
        # One row per arc: start, end, centre, radius, the start direction's arctan2
        # arguments, the half sweep's sine and cosine, u_start, u_end, deviation and its u.
        table += (
            (a0x, a0y, gx, gy, c0x, c0y, r0, sn * e0y + c * y0, c * e0y - sn * y0, sin_half_a,
             cos_half_a, u0, t, dev0, u_arc0),
            (gx, gy, a1x, a1y, c1x, c1y, r1, sn * ecy + c * yc, c * ecy - sn * yc, sin_half_b,
             cos_half_b, t, u1, dev1, u_arc1),
        )  # fmt: skip
    columns = np.array(table)
    if not np.isfinite(columns).all():
        return None
    sweep = 2.0 * np.arctan2(columns[:, 9], columns[:, 10])
    if not (sweep > FLAT_SWEEP_RAD).all():
        return None
    radius = columns[:, 6]
    segments = SegmentColumns(
        is_arc=np.ones(len(table), dtype=bool),
        start=columns[:, 0:2],
        end=columns[:, 2:4],
        center=columns[:, 4:6],
        radius=radius,
        start_angle_rad=np.arctan2(columns[:, 7], columns[:, 8]),
        sweep_rad=mirror * sweep,
        length=radius * sweep,
        u_start=columns[:, 11],
        u_end=columns[:, 12],
        max_deviation=columns[:, 13],
        u_at_max_deviation=columns[:, 14],
    )
    return ArcSpline(segments, stats_one(segments, spiral_length, tolerance), tolerance, strategy)
