"""The exact two-sided deviation of a G1 chain of arcs from the canonical spiral.

Used by the ``fewest-arcs`` strategy (:mod:`arcspline.geometry.fewest`), whose arcs need not
touch the spiral: a chain's joints ``J_i`` (with unit tangents ``T_i``) may lie off the curve.
Everything is in the canonical frame of :mod:`arcspline.geometry.canonical`,
``Q(u) = (3u + k·u³, m·u³)``.

**Which spiral points an arc answers for.** Arc ``i`` runs from ``J_i`` (direction ``φ_i``,
signed curvature ``κ_i``, centre ``C_i = J_i + N_i/κ_i``, ``N`` the left normal) to
``J_{i+1}``. Its end rays ``C_i→J_i`` and ``C_i→J_{i+1}`` are the normal lines of the chain at
its joints — G1 puts both neighbouring centres on the normal line at a joint — so a single
parameter ``s_i`` per joint, the root of ``(Q(s) − J_i)·T_i = 0`` (a cubic increasing in ``s``
because every spiral tangent is within 90° of ``T_i``), splits the spiral between the arcs
before and after ``J_i``: arc ``i`` answers for ``u ∈ [s_i, s_{i+1}]``, and the pieces tile
``[0, 1]`` in order (``s_0 = 0`` and ``s_n = 1`` because the chain starts and ends on the
spiral with its tangents).

**Why the radial deviation is the two-sided distance.** If the polar angle of ``Q(u)`` about
``C_i`` is strictly monotone on ``[s_i, s_{i+1}]`` and ``Q(s_i)``, ``Q(s_{i+1})`` lie on the rays
through ``J_i``, ``J_{i+1}`` (not on the opposite side of ``C_i``), then the spiral piece and the
arc are both polar graphs ``ρ(ψ)`` over the *same* angular interval; each point of one is then
within ``|ρ_spiral(ψ) − r|`` of the point of the other at the same angle ``ψ``, so the Hausdorff
distance between the piece and the arc is at most ``max_u |‖Q(u) − C_i‖ − r_i|`` — and at least
it, since that is attained. Both conditions are checked exactly:

* monotone angle ⇔ ``w(u) = κ·(Q − J)×Q' + T·Q' > 0``, and ``w/3 = κ·j_y + T_x +
  (κ(k·j_y − m·j_x) + k·T_x + m·T_y)·u² + 2mκ·u³`` is a cubic whose minimum over the piece is at
  an end or at its one interior critical point;
* right side of the centre ⇔ ``(κ(Q(s) − J) − N)·(κ(J_end − J) − N) > 0`` at both ends.

A candidate arc failing either check is rejected (deviation reported as ``inf``). With
``κ → 0`` all of this is continuous and becomes the statement for a line segment.

**The maximum, exactly.** ``e(u) = |‖Q(u) − C‖ − r|`` is evaluated as
``|κ‖P‖² − 2P·N| / (‖κP − N‖ + 1)`` with ``P = Q(u) − J`` (no cancellation for huge radii). Its
interior extrema are roots of ``h(u) = κ·P·Q'/3 − N·Q'/3``, a quintic
``c0 + c1·u + c2·u² + c3·u³ + c5·u⁵`` (``c1 = 3κ``, ``c3 = 4kκ``, ``c5 = κ(k² + m²)``; the paper's
Theorem 2 polynomial times ``κ``). All its roots in the piece are isolated rigorously by the
*derivative cascade*: ``h⁽⁵⁾`` is constant, so ``h⁽⁴⁾`` is monotone on the piece and has at most
one root there; between consecutive roots of ``h⁽ᵈ⁺¹⁾`` the function ``h⁽ᵈ⁾`` is monotone, so a
sign change brackets its only root in that sub-interval and no sign change means none. Going
down from ``d = 4`` to ``d = 0`` with a bracketed Newton iteration at each level yields every
root of ``h`` in the piece (up to the iteration's resolution, where ``e`` is flat). Since
``c4 = 0``, ``h⁽⁴⁾ = 120·c5·u`` has no root in ``u > 0`` and ``h⁽³⁾ = 6·c3 + 60·c5·u²`` has its
root in closed form, so the iteration runs on levels 2, 1 and 0 only. The maximum
of ``e`` over the piece is the largest value at the piece's ends and at these roots; no sample
is involved. The distance at the ends is the exact distance between the spiral point on the
joint's normal line and the joint.

Calls with a few elements run element by element in Python floats
(:mod:`arcspline.geometry.fewest_exact_one`), bit for bit the same numbers.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from . import fewest_exact_one
from .fewest_exact_one import CENTRE_ULPS
from .roots import bracketed_newton
from .types import BoolArray, FloatArray

Float = float | FloatArray

_EPS = float(np.finfo(np.float64).eps)

#: Root levels of the cascade: derivative orders 4, 3, 2, 1, 0 of the quintic ``h``.
_LEVELS = (4, 3, 2, 1, 0)

#: Newton steps of screening's split parameter (:func:`split_guess`).
SPLIT_STEPS = 3

#: Calls of :func:`joint_split` and :func:`arc_deviation` with at most this many elements run
#: element by element in floats (:mod:`arcspline.geometry.fewest_exact_one`, the same numbers):
#: below it numpy's per-call overhead costs more than the arithmetic.
FLOAT_ELEMENTS = 8


@dataclass(frozen=True, slots=True)
class ArcDeviation:
    """Exact largest two-sided distance of each arc from its spiral piece (canonical units).

    ``value`` is ``inf`` where the piece is not a polar graph over the arc (see module text).
    """

    value: FloatArray
    u: FloatArray


def radial(
    k: Float,
    m: Float,
    jx: Float,
    jy: Float,
    phi: Float,
    kappa: Float,
    u: FloatArray,
) -> FloatArray:
    """``|‖Q(u) − C‖ − r|``, the circle through ``J`` with direction ``φ`` and curvature ``κ``."""
    u2 = u * u
    px = u * (3.0 + k * u2) - jx
    py = m * u2 * u - jy
    nx, ny = -np.sin(phi), np.cos(phi)
    numerator = kappa * (px * px + py * py) - 2.0 * (px * nx + py * ny)
    ax, ay = kappa * px - nx, kappa * py - ny
    # Not np.hypot: the float path's math.hypot may differ from it in the last bit. A square
    # that overflows (a circle far too small) must not read as distance 0: inf, refused.
    with np.errstate(over="ignore", invalid="ignore"):
        square = ax * ax + ay * ay
        result: FloatArray = np.where(
            np.isfinite(square), np.abs(numerator) / (np.sqrt(square) + 1.0), np.inf
        )
    return result


def joint_split(
    k: FloatArray, m: FloatArray, jx: FloatArray, jy: FloatArray, phi: FloatArray
) -> FloatArray:
    """The ``s ∈ [0, 1]`` where the spiral crosses the normal line at joint ``J``; NaN if none.

    ``f(s) = (Q(s) − J)·T`` has ``f'(s) = 3(T_x(1 + k·s²) + T_y·m·s²) > 0`` for the directions
    used here, so a sign change over ``[0, 1]`` brackets its only root. Up to
    ``FLOAT_ELEMENTS`` joints are solved one by one in floats, with the same result.
    """
    tx, ty = np.cos(phi), np.sin(phi)
    shape = np.broadcast_shapes(k.shape, m.shape, jx.shape, jy.shape, phi.shape)
    if math.prod(shape) > FLOAT_ELEMENTS:
        return _joint_split_arrays(k, m, jx, jy, tx, ty)
    columns = [np.broadcast_to(v, shape).ravel().tolist() for v in (k, m, jx, jy, tx, ty)]
    splits = [one_joint_split(*args) for args in zip(*columns, strict=True)]
    return np.array(splits, dtype=np.float64).reshape(shape)


def one_joint_split(k: float, m: float, jx: float, jy: float, tx: float, ty: float) -> float:
    """:func:`joint_split` of one joint, given ``tx, ty = np.cos(φ), np.sin(φ)``: in floats,
    or by the arrays where the float restatement hands the joint back."""
    try:
        return fewest_exact_one.joint_split(k, m, jx, jy, tx, ty)
    except fewest_exact_one.HandBackError:
        return float(_joint_split_arrays(*(np.array([v]) for v in (k, m, jx, jy, tx, ty)))[0])


def _joint_split_arrays(
    k: FloatArray, m: FloatArray, jx: FloatArray, jy: FloatArray, tx: FloatArray, ty: FloatArray
) -> FloatArray:
    """:func:`joint_split` by the arrays, given the direction's cosine and sine (one shape)."""

    def f(s: FloatArray) -> tuple[FloatArray, FloatArray]:
        s2 = s * s
        value = (s * (3.0 + k * s2) - jx) * tx + (m * s2 * s - jy) * ty
        return value, 3.0 * (tx * (1.0 + k * s2) + ty * m * s2)

    lo, hi = np.zeros_like(jx), np.ones_like(jx)
    f_lo, f_hi = f(lo)[0], f(hi)[0]
    ok = (f_lo <= 0.0) & (f_hi >= 0.0) & (f(lo)[1] > 0.0) & (f(hi)[1] > 0.0)
    s = np.full_like(jx, np.nan)
    if ok.any():
        kk, mm, xx, yy, cx, cy = k[ok], m[ok], jx[ok], jy[ok], tx[ok], ty[ok]

        def g(v: FloatArray) -> tuple[FloatArray, FloatArray]:
            v2 = v * v
            value = (v * (3.0 + kk * v2) - xx) * cx + (mm * v2 * v - yy) * cy
            return value, 3.0 * (cx * (1.0 + kk * v2) + cy * mm * v2)

        start = np.clip(xx / 3.0, 0.0, 1.0)
        s[ok] = bracketed_newton(g, lo[ok], hi[ok], start)
    return s


def split_guess(
    k: FloatArray,
    m: FloatArray,
    gx: FloatArray,
    gy: FloatArray,
    tx: FloatArray,
    ty: FloatArray,
    u0: FloatArray,
    u1: FloatArray,
    start: FloatArray | None = None,
) -> FloatArray:
    """Screening's split parameter of a joint of direction ``T = (tx, ty)``: plain Newton steps
    on ``(Q(s) − G)·T`` from the piece's middle or ``start`` (the proof recomputes it with
    :func:`joint_split`); NaN if it leaves the piece ``(u0, u1)``."""
    # (Q(s) − G)·T = a·s³ + 3·t_x·s − G·T with a = k·t_x + m·t_y: a few operations a step.
    a = k * tx + m * ty
    b = 3.0 * tx
    c = gx * tx + gy * ty
    a3 = 3.0 * a
    s = 0.5 * (u0 + u1) if start is None else start
    for _ in range(SPLIT_STEPS):
        s2 = s * s
        s = s - (s * (a * s2 + b) - c) / (a3 * s2 + b)
    result: FloatArray = np.where((s > u0) & (s < u1), s, np.nan)
    return result


def screen_radial(
    k: FloatArray,
    m: FloatArray,
    jx: FloatArray,
    jy: FloatArray,
    nx: FloatArray,
    ny: FloatArray,
    kappa: FloatArray,
    u: FloatArray,
) -> FloatArray:
    """Screening's ``|‖Q(u) − C‖ − r|``: with ``P = Q − J`` and ``d = ‖Q − C‖ = r + s``,
    ``ν = κ‖P‖² − 2P·N = s·(2 + κs)``, so ``|s| = |ν| / (1 + √(1 + κν))`` (one square root,
    no ``hypot``; exact in exact arithmetic)."""
    # In-place arithmetic: this runs on every screened sample, and temporaries cost more
    # than the arithmetic at these array sizes.
    u2 = u * u
    px = k * u2
    px += 3.0
    px *= u
    px -= jx
    py = m * u2
    py *= u
    py -= jy
    nu = px * px
    nu += py * py
    nu *= kappa
    px *= nx
    py *= ny
    px += py
    px *= 2.0
    nu -= px
    root = kappa * nu
    root += 1.0
    np.abs(root, out=root)
    np.sqrt(root, out=root)
    root += 1.0
    np.abs(nu, out=nu)
    nu /= root
    result: FloatArray = nu
    return result


def arc_deviation(
    k: FloatArray,
    m: FloatArray,
    jx: FloatArray,
    jy: FloatArray,
    phi: FloatArray,
    kappa: FloatArray,
    ex: FloatArray,
    ey: FloatArray,
    s_lo: FloatArray,
    s_hi: FloatArray,
    tolerance: Float,
) -> ArcDeviation:
    """Exact deviation of arcs from ``J = (jx, jy)`` to ``E = (ex, ey)`` over ``[s_lo, s_hi]``.

    Arcs so flat that their world centre (``radius/tolerance`` beyond ``1/(CENTRE_ULPS·eps)``)
    cannot be written in double precision to a small fraction of the tolerance are refused
    (``inf``): the numbers handed out would not carry the guarantee. ``u`` is meaningful
    only where the value is finite.

    Up to ``FLOAT_ELEMENTS`` arcs are measured one by one in floats, with the same result.
    """
    n = jx.shape[0]
    tol = np.broadcast_to(np.asarray(tolerance, dtype=np.float64), jx.shape)
    if n > FLOAT_ELEMENTS:
        return _arc_deviation_arrays(k, m, jx, jy, phi, kappa, ex, ey, s_lo, s_hi, tol)
    tx, ty = np.cos(phi), np.sin(phi)
    value, u = np.empty(n), np.empty(n)
    columns = (k, m, jx, jy, phi, tx, ty, kappa, ex, ey, s_lo, s_hi, tol)
    for i, args in enumerate(zip(*(c.tolist() for c in columns), strict=True)):
        value[i], u[i] = one_arc_deviation(*args)
    return ArcDeviation(value=value, u=u)


def one_arc_deviation(
    k: float,
    m: float,
    jx: float,
    jy: float,
    phi: float,
    tx: float,
    ty: float,
    kappa: float,
    ex: float,
    ey: float,
    s_lo: float,
    s_hi: float,
    tolerance: float,
) -> tuple[float, float]:
    """:func:`arc_deviation` of one arc, ``(value, u)``, given ``tx, ty = np.cos(φ), np.sin(φ)``:
    in floats, or by the arrays where the float restatement hands the arc back."""
    one = fewest_exact_one.arc_deviation(k, m, jx, jy, tx, ty, kappa, ex, ey, s_lo, s_hi, tolerance)
    if one is not None:
        return one
    d = _arc_deviation_arrays(
        *(np.array([v]) for v in (k, m, jx, jy, phi, kappa, ex, ey, s_lo, s_hi, tolerance))
    )
    return float(d.value[0]), float(d.u[0])


def _arc_deviation_arrays(
    k: FloatArray,
    m: FloatArray,
    jx: FloatArray,
    jy: FloatArray,
    phi: FloatArray,
    kappa: FloatArray,
    ex: FloatArray,
    ey: FloatArray,
    s_lo: FloatArray,
    s_hi: FloatArray,
    tolerance: FloatArray,
) -> ArcDeviation:
    # A piece outside the spiral's [0, 1] is none of its pieces (the chains' pieces tile it).
    valid = (s_lo >= 0.0) & (s_hi <= 1.0)
    valid &= _is_graph(k, m, jx, jy, phi, kappa, ex, ey, s_lo, s_hi)
    valid &= (kappa == 0.0) | (np.abs(kappa) * tolerance >= CENTRE_ULPS * _EPS)
    nx, ny = -np.sin(phi), np.cos(phi)
    coeffs = np.zeros((jx.shape[0], 6))
    coeffs[:, 0] = -kappa * jx - nx
    coeffs[:, 1] = 3.0 * kappa
    coeffs[:, 2] = -kappa * (k * jx + m * jy) - (k * nx + m * ny)
    coeffs[:, 3] = 4.0 * k * kappa
    coeffs[:, 5] = kappa * (k * k + m * m)
    points = _cascade_roots(coeffs, s_lo, s_hi, valid)
    n = points.shape[1]
    e = radial(
        np.repeat(k, n),
        np.repeat(m, n),
        np.repeat(jx, n),
        np.repeat(jy, n),
        np.repeat(phi, n),
        np.repeat(kappa, n),
        points.ravel(),
    ).reshape(points.shape)
    worst = np.argmax(e, axis=1)
    rows = np.arange(points.shape[0])
    value = np.where(valid, e[rows, worst], np.inf)
    return ArcDeviation(value=value, u=points[rows, worst])


def _is_graph(
    k: FloatArray,
    m: FloatArray,
    jx: FloatArray,
    jy: FloatArray,
    phi: FloatArray,
    kappa: FloatArray,
    ex: FloatArray,
    ey: FloatArray,
    s_lo: FloatArray,
    s_hi: FloatArray,
) -> BoolArray:
    """Both conditions of the module text, exactly (the cubic ``w`` and the ray sides)."""
    tx, ty = np.cos(phi), np.sin(phi)
    nx, ny = -ty, tx
    w0 = kappa * jy + tx
    w2 = kappa * (k * jy - m * jx) + k * tx + m * ty
    w3 = 2.0 * m * kappa

    def w(u: FloatArray) -> FloatArray:
        result: FloatArray = w0 + u * u * (w2 + w3 * u)
        return result

    with np.errstate(divide="ignore", invalid="ignore"):
        critical = np.where(w3 != 0.0, -w2 / (1.5 * w3), s_lo)
    inside = (critical > s_lo) & (critical < s_hi)
    w_min = np.minimum(w(s_lo), w(s_hi))
    w_min = np.where(inside, np.minimum(w_min, w(np.where(inside, critical, s_lo))), w_min)
    dx, dy = kappa * (ex - jx) - nx, kappa * (ey - jy) - ny
    ok = (w_min > 0.0) & (s_hi > s_lo)
    for s in (s_lo, s_hi):
        s2 = s * s
        px = kappa * (s * (3.0 + k * s2) - jx) - nx
        py = kappa * (m * s2 * s - jy) - ny
        ok &= px * dx + py * dy > 0.0
    return ok


def _cascade_roots(
    coeffs: FloatArray, lo: FloatArray, hi: FloatArray, valid: BoolArray
) -> FloatArray:
    """Every root in ``[lo, hi]`` of each row's polynomial (ascending ``coeffs``, degree 5),
    plus the ends and the roots of its derivatives, sorted per row (repeats moved to the end).
    Rows not ``valid`` (refused whatever their roots) do not decide the shortcut below, so
    that a valid row's roots do not depend on the others.

    Each level adds at most one point per interval, see the module text.
    """
    derivatives = [coeffs]
    for _ in range(5):
        c = derivatives[-1]
        derivatives.append(c[:, 1:] * np.arange(1, c.shape[1]))
    points = np.stack([lo, hi], axis=1)
    # h⁽⁴⁾ = 120·c5·u + 24·c4 vanishes only at u = 0 when c4 = 0 (always, for this quintic),
    # so on pieces with lo ≥ 0 it has no interior root and the level can be skipped.
    skip_top = bool(np.all(coeffs[:, 4] == 0.0)) and bool(np.all(lo[valid] >= 0.0))
    for level in _LEVELS[1:] if skip_top else _LEVELS:
        c = derivatives[level]
        f = _horner(c, points)
        a, fa, fb = points[:, :-1], f[:, :-1], f[:, 1:]
        b = points[:, 1:]
        bracketed = ((fa < 0.0) & (fb > 0.0)) | ((fa > 0.0) & (fb < 0.0))
        roots = a.copy()
        rows, cols = np.nonzero(bracketed)
        if rows.size and level == 3 and skip_top:
            # The third derivative is 6·c3 + 60·c5·u² (c4 = 0): its root in u > 0 in closed form.
            with np.errstate(invalid="ignore", divide="ignore"):
                root = np.sqrt(-c[rows, 0] / c[rows, 2])
            roots[rows, cols] = np.clip(root, a[rows, cols], b[rows, cols])
        elif rows.size:
            cr = c[rows]
            dc = (
                derivatives[level + 1][rows] if level < 4 else cr[:, 1:] * np.arange(1, cr.shape[1])
            )

            # Not oriented: Newton's steps f/f' do not depend on the sign, and the safeguarded
            # iteration orients each element itself.
            def fn(
                x: FloatArray, cr: FloatArray = cr, dc: FloatArray = dc
            ) -> tuple[FloatArray, FloatArray]:
                return _horner(cr, x), _horner(dc, x)

            a_w, b_w = a[rows, cols], b[rows, cols]
            fa_w, fb_w = fa[rows, cols], fb[rows, cols]
            secant = a_w + (b_w - a_w) * fa_w / (fa_w - fb_w)
            roots[rows, cols] = bracketed_newton(fn, a_w, b_w, secant)
        # A monotone piece holds at most one root, so one new point per level suffices only
        # per piece; keep all pieces' roots (duplicates of ``a`` where there is none).
        points = _distinct(np.concatenate([points, roots], axis=1), hi)
    return points


def _distinct(points: FloatArray, hi: FloatArray) -> FloatArray:
    """``points`` sorted per row with repeated values moved to the end as copies of ``hi``
    (zero-width intervals, which never bracket a root), and columns that are such copies in
    every row dropped. Each row keeps the same set of values, so its roots do not depend on
    the other rows."""
    points = np.sort(points, axis=1)
    repeat = np.zeros(points.shape, dtype=bool)
    repeat[:, 1:] = points[:, 1:] == points[:, :-1]
    points = np.sort(np.where(repeat, np.inf, points), axis=1)
    width = int((~repeat).sum(axis=1).max())
    points = points[:, :width]
    result: FloatArray = np.where(np.isinf(points), hi[:, None], points)
    return result


def _horner(c: FloatArray, x: FloatArray) -> FloatArray:
    """Ascending coefficients ``c`` (rows, degree+1) at ``x`` (rows,) or (rows, j)."""
    columns = c.T.reshape(c.shape[::-1] + (1,) * (x.ndim - 1))
    if len(columns) == 1:
        return np.broadcast_to(columns[0], x.shape).copy()
    # The first step ``c_d·x + c_(d−1)`` starts the array (a broadcast copy of ``c_d`` to
    # multiply in place costs more, on these many small calls): the same operations.
    result: FloatArray = columns[-1] * x
    result += columns[-2]
    for cj in columns[-3::-1]:
        result *= x
        result += cj
    return result
