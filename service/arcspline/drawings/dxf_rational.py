"""A rational cubic Bézier piece as plain cubics within a certified distance (docs/drawings.md
§4).

Our curves are rational of degree ≤ 2, so a rational cubic ``R(t) = P(t)/w(t)`` (homogeneous
control points ``H_i = (w_i·p_i, w_i)``, ``P = Σ B³_i·w_i·p_i``, ``w = Σ B³_i·w_i``) that is
not an elevated conic is replaced by cubics. The candidate on a piece is the cubic Hermite
interpolant ``C`` of ``R``: same end points, and the end derivatives ``R'(0) = 3·(w1/w0)·(p1 −
p0)`` and ``R'(1) = 3·(w2/w3)·(p3 − p2)`` (Farin, "Curves and Surfaces for CAGD", §13.2), so
``C1 = p0 + (w1/w0)·(p1 − p0)``, ``C2 = p3 − (w2/w3)·(p3 − p2)`` and the result is G1 wherever
``R`` is.

The distance is certified: ``R − C = D/w`` with ``D = P − w·C`` of degree 6, whose Bernstein
coefficients are, by the product formula ``B³_i·B³_j = C(3,i)·C(3,j)/C(6,i+j) · B⁶_{i+j}``
(``P`` elevated as ``P·1`` with ``1 = Σ B³_j``),

    d_k = Σ_{i+j=k} C(3,i)·C(3,j)/C(6,k) · (w_i·p_i − w_i·C_j).

By the convex hull property ``|D(t)| ≤ max_k |d_k|`` and ``w(t) ≥ min_i w_i > 0``, so
``sup_t |R(t) − C(t)| ≤ max_k |d_k| / min_i w_i``, to which a bound on the rounding of these
sums is added. A piece whose bound exceeds the tolerance is halved (de Casteljau on the
homogeneous points) until every piece is within it, or refused beyond a number of pieces.
"""

from __future__ import annotations

import math
import sys
from collections.abc import Sequence
from typing import NamedTuple

from arcspline.geometry.curves.segments import Cubic
from arcspline.geometry.spline import Point

#: A control point in homogeneous coordinates ``(w·x, w·y, w)``.
Homogeneous = tuple[float, float, float]

#: ``C(3,i)·C(3,j)/C(6,i+j)`` for ``i, j`` in ``0..3``: the Bernstein product formula.
_PRODUCT = tuple(
    tuple(math.comb(3, i) * math.comb(3, j) / math.comb(6, i + j) for j in range(4))
    for i in range(4)
)
#: Units in the last place allowed for the rounding of a piece's control points (de Casteljau
#: levels, blossoms) and of the sums ``d_k``, times the piece's coordinate scale: a generous
#: multiple of the few ulps each step can lose.
ROUNDING_ULPS = 256.0


class CubicFit(NamedTuple):
    """Cubics chained end to end standing for a rational cubic, and the certified largest
    distance ``bound`` between the two, in the curve's own units."""

    cubics: tuple[Cubic, ...]
    bound: float


class PieceBound(NamedTuple):
    """The Hermite cubic of one rational piece, and its certified distance from it."""

    cubic: Cubic
    bound: float


def rational_cubic_fit(
    piece: Sequence[Homogeneous], start: Point, tolerance: float, max_cubics: int
) -> CubicFit | None:
    """Cubics within ``tolerance`` of the rational cubic ``piece`` (module docstring), the
    first starting at ``start`` (the previous segment's end, bit for bit), or None when more
    than ``max_cubics`` would be needed. Every weight must be > 0."""
    if any(not h[2] > 0.0 for h in piece):
        raise ValueError("a rational piece needs weights > 0")
    pending: list[tuple[Homogeneous, ...]] = [tuple(piece)]
    cubics: list[Cubic] = []
    bound = 0.0
    while pending:
        current = pending.pop()
        fit = hermite_bound(current, start)
        if fit.bound <= tolerance:
            cubics.append(fit.cubic)
            start = fit.cubic.end
            bound = max(bound, fit.bound)
            continue
        if len(cubics) + len(pending) + 2 > max_cubics:
            return None
        left, right = halve(current)
        pending.extend((right, left))  # the left half is taken next: the cubics stay in order
    return CubicFit(tuple(cubics), bound)


def hermite_bound(piece: Sequence[Homogeneous], start: Point) -> PieceBound:
    """The Hermite cubic of the rational cubic ``piece`` starting at ``start``, and
    ``max_k |d_k| / min_i w_i`` plus a rounding allowance (module docstring)."""
    p = [Point(h[0] / h[2], h[1] / h[2]) for h in piece]
    w = [h[2] for h in piece]
    r0, r1 = w[1] / w[0], w[2] / w[3]
    c1 = Point(start[0] + r0 * (p[1][0] - p[0][0]), start[1] + r0 * (p[1][1] - p[0][1]))
    c2 = Point(p[3][0] - r1 * (p[3][0] - p[2][0]), p[3][1] - r1 * (p[3][1] - p[2][1]))
    cubic = Cubic(start, c1, c2, p[3])
    d_max = 0.0
    for k in range(7):
        dx = dy = 0.0
        for i in range(max(0, k - 3), min(3, k) + 1):
            j = k - i
            c = _PRODUCT[i][j]
            dx += c * (piece[i][0] - w[i] * cubic[j][0])
            dy += c * (piece[i][1] - w[i] * cubic[j][1])
        d_max = max(d_max, math.hypot(dx, dy))
    w_min = min(w)
    size = max(abs(c) for point in (*p, *cubic) for c in point)
    scale = max(abs(c) for h in piece for c in h[:2]) + max(w) * size
    rounding = ROUNDING_ULPS * sys.float_info.epsilon * scale / w_min
    return PieceBound(cubic, d_max / w_min + rounding)


def halve(piece: Sequence[Homogeneous]) -> tuple[tuple[Homogeneous, ...], tuple[Homogeneous, ...]]:
    """The two halves ``t ∈ [0, ½]`` and ``[½, 1]`` of a cubic in homogeneous coordinates (de
    Casteljau); they share their middle point, the very same tuple."""
    a, b, c, d = piece
    ab, bc, cd = _mid(a, b), _mid(b, c), _mid(c, d)
    abc, bcd = _mid(ab, bc), _mid(bc, cd)
    m = _mid(abc, bcd)
    return (a, ab, abc, m), (m, bcd, cd, d)


def _mid(p: Homogeneous, q: Homogeneous) -> Homogeneous:
    return ((p[0] + q[0]) / 2.0, (p[1] + q[1]) / 2.0, (p[2] + q[2]) / 2.0)
