"""Walton & Meek's subdivision (paper §5) for one spiral, in Python floats.

A single spiral's recursion has a few dozen pieces spread over several levels; numpy's cost
per call (about half a microsecond, whatever the array's size) then outweighs the arithmetic,
so one spiral is faster in plain floats, depth first. The arithmetic is the batch path's own
(``incentre_biarcs``, ``split_cubic``, ``side_quartic``, ``radial_gap``, ``join_gap`` and the
Newton iteration of ``roots.polynomial_root``), written out inline — function calls cost
more than arithmetic here — with the same operations in the same order, each correctly
rounded in numpy as in Python; so the kept biarcs are bit-identical to those of
:func:`arcspline.geometry.subdivide.subdivide` for the same spiral (held so by
tests/geometry/test_subdivide_one.py). A root the plain Newton steps miss is solved by the
array version for that one element, safeguards and all.

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
from .roots import FAST_ITERATIONS, RESOLUTION_ULPS, one_root
from .subdivide import STUCK_ULPS, Kept

_EPS = float(np.finfo(np.float64).eps)
_RESOLUTION = RESOLUTION_ULPS * _EPS

#: Pieces looked at before giving up: a spiral that needs more is subdivided faster by the
#: batch path, whose numpy levels cost about as much as 20 pieces here, whatever their width.
MAX_PIECES = 256

#: A kept piece: the fields of ``Biarcs`` then those of ``Deviation``, in order.
Row = tuple[float, ...]


def subdivide_one(k: float, m: float, tolerance: float, max_biarcs: int) -> list[Row] | None:
    """The biarcs :func:`~arcspline.geometry.subdivide.subdivide` keeps for the one spiral
    ``(k, m)``, in parameter order, as rows (:func:`kept` turns them into its columns), or
    ``None`` where that function must decide or is faster (beyond ``MAX_PIECES``)."""
    alpha4 = k * k + m * m
    kept: list[Row] = []
    # A stack: the top is the leftmost piece not yet looked at. No piece is deeper than
    # MAX_PIECES < MAX_LEVELS, so the batch path's level cap cannot apply here.
    pending = [(_end(k, m, 0.0), _end(k, m, 1.0))]
    try:
        for _ in range(MAX_PIECES):
            if not pending:
                return kept
            end0, end1 = pending.pop()
            row = _piece(k, m, alpha4, end0, end1)
            value, at = row[-2], row[-1]
            if value > tolerance:  # the batch path's test, NaN included
                u0, u1 = end0[0], end1[0]
                if min(at - u0, u1 - at) <= STUCK_ULPS * _EPS * u1:
                    return None
                middle = _end(k, m, at)
                pending += ((middle, end1), (end0, middle))
                if len(kept) + len(pending) > max_biarcs:
                    return None
            else:
                kept.append(row)
    except (ArithmeticError, ValueError):  # a division by zero, a math domain error
        return None
    return kept if not pending else None


def kept(rows: list[Row], spiral: int = 0) -> Kept:
    """The batch path's columns of these rows, as those of spiral ``spiral``."""
    columns = np.array(rows).T
    split = len(Biarcs._fields)
    return Kept(
        spiral=np.full(len(rows), spiral, dtype=np.intp),
        biarcs=Biarcs(*columns[:split]),
        deviation=Deviation(*columns[split:]),
    )


#: What a piece needs of one of its ends ``u`` (:func:`_end`): computed once per split point
#: for both pieces that share it (the batch path computes the same numbers per piece).
End = tuple[float, float, float, float, float, float, float, float, float]


def _end(k: float, m: float, u: float) -> End:
    """``u``, ``w = u²``, the direction ``(x, y) = (1 + k·w, m·w)``, its norm and unit vector,
    and ``Q(u)`` (``canonical.point``)."""
    w = u * u
    x, y = 1.0 + k * w, m * w
    n = math.sqrt(x * x + y * y)
    return (u, w, x, y, n, x / n, y / n, u * (3.0 + k * w), m * w * u)


def _piece(k: float, m: float, alpha4: float, end0: End, end1: End) -> Row:
    """One piece: ``incentre_biarcs``, ``split_parameter`` and ``max_deviation`` for one element,
    written out operation for operation (the function calls of the shared form cost more
    than the arithmetic here; tests/geometry/test_subdivide_one.py holds the two equal)."""
    sqrt = math.sqrt
    u0, w0, x0, y0, n0, e0x, e0y, q0x, q0y = end0
    u1, w1, x1, y1, n1, e1x, e1y, q1x, q1y = end1
    # incentre_biarcs
    h = u1 - u0
    w_chord = (w1 + u1 * u0 + w0) / 3.0
    xc, yc = 1.0 + k * w_chord, m * w_chord
    nc = sqrt(xc * xc + yc * yc)
    n0c, nc1 = n0 * nc, nc * n1
    cos_half_a = sqrt(0.5 + 0.5 * ((x0 * xc + y0 * yc) / n0c))
    cos_half_b = sqrt(0.5 + 0.5 * ((xc * x1 + yc * y1) / nc1))
    sin_half_a = m * (h * (u1 + 2.0 * u0) / 3.0) / (n0c * (2.0 * cos_half_a))
    sin_half_b = m * (h * (2.0 * u1 + u0) / 3.0) / (nc1 * (2.0 * cos_half_b))
    chord_length = 3.0 * h * nc
    chord_over_s = chord_length / (sin_half_a * cos_half_b + cos_half_a * sin_half_b)
    join_distance = chord_over_s * sin_half_b
    ecx, ecy = xc / nc, yc / nc
    along = join_distance / (2.0 * cos_half_a)
    join_dx, join_dy = along * (e0x + ecx), along * (e0y + ecy)
    radius0 = join_distance / (2.0 * sin_half_a)
    radius1 = chord_over_s * sin_half_a / (2.0 * sin_half_b)
    # split_cubic, then its root
    big_k = k * ecx + m * ecy
    c0 = -join_distance * cos_half_a
    c2 = 3.0 * u0 * big_k
    c1 = 3.0 * ecx + 3.0 * u0 * u0 * big_k
    # roots.polynomial_root for this one cubic on [0, h]: the same iterates (its
    # fixed_iterations, then until the first step within the resolution), the same result.
    resolution = _RESOLUTION * abs(h)  # max(|0|, |h|)
    v = h * (-c0 / chord_length)
    v = 0.0 if v < 0.0 else v
    start = v = h if v > h else v
    s2, s1 = 3 * big_k, 2 * c2
    steps = 1
    while steps < SPLIT_FIXED_ITERATIONS:
        v = v - (((big_k * v + c2) * v + c1) * v + c0) / ((s2 * v + s1) * v + c1)
        steps += 1
    while True:
        step = (((big_k * v + c2) * v + c1) * v + c0) / ((s2 * v + s1) * v + c1)
        v = v - step
        if abs(step) <= resolution and 0.0 <= v <= h:
            break
        if steps == FAST_ITERATIONS or abs(step) <= resolution:
            # Past the plain steps: the safeguarded iteration, from the array version.
            v = one_root((big_k, c2, c1, c0), 0.0, h, start, SPLIT_FIXED_ITERATIONS)
            break
        steps += 1
    t = u0 + v
    # join_gap
    d = t - u0
    sigma = t * t + t * u0 + w0
    dx, dy = d * (3.0 + k * sigma) - join_dx, d * m * sigma - join_dy
    at_t = sqrt(dx * dx + dy * dy)
    arc0, u_arc0 = _side(k, m, alpha4, u0, w0, q0x, q0y, u0, t, radius0, e0x, e0y, at_t, t)
    arc1, u_arc1 = _side(k, m, alpha4, u1, w1, q1x, q1y, t, u1, radius1, e1x, e1y, at_t, t)
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
    ax: float,
    ay: float,
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
    # The root in [lo, hi] as for the cubic above.
    a, b = abs(lo), abs(hi)
    resolution = _RESOLUTION * (a if a >= b else b)
    x = lo if x < lo else x
    start = u = hi if x > hi else x
    s3, s2, s1 = 4 * alpha4, 3 * c3, 2 * c2
    steps = 1
    while steps < SIDE_FIXED_ITERATIONS:
        value = (((alpha4 * u + c3) * u + c2) * u + c1) * u + c0
        u = u - value / (((s3 * u + s2) * u + s1) * u + c1)
        steps += 1
    while True:
        value = (((alpha4 * u + c3) * u + c2) * u + c1) * u + c0
        step = value / (((s3 * u + s2) * u + s1) * u + c1)
        u = u - step
        if abs(step) <= resolution and lo <= u <= hi:
            break
        if steps == FAST_ITERATIONS or abs(step) <= resolution:
            u = one_root((alpha4, c3, c2, c1, c0), lo, hi, start, SIDE_FIXED_ITERATIONS)
            break
        steps += 1
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
