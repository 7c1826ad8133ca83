"""The Newton step of ``fewest-arcs``: the next biarc from the previous one, by Newton's method.

Between the join parameters where each arc's deviation is least, the first arc's deviation
grows with ``λ`` and the second's shrinks, so the longest biarc within the tolerance is where
both reach it — two smooth equations in ``x = (log(u1 − u0), λ)`` — and along a spiral the
solution and its Jacobian change slowly. :func:`newton_many` solves them for the rows of a
batch in lockstep with numpy; :func:`newton_one` restates it for one row in Python floats,
operation for operation (exponentials and logarithms are numpy's own), bit for bit the same
(tests/geometry/test_fewest_newton.py); :func:`newton_step` takes whichever is cheaper.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np
import numpy.typing as npt

from .fewest_biarc import (
    LAMBDA_MARGIN,
    Biarc,
    SabinBiarcs,
    numpy_divide,
    sabin_biarc_one,
    sabin_biarcs,
    verify,
    verify_one,
)
from .fewest_exact_one import _maximum
from .types import BoolArray, FloatArray

#: The Newton step (see :func:`newton_many`): both arcs aim at this fraction of the tolerance;
#: a proven biarc whose larger deviation reaches ``NEWTON_ACCEPT`` of it ends the iteration;
#: after ``NEWTON_ITERATIONS`` the longest proven one is kept if it reaches ``NEWTON_FLOOR``,
#: else the row is searched by the grids.
NEWTON_TARGET = 0.995
NEWTON_ACCEPT = 0.97
NEWTON_FLOOR = 0.9
NEWTON_ITERATIONS = 6
#: Largest Newton step in ``log(span)`` and in ``λ``.
NEWTON_MAX_LOG_STEP = 0.5
NEWTON_MAX_LAMBDA_STEP = 0.1
#: The first Jacobian of the residuals ``log(dev_i / target)`` in ``(log span, λ)``: a
#: deviation grows about as the span cubed, and ``λ`` moves deviation from one arc to the
#: other. (Measured by finite differences on the paper's example and 200 random spirals:
#: 2.3–3.3, 11.9–13.5, 2.8–3.7, −12.1…−10.7.) Broyden's update refines it.
NEWTON_JACOBIAN = ((3.0, 12.5), (3.2, -11.5))

Devs = tuple[FloatArray, ...]


def equations(
    k: FloatArray,
    m: FloatArray,
    u0: FloatArray,
    tol: FloatArray,
    log_span: FloatArray,
    lam: FloatArray,
) -> tuple[SabinBiarcs, Devs, FloatArray, FloatArray]:
    """The biarcs of each row at ``(log(u1 − u0), λ)``, their exact deviations (as
    :func:`~arcspline.geometry.fewest_biarc.verify`), and the residuals
    ``log(dev / (NEWTON_TARGET·tol))`` of both arcs (non-finite where the biarc is invalid)."""
    u1 = u0 + np.exp(log_span)
    with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
        b = sabin_biarcs(k, m, u0, u1, lam)
        devs = verify(k, m, u0, b, tol)
        aim = NEWTON_TARGET * tol
        f0, f1 = np.log(devs[0] / aim), np.log(devs[2] / aim)
    return b, devs, f0, f1


def broyden(
    jac: FloatArray,
    rows: npt.NDArray[np.intp],
    s0: FloatArray,
    s1: FloatArray,
    df0: FloatArray,
    df1: FloatArray,
) -> None:
    """Broyden's update of ``jac[rows]`` in place after the step ``(s0, s1)`` changed the
    residuals by ``(df0, df1)``: ``J += (Δf − J·Δx)·Δxᵀ / (Δx·Δx)`` (C.G. Broyden, *A class
    of methods for solving nonlinear simultaneous equations*, Math. Comp. 19 (1965), the
    "good" update), where both changes are finite."""
    with np.errstate(invalid="ignore"):
        r0 = df0 - (jac[rows, 0, 0] * s0 + jac[rows, 0, 1] * s1)
        r1 = df1 - (jac[rows, 1, 0] * s0 + jac[rows, 1, 1] * s1)
        norm2 = s0 * s0 + s1 * s1
    usable = np.isfinite(r0) & np.isfinite(r1) & (norm2 > 0.0)
    up, r0, r1, s0, s1, norm2 = (v[usable] for v in (rows, r0, r1, s0, s1, norm2))
    jac[up, 0, 0] += r0 * s0 / norm2
    jac[up, 0, 1] += r0 * s1 / norm2
    jac[up, 1, 0] += r1 * s0 / norm2
    jac[up, 1, 1] += r1 * s1 / norm2


def newton_many(
    k: FloatArray,
    m: FloatArray,
    u0: FloatArray,
    tol: FloatArray,
    hint: FloatArray,
    lam_hint: FloatArray,
    jacobian: FloatArray,
) -> tuple[BoolArray, SabinBiarcs, Devs, FloatArray]:
    """From each row's ``u0``, the biarc whose two arcs both deviate by ``NEWTON_TARGET·tol``,
    by Newton's method on ``x = (log(u1 − u0), λ)`` from the previous piece (span ``hint``,
    join parameter ``lam_hint``), with Broyden's update of the Jacobian ``jacobian`` (rows,
    2, 2; first ``NEWTON_JACOBIAN``), which the walk carries from step to step.

    Why it works: see the module text (about two exact evaluations per step on the paper's
    example at 1e-5). Every iterate is measured exactly (``fewest_biarc.verify``), so the
    longest proven one is kept; a row is left to the grids (``found`` false) when no proven
    iterate reaches ``NEWTON_FLOOR`` of the tolerance, an iterate is invalid, or a step would
    pass the spiral's end. Returns ``found``, the biarcs, their deviations and the updated
    Jacobians."""
    n = k.size
    x0, x1 = np.log(hint), lam_hint.copy()
    jac = jacobian.copy()
    b, devs, f0, f1 = equations(k, m, u0, tol, x0, x1)
    chosen = SabinBiarcs(*(np.array(getattr(b, f)) for f in SabinBiarcs.__slots__))
    best = tuple(np.full(n, np.nan) for _ in range(4))
    best_u1 = np.full(n, -np.inf)
    active = np.ones(n, dtype=bool)
    for iteration in range(NEWTON_ITERATIONS):
        proven = active & b.ok & (devs[0] <= tol) & (devs[2] <= tol)
        better = np.flatnonzero(proven & (b.u1 > best_u1))
        for name in SabinBiarcs.__slots__:
            np.asarray(getattr(chosen, name))[better] = np.asarray(getattr(b, name))[better]
        for mine, theirs in zip(best, devs, strict=True):
            mine[better] = theirs[better]
        best_u1[better] = b.u1[better]
        worst = np.maximum(devs[0], devs[2])
        active &= ~(proven & (worst >= NEWTON_ACCEPT * tol)) & np.isfinite(f0) & np.isfinite(f1)
        if iteration == NEWTON_ITERATIONS - 1:
            break
        with np.errstate(invalid="ignore", divide="ignore"):
            det = jac[:, 0, 0] * jac[:, 1, 1] - jac[:, 0, 1] * jac[:, 1, 0]
            s0 = -(jac[:, 1, 1] * f0 - jac[:, 0, 1] * f1) / det
            s1 = -(jac[:, 0, 0] * f1 - jac[:, 1, 0] * f0) / det
        s0 = np.clip(s0, -NEWTON_MAX_LOG_STEP, NEWTON_MAX_LOG_STEP)
        s1 = np.clip(s1, -NEWTON_MAX_LAMBDA_STEP, NEWTON_MAX_LAMBDA_STEP)
        with np.errstate(over="ignore"):
            inside = u0 + np.exp(x0 + s0) < 1.0
        active &= np.isfinite(s0) & np.isfinite(s1) & inside
        rows = np.flatnonzero(active)
        if rows.size == 0:
            break
        s0, s1 = s0[rows], s1[rows]
        x0[rows], x1[rows] = x0[rows] + s0, np.clip(x1[rows] + s1, LAMBDA_MARGIN, 1 - LAMBDA_MARGIN)
        nb, nd, g0, g1 = equations(k[rows], m[rows], u0[rows], tol[rows], x0[rows], x1[rows])
        broyden(jac, rows, s0, s1, g0 - f0[rows], g1 - f1[rows])
        for name in SabinBiarcs.__slots__:
            np.asarray(getattr(b, name))[rows] = getattr(nb, name)
        for mine, theirs in zip(devs, nd, strict=True):
            mine[rows] = theirs
        f0[rows], f1[rows] = g0, g1
    found = np.isfinite(best_u1) & (np.maximum(best[0], best[2]) >= NEWTON_FLOOR * tol)
    return found, chosen, best, jac


#: Steps of at most this many rows run one row at a time in floats (:func:`newton_one`):
#: one row costs about a third of numpy's lockstep call, whatever its size.
FLOAT_ROWS = 2


def newton_step(
    k: FloatArray,
    m: FloatArray,
    u0: FloatArray,
    tol: FloatArray,
    hint: FloatArray,
    lam_hint: FloatArray,
    jacobian: FloatArray,
) -> tuple[BoolArray, SabinBiarcs, Devs, FloatArray]:
    """:func:`newton_many`, for a few rows by :func:`newton_one` instead (the same numbers)."""
    n = k.size
    if n > FLOAT_ROWS:
        return newton_many(k, m, u0, tol, hint, lam_hint, jacobian)
    columns = (k, m, u0, tol, hint, lam_hint)
    rows = [
        newton_one(kk, mm, uu, tt, hh, ll, jac)
        for (kk, mm, uu, tt, hh, ll), jac in zip(
            zip(*(c.tolist() for c in columns), strict=True), jacobian.tolist(), strict=True
        )
    ]
    found = np.array([r.found for r in rows], dtype=bool)
    chosen = SabinBiarcs.of([r.biarc for r in rows])
    devs = tuple(np.array([r.devs[i] for r in rows]) for i in range(4))
    return found, chosen, devs, np.array([r.jacobian for r in rows])


class NewtonOne(NamedTuple):
    """:func:`newton_one`'s result for its row."""

    found: bool
    biarc: Biarc
    devs: tuple[float, float, float, float]
    jacobian: list[list[float]]


def _equations_one(
    k: float, m: float, u0: float, tol: float, log_span: float, lam: float
) -> tuple[Biarc, tuple[float, float, float, float], float, float]:
    """:func:`equations` for one row."""
    u1 = u0 + float(np.exp(log_span))
    b = sabin_biarc_one(k, m, u0, u1, lam)
    devs = verify_one(k, m, u0, b, tol)
    aim = NEWTON_TARGET * tol
    with np.errstate(divide="ignore", invalid="ignore"):
        f0, f1 = np.log([devs[0] / aim, devs[2] / aim]).tolist()
    return b, devs, f0, f1


def newton_one(
    k: float,
    m: float,
    u0: float,
    tol: float,
    hint: float,
    lam_hint: float,
    jacobian: list[list[float]],
) -> NewtonOne:
    """:func:`newton_many` for one row, in floats: the same iterates, the same result."""
    x0, x1 = float(np.log(hint)), lam_hint
    (j00, j01), (j10, j11) = jacobian
    b, devs, f0, f1 = _equations_one(k, m, u0, tol, x0, x1)
    chosen, best, best_u1 = b, (math.nan,) * 4, -math.inf
    active = True
    for iteration in range(NEWTON_ITERATIONS):
        proven = active and b.ok and devs[0] <= tol and devs[2] <= tol
        if proven and b.u1 > best_u1:
            chosen, best, best_u1 = b, devs, b.u1
        worst = _maximum(devs[0], devs[2])
        accepted = proven and worst >= NEWTON_ACCEPT * tol
        if accepted or not (math.isfinite(f0) and math.isfinite(f1)):
            break
        if iteration == NEWTON_ITERATIONS - 1:
            break
        det = j00 * j11 - j01 * j10
        # Clipped before the test, as np.clip does: an infinite step becomes the largest.
        s0 = numpy_divide(-(j11 * f0 - j01 * f1), det)
        s1 = numpy_divide(-(j00 * f1 - j10 * f0), det)
        s0 = min(max(s0, -NEWTON_MAX_LOG_STEP), NEWTON_MAX_LOG_STEP)
        s1 = min(max(s1, -NEWTON_MAX_LAMBDA_STEP), NEWTON_MAX_LAMBDA_STEP)
        if not (math.isfinite(s0) and math.isfinite(s1)):
            break
        with np.errstate(over="ignore"):
            if not u0 + float(np.exp(x0 + s0)) < 1.0:
                break
        x0, x1 = x0 + s0, min(max(x1 + s1, LAMBDA_MARGIN), 1 - LAMBDA_MARGIN)
        b, devs, g0, g1 = _equations_one(k, m, u0, tol, x0, x1)
        # broyden() for this row
        r0 = (g0 - f0) - (j00 * s0 + j01 * s1)
        r1 = (g1 - f1) - (j10 * s0 + j11 * s1)
        norm2 = s0 * s0 + s1 * s1
        if math.isfinite(r0) and math.isfinite(r1) and norm2 > 0.0:
            j00 += r0 * s0 / norm2
            j01 += r0 * s1 / norm2
            j10 += r1 * s0 / norm2
            j11 += r1 * s1 / norm2
        f0, f1 = g0, g1
    found = math.isfinite(best_u1) and _maximum(best[0], best[2]) >= NEWTON_FLOOR * tol
    return NewtonOne(found, chosen, best, [[j00, j01], [j10, j11]])
