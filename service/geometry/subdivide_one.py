"""Walton & Meek's subdivision (paper §5) for one spiral, in Python floats.

A single spiral's recursion has a few dozen pieces spread over several levels; numpy's cost
per call (about half a microsecond, whatever the array's size) then outweighs the arithmetic,
so one spiral is faster in plain floats, depth first. The arithmetic is the batch path's own
(``biarc_terms``, ``split_cubic``, ``side_quartic``, ``radial_gap``, ``join_gap`` and the
one-element Newton twins in ``service.geometry.roots``), the same operations in the same
order — correctly rounded in numpy as in Python — so the kept biarcs are bit-identical to
those of :func:`service.geometry.subdivide.subdivide` for the same spiral.

Anything out of the ordinary — a division by zero, a piece too short to split, the segment
limit, a NaN where the two paths' choices between values could differ — returns ``None``:
the caller then runs the batch path, which decides those cases (and words their errors) the
one way. Other non-finite numbers are kept exactly as the batch path keeps them and refused
with its results.
"""

from __future__ import annotations

import math

import numpy as np

from .biarc import Biarcs
from .deviation import SIDE_FIXED_ITERATIONS, SPLIT_FIXED_ITERATIONS, Deviation
from .roots import cubic_root, quartic_root
from .subdivide import STUCK_ULPS, Kept

_EPS = float(np.finfo(np.float64).eps)

#: Pieces looked at before giving up: a spiral that needs more is subdivided faster by the
#: batch path, whose numpy levels cost about as much as 20 pieces here, whatever their width.
MAX_PIECES = 256

#: A kept piece: the fields of ``Biarcs`` then those of ``Deviation``, in order.
Row = tuple[float, ...]


def subdivide_one(k: float, m: float, tolerance: float, max_biarcs: int) -> list[Row] | None:
    """The biarcs :func:`~service.geometry.subdivide.subdivide` keeps for the one spiral
    ``(k, m)``, in parameter order, as rows (:func:`kept` turns them into its columns), or
    ``None`` where that function must decide or is faster (beyond ``MAX_PIECES``)."""
    alpha4 = k * k + m * m
    kept: list[Row] = []
    # A stack: the top is the leftmost piece not yet looked at. No piece is deeper than
    # MAX_PIECES < MAX_LEVELS, so the batch path's level cap cannot apply here.
    pending = [(0.0, 1.0)]
    try:
        for _ in range(MAX_PIECES):
            if not pending:
                return kept
            u0, u1 = pending.pop()
            row = _piece(k, m, alpha4, u0, u1)
            value, at = row[-2], row[-1]
            if value > tolerance:  # the batch path's test, NaN included
                if min(at - u0, u1 - at) <= STUCK_ULPS * _EPS * u1:
                    return None
                pending += ((at, u1), (u0, at))
                if len(kept) + len(pending) > max_biarcs:
                    return None
            else:
                kept.append(row)
    except (ArithmeticError, ValueError):  # a division by zero, a math domain error
        return None
    return kept if not pending else None


def kept(rows: list[Row]) -> Kept:
    """The batch path's columns of these rows."""
    columns = np.array(rows).T
    split = len(Biarcs._fields)
    return Kept(
        spiral=np.zeros(len(rows), dtype=np.intp),
        biarcs=Biarcs(*columns[:split]),
        deviation=Deviation(*columns[split:]),
    )


def _piece(k: float, m: float, alpha4: float, u0: float, u1: float) -> Row:
    """One piece: ``biarc_terms``, ``split_parameter`` and ``max_deviation`` for one element,
    written out operation for operation (the function calls of the shared form cost more
    than the arithmetic here; tests/geometry/test_subdivide_one.py holds the two equal)."""
    sqrt = math.sqrt
    # biarc_terms
    h = u1 - u0
    w0, w1 = u0 * u0, u1 * u1
    w_chord = (w1 + u1 * u0 + w0) / 3.0
    x0, y0 = 1.0 + k * w0, m * w0
    xc, yc = 1.0 + k * w_chord, m * w_chord
    x1, y1 = 1.0 + k * w1, m * w1
    n0, nc, n1 = sqrt(x0 * x0 + y0 * y0), sqrt(xc * xc + yc * yc), sqrt(x1 * x1 + y1 * y1)
    n0c, nc1 = n0 * nc, nc * n1
    cos_half_a = sqrt(0.5 + 0.5 * ((x0 * xc + y0 * yc) / n0c))
    cos_half_b = sqrt(0.5 + 0.5 * ((xc * x1 + yc * y1) / nc1))
    sin_half_a = m * (h * (u1 + 2.0 * u0) / 3.0) / (n0c * (2.0 * cos_half_a))
    sin_half_b = m * (h * (2.0 * u1 + u0) / 3.0) / (nc1 * (2.0 * cos_half_b))
    chord_length = 3.0 * h * nc
    chord_over_s = chord_length / (sin_half_a * cos_half_b + cos_half_a * sin_half_b)
    join_distance = chord_over_s * sin_half_b
    e0x, e0y = x0 / n0, y0 / n0
    ecx, ecy = xc / nc, yc / nc
    e1x, e1y = x1 / n1, y1 / n1
    along = join_distance / (2.0 * cos_half_a)
    join_dx, join_dy = along * (e0x + ecx), along * (e0y + ecy)
    radius0 = join_distance / (2.0 * sin_half_a)
    radius1 = chord_over_s * sin_half_a / (2.0 * sin_half_b)
    # split_cubic, then its root
    big_k = k * ecx + m * ecy
    c0 = -join_distance * cos_half_a
    c2 = 3.0 * u0 * big_k
    c1 = 3.0 * ecx + 3.0 * u0 * u0 * big_k
    v = cubic_root(big_k, c2, c1, c0, 0.0, h, h * (-c0 / chord_length), SPLIT_FIXED_ITERATIONS)
    t = u0 + v
    # join_gap
    d = t - u0
    sigma = t * t + t * u0 + w0
    dx, dy = d * (3.0 + k * sigma) - join_dx, d * m * sigma - join_dy
    at_t = sqrt(dx * dx + dy * dy)
    arc0, u_arc0 = _side(k, m, alpha4, u0, w0, u0, t, radius0, e0x, e0y, at_t, t)
    arc1, u_arc1 = _side(k, m, alpha4, u1, w1, t, u1, radius1, e1x, e1y, at_t, t)
    value, at = (arc0, u_arc0) if arc0 >= arc1 else (arc1, u_arc1)
    return (
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
        chord_length,
        join_distance,
        join_dx,
        join_dy,
        radius0,
        radius1,
        t,
        arc0,
        u_arc0,
        arc1,
        u_arc1,
        value,
        at,
    )


def _side(
    k: float,
    m: float,
    alpha4: float,
    ui: float,
    ui2: float,
    lo: float,
    hi: float,
    radius: float,
    ex: float,
    ey: float,
    at_t: float,
    t: float,
) -> tuple[float, float]:
    """The largest deviation over one side and where it is: ``side_quartic``, the false
    position start, the root, ``radial_gap`` and the choice against the gap at ``t``."""
    rs, rc = radius * ey, radius * ex
    ax, ay = ui * (3.0 + k * ui2), m * ui2 * ui
    alpha2 = k * (rs - ax) - m * (ay + rc)
    c2 = 4.0 * k + alpha4 * ui2
    c1 = alpha2 + ui * c2
    c3, c0 = alpha4 * ui, 3.0 + ui * c1
    q_lo = (((alpha4 * lo + c3) * lo + c2) * lo + c1) * lo + c0
    q_hi = (((alpha4 * hi + c3) * hi + c2) * hi + c1) * hi + c0
    if not q_lo * q_hi < 0.0:
        return at_t, t
    x = lo + (hi - lo) * q_lo / (q_lo - q_hi)
    q_x = (((alpha4 * x + c3) * x + c2) * x + c1) * x + c0
    if (q_x < 0.0) == (q_lo < 0.0):  # the root lies right of the secant point
        x = x + (hi - x) * q_x / (q_x - q_hi)
    else:
        x = x + (lo - x) * q_x / (q_x - q_lo)
    u = quartic_root(alpha4, c3, c2, c1, c0, lo, hi, x, SIDE_FIXED_ITERATIONS)
    d = u - ui
    sigma = u * u + u * ui + ui2
    px, py = d * (3.0 + k * sigma), d * m * sigma
    numerator = px * px + py * py + 2.0 * (px * rs - py * rc)
    dx, dy = px + rs, py - rc
    gap = abs(numerator) / (math.sqrt(dx * dx + dy * dy) + radius)
    if gap > at_t:
        return gap, u
    if gap <= at_t:
        return at_t, t
    # A NaN gap: np.maximum would keep it where this comparison cannot; the batch decides.
    raise FloatingPointError
