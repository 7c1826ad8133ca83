"""The proof of :mod:`arcspline.geometry.fewest_exact` for one arc at a time, in Python floats.

A greedy step of ``fewest-arcs`` proves a handful of arcs — often only the two of its first
candidate — and numpy spends far more on the call overhead of the cascade's small arrays than
on the arithmetic. This module restates :func:`~arcspline.geometry.fewest_exact.joint_split` and
:func:`~arcspline.geometry.fewest_exact.arc_deviation` (the polar-graph conditions, the quintic
``h``, its derivative cascade and the bracketed Newton iteration of
:func:`arcspline.geometry.roots.bracketed_newton`) for one element, operation for operation:
the same additions, multiplications, divisions and square roots in the same order, each
correctly rounded in Python as in numpy, so every result is bit for bit the array result.
Sines and cosines are not restated (numpy's may differ from ``math``'s in the last bit): the
callers pass them in, computed by numpy.

Where the iteration meets something the plain restatement does not mirror (a NaN, a zero
or non-finite slope), the functions give up (:class:`HandBackError`, or ``None``); the caller
then runs the array version on that one element. (A zero's sign may differ where the array
sort orders ``-0.0`` and ``0.0`` differently; the values are equal.)
"""

from __future__ import annotations

import math
from collections.abc import Callable

from .roots import FAST_ITERATIONS, FIXED_ITERATIONS, MAX_ITERATIONS, RESOLUTION_ULPS

#: An arc's centre is stored with an error of about ``eps·radius``; this many ulps of the radius
#: must fit in the tolerance (error ≤ 1e-4 of it).
CENTRE_ULPS = 1e4
_EPS = 2.0**-52

ValueAndSlope = Callable[[float], tuple[float, float]]


class HandBackError(Exception):
    """The element left what the float restatement mirrors: the caller uses numpy."""


def _maximum(a: float, b: float) -> float:
    """``np.maximum``: the second on a tie (signed zeros), NaN from either."""
    return a if a > b or a != a else b


def _minimum(a: float, b: float) -> float:
    """``np.minimum``: the second on a tie, NaN from either."""
    return a if a < b or a != a else b


def _step(value: float, slope: float) -> float:
    if slope == 0.0 or not math.isfinite(value) or not math.isfinite(slope):
        raise HandBackError
    return value / slope


def newton(fn: ValueAndSlope, lo: float, hi: float, start: float) -> float:
    """``bracketed_newton`` for one element: plain steps, then the safeguarded iteration."""
    resolution = RESOLUTION_ULPS * _EPS * max(abs(lo), abs(hi))
    x = _minimum(_maximum(start, lo), hi)
    isfinite = math.isfinite
    step = math.nan
    for _ in range(FIXED_ITERATIONS):
        value, slope = fn(x)
        if slope == 0.0 or not (isfinite(value) and isfinite(slope)):
            raise HandBackError
        step = value / slope
        x = x - step
    done = abs(step) <= resolution
    for _ in range(FAST_ITERATIONS - FIXED_ITERATIONS):
        if done:
            break
        step = _step(*fn(x))
        x = x - step
        done = abs(step) <= resolution
    if done and lo <= x <= hi:
        return x
    return _safeguarded(fn, lo, hi, start, resolution)


def _safeguarded(fn: ValueAndSlope, lo: float, hi: float, start: float, resolution: float) -> float:
    x = _minimum(_maximum(start, lo), hi)
    sign = 1.0 if fn(lo)[0] <= 0.0 else -1.0
    for _ in range(MAX_ITERATIONS):
        value, slope = fn(x)
        f, df = sign * value, sign * slope
        if f < 0.0:
            lo = x
        else:
            hi = x
        step = _step(f, df)
        newton = x - step
        if abs(step) <= resolution:
            return newton
        x = newton if lo < newton < hi else 0.5 * (lo + hi)
    return x


def joint_split(k: float, m: float, jx: float, jy: float, tx: float, ty: float) -> float:
    """``joint_split`` for one joint of direction ``(tx, ty)``; NaN where the array version
    gives NaN (no sign change over ``[0, 1]``)."""

    def f(s: float) -> tuple[float, float]:
        s2 = s * s
        value = (s * (3.0 + k * s2) - jx) * tx + (m * s2 * s - jy) * ty
        return value, 3.0 * (tx * (1.0 + k * s2) + ty * m * s2)

    (f_lo, d_lo), (f_hi, d_hi) = f(0.0), f(1.0)
    if not (f_lo <= 0.0 and f_hi >= 0.0 and d_lo > 0.0 and d_hi > 0.0):
        return math.nan
    return newton(f, 0.0, 1.0, min(max(jx / 3.0, 0.0), 1.0))


def _horner(c: list[float], x: float) -> float:
    """Ascending coefficients, as ``fewest_exact._horner``."""
    result = c[-1]
    for cj in c[-2::-1]:
        result = result * x + cj
    return result


def _value_and_slope(c: list[float], dc: list[float]) -> ValueAndSlope:
    """``(_horner(c, x), _horner(dc, x))`` written out for the cascade's degrees (the same
    operations in the same order, without the loop: this runs at every Newton step)."""
    if len(c) == 3 and len(dc) == 2:
        c0, c1, c2 = c
        d0, d1 = dc
        return lambda x: ((c2 * x + c1) * x + c0, d1 * x + d0)
    if len(c) == 4 and len(dc) == 3:
        c0, c1, c2, c3 = c
        d0, d1, d2 = dc
        return lambda x: (((c3 * x + c2) * x + c1) * x + c0, (d2 * x + d1) * x + d0)
    if len(c) == 5 and len(dc) == 4:
        c0, c1, c2, c3, c4 = c
        d0, d1, d2, d3 = dc
        return lambda x: (
            (((c4 * x + c3) * x + c2) * x + c1) * x + c0,
            ((d3 * x + d2) * x + d1) * x + d0,
        )
    if len(c) == 6 and len(dc) == 5:
        c0, c1, c2, c3, c4, c5 = c
        d0, d1, d2, d3, d4 = dc
        return lambda x: (
            ((((c5 * x + c4) * x + c3) * x + c2) * x + c1) * x + c0,
            (((d4 * x + d3) * x + d2) * x + d1) * x + d0,
        )
    return lambda x: (_horner(c, x), _horner(dc, x))


def is_graph(
    k: float,
    m: float,
    jx: float,
    jy: float,
    tx: float,
    ty: float,
    kappa: float,
    ex: float,
    ey: float,
    s_lo: float,
    s_hi: float,
) -> bool:
    """``fewest_exact._is_graph`` for one arc."""
    nx, ny = -ty, tx
    w0 = kappa * jy + tx
    w2 = kappa * (k * jy - m * jx) + k * tx + m * ty
    w3 = 2.0 * m * kappa

    def w(u: float) -> float:
        return w0 + u * u * (w2 + w3 * u)

    values = [w(s_lo), w(s_hi)]
    if w3 != 0.0:
        critical = -w2 / (1.5 * w3)
        if s_lo < critical < s_hi:
            values.append(w(critical))
    if any(math.isnan(v) for v in values):
        raise HandBackError
    if not (min(values) > 0.0 and s_hi > s_lo):
        return False
    dx, dy = kappa * (ex - jx) - nx, kappa * (ey - jy) - ny
    for s in (s_lo, s_hi):
        s2 = s * s
        px = kappa * (s * (3.0 + k * s2) - jx) - nx
        py = kappa * (m * s2 * s - jy) - ny
        if not px * dx + py * dy > 0.0:
            return False
    return True


def arc_deviation(
    k: float,
    m: float,
    jx: float,
    jy: float,
    tx: float,
    ty: float,
    kappa: float,
    ex: float,
    ey: float,
    s_lo: float,
    s_hi: float,
    tolerance: float,
) -> tuple[float, float] | None:
    """``fewest_exact.arc_deviation`` for one arc of direction ``(tx, ty) = (cos φ, sin φ)``:
    ``(value, u)``, value ``inf`` where the arc is refused; ``None`` to hand it to numpy.
    Its piece lies in ``[0, 1]`` (else it is refused), so the cascade starts at level 3."""
    try:
        valid = s_lo >= 0.0 and s_hi <= 1.0
        valid = valid and is_graph(k, m, jx, jy, tx, ty, kappa, ex, ey, s_lo, s_hi)
        valid = valid and (kappa == 0.0 or abs(kappa) * tolerance >= CENTRE_ULPS * _EPS)
        if not valid:
            return math.inf, s_lo
        points = _cascade_roots(k, m, jx, jy, -ty, tx, kappa, s_lo, s_hi)
    except HandBackError:
        return None
    nx, ny = -ty, tx
    worst, at = -math.inf, s_lo
    for u in points:
        u2 = u * u
        px = u * (3.0 + k * u2) - jx
        py = m * u2 * u - jy
        numerator = kappa * (px * px + py * py) - 2.0 * (px * nx + py * ny)
        ax, ay = kappa * px - nx, kappa * py - ny
        square = ax * ax + ay * ay
        e = abs(numerator) / (math.sqrt(square) + 1.0) if square < math.inf else math.inf
        if math.isnan(e):
            return None
        if e > worst:
            worst, at = e, u
    return worst, at


def _cascade_roots(
    k: float,
    m: float,
    jx: float,
    jy: float,
    nx: float,
    ny: float,
    kappa: float,
    lo: float,
    hi: float,
) -> list[float]:
    """``fewest_exact._cascade_roots`` for one arc with ``lo ≥ 0`` (levels 3 to 0)."""
    coeffs = [
        -kappa * jx - nx,
        3.0 * kappa,
        -kappa * (k * jx + m * jy) - (k * nx + m * ny),
        4.0 * k * kappa,
        0.0,
        kappa * (k * k + m * m),
    ]
    derivatives = [coeffs]
    for _ in range(5):
        c = derivatives[-1]
        derivatives.append([c[j] * float(j) for j in range(1, len(c))])
    points = [lo, hi]
    for level in (3, 2, 1, 0):
        c = derivatives[level]
        value = _value_and_slope(c, derivatives[level + 1])
        f = [value(p)[0] for p in points]
        roots = []
        for a, b, fa, fb in zip(points, points[1:], f, f[1:], strict=False):
            if not ((fa < 0.0 and fb > 0.0) or (fa > 0.0 and fb < 0.0)):
                continue
            if level == 3:
                ratio = -c[0] / c[2]
                if not ratio >= 0.0:
                    raise HandBackError
                root = min(max(math.sqrt(ratio), a), b)
            else:
                root = newton(value, a, b, a + (b - a) * fa / (fa - fb))
            if math.isnan(root):
                raise HandBackError
            roots.append(root)
        if roots:
            points = sorted(set(points + roots))
    return points
