"""Sabin's-circle biarcs of ``fewest-arcs``, and their exact deviations.

From ``A0 = Q(u0)`` with the spiral's direction ``φ0`` to ``Q(u1)`` with ``φ1``, the biarcs
form a one-parameter family (M.A. Sabin, *The use of piecewise forms for the numerical
representation of shape*, 1977: the joints lie on a circle through both ends). With ``χ`` the
chord's direction, the join tangent ``ψ`` ranges over ``(2χ − φ1, 2χ − φ0)`` (the incentre
biarc is ``ψ = χ``) and is taken as ``χ − β + λ(α + β)``, ``λ ∈ (0, 1)``, ``α = χ − φ0``,
``β = φ1 − χ``. Each arc's chord runs along the mean of its end directions, so the chord
lengths solve ``A1 − A0 = L0·e((φ0 + ψ)/2) + L1·e((ψ + φ1)/2)``, the joint is
``G = A0 + L0·e((φ0 + ψ)/2)`` and the curvatures are ``κ = 2·sin(turn/2)/L``.

:func:`sabin_biarcs` and :func:`verify` work on arrays (a search's grid, a batch's rows);
:func:`sabin_biarc_one` and :func:`verify_one` restate them for one candidate in Python floats,
operation for operation, for the steps that look at one candidate at a time (numpy's
per-call overhead would cost several times the arithmetic). Arctangents, sines and cosines
are numpy's own, called on the few values at once, so every number is bit for bit the array
result (tests/geometry/test_fewest_biarc.py holds them equal).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

from . import canonical
from .fewest_exact import (
    arc_deviation,
    joint_split,
    one_arc_deviation,
    one_joint_split,
    split_guess,
)
from .types import BoolArray, FloatArray

#: Join parameters stay this far inside ``(0, 1)``.
LAMBDA_MARGIN = 1e-3


@dataclass(frozen=True, slots=True)
class SabinBiarcs:
    """Candidate biarcs from ``A0 = Q(u0)`` (shared) to ``Q(u1)``, one per element."""

    u1: FloatArray
    lam: FloatArray
    phi0: FloatArray
    psi: FloatArray
    phi1: FloatArray
    kappa0: FloatArray
    kappa1: FloatArray
    gx: FloatArray
    gy: FloatArray
    split: FloatArray
    ok: BoolArray

    @classmethod
    def of(cls, biarcs: Sequence[Biarc]) -> SabinBiarcs:
        """One element per candidate built in floats (:func:`sabin_biarc_one`)."""
        return cls(*(np.array([b[i] for b in biarcs]) for i in range(len(cls.__slots__))))


def sabin_biarcs(
    k: FloatArray,
    m: FloatArray,
    u0: FloatArray,
    u1: FloatArray,
    lam: FloatArray,
    exact: bool = True,
) -> SabinBiarcs:
    """Sabin's-circle biarcs; ``exact=False`` (screening) finds the joint's split parameter
    by a few plain Newton steps instead of the bracketed iteration. The arguments broadcast
    together (``exact`` needs them all of one shape)."""
    ax, ay = canonical.point(k, m, u0)
    dx, dy = canonical.offset(k, m, u0, u1)
    phi0 = canonical.direction_rad(k, m, u0 * u0)
    phi1 = canonical.direction_rad(k, m, u1 * u1)
    chi = np.arctan2(dy, dx)
    alpha, beta = chi - phi0, phi1 - chi
    psi = chi - beta + lam * (alpha + beta)
    h0, h1 = 0.5 * (phi0 + psi), 0.5 * (psi + phi1)
    den = np.sin(0.5 * (phi1 - phi0))
    c0, s0, c1, s1 = np.cos(h0), np.sin(h0), np.cos(h1), np.sin(h1)
    with np.errstate(divide="ignore", invalid="ignore"):
        len0 = (dx * s1 - dy * c1) / den
        len1 = (c0 * dy - s0 * dx) / den
        kappa0 = 2.0 * np.sin(0.5 * (psi - phi0)) / len0
        kappa1 = 2.0 * np.sin(0.5 * (phi1 - psi)) / len1
    gx, gy = ax + len0 * c0, ay + len0 * s0
    ok = (len0 > 0.0) & (len1 > 0.0) & np.isfinite(kappa0) & np.isfinite(kappa1)
    if exact:
        split = joint_split(k, m, gx, gy, psi)
    else:
        split = split_guess(k, m, gx, gy, np.cos(psi), np.sin(psi), u0, u1)
    ok &= (split > u0) & (split < u1)
    return SabinBiarcs(u1, lam, phi0, psi, phi1, kappa0, kappa1, gx, gy, split, ok)


def verify(
    k: FloatArray, m: FloatArray, u0: FloatArray, b: SabinBiarcs, tol: FloatArray
) -> tuple[FloatArray, ...]:
    """Exact deviations of both arcs of each candidate: ``(dev0, u0_at, dev1, u1_at)``."""
    n = b.u1.shape[0]
    ax, ay = canonical.point(k, m, u0)
    bx, by = canonical.point(k, m, b.u1)
    d = arc_deviation(
        np.concatenate([k, k]),
        np.concatenate([m, m]),
        np.concatenate([ax, b.gx]),
        np.concatenate([ay, b.gy]),
        np.concatenate([b.phi0, b.psi]),
        np.concatenate([b.kappa0, b.kappa1]),
        np.concatenate([b.gx, bx]),
        np.concatenate([b.gy, by]),
        np.concatenate([u0, b.split]),
        np.concatenate([b.split, b.u1]),
        np.concatenate([tol, tol]),
    )
    value = np.where(np.concatenate([b.ok, b.ok]), d.value, np.inf)
    return value[:n], d.u[:n], value[n:], d.u[n:]


class Biarc(NamedTuple):
    """One candidate of :class:`SabinBiarcs` in floats, with the cosines and sines of its two
    start directions (``φ0`` and ``ψ``) that its proof needs."""

    u1: float
    lam: float
    phi0: float
    psi: float
    phi1: float
    kappa0: float
    kappa1: float
    gx: float
    gy: float
    split: float
    ok: bool
    cos_phi0: float
    sin_phi0: float
    cos_psi: float
    sin_psi: float


#: A candidate that was never built: what a row without a result carries (never read).
NO_BIARC = Biarc(*(math.nan,) * 10, False, *(math.nan,) * 4)


def numpy_divide(a: float, b: float) -> float:
    """``a / b`` as numpy divides, bit for bit: ``±inf`` or NaN by zero, not an exception."""
    if b != 0.0:
        return a / b
    if a != a:
        return a
    if a == 0.0:
        return 0.0 * math.inf  # the processor's default NaN, as its 0/0 gives
    return math.copysign(math.inf, a) * math.copysign(1.0, b)


def sabin_biarc_one(k: float, m: float, u0: float, u1: float, lam: float) -> Biarc:
    """:func:`sabin_biarcs` (``exact=True``) for one candidate, in floats."""
    u2 = u0 * u0
    ax, ay = u0 * (3.0 + k * u2), m * u2 * u0
    h = u1 - u0
    sigma = u1 * u1 + u1 * u0 + u0 * u0
    dx, dy = h * (3.0 + k * sigma), h * m * sigma
    w0, w1 = u0 * u0, u1 * u1
    phi0, phi1, chi = np.arctan2([m * w0, m * w1, dy], [1.0 + k * w0, 1.0 + k * w1, dx]).tolist()
    alpha, beta = chi - phi0, phi1 - chi
    psi = chi - beta + lam * (alpha + beta)
    h0, h1 = 0.5 * (phi0 + psi), 0.5 * (psi + phi1)
    half_turn, s0, s1, half_a, half_b, sin_psi, sin_phi0 = np.sin(
        [0.5 * (phi1 - phi0), h0, h1, 0.5 * (psi - phi0), 0.5 * (phi1 - psi), psi, phi0]
    ).tolist()
    c0, c1, cos_psi, cos_phi0 = np.cos([h0, h1, psi, phi0]).tolist()
    len0 = numpy_divide(dx * s1 - dy * c1, half_turn)
    len1 = numpy_divide(c0 * dy - s0 * dx, half_turn)
    kappa0 = numpy_divide(2.0 * half_a, len0)
    kappa1 = numpy_divide(2.0 * half_b, len1)
    gx, gy = ax + len0 * c0, ay + len0 * s0
    ok = len0 > 0.0 and len1 > 0.0 and math.isfinite(kappa0) and math.isfinite(kappa1)
    split = one_joint_split(k, m, gx, gy, cos_psi, sin_psi)
    ok = ok and u0 < split < u1
    return Biarc(
        u1, lam, phi0, psi, phi1, kappa0, kappa1, gx, gy, split, ok,
        cos_phi0, sin_phi0, cos_psi, sin_psi,
    )  # fmt: skip


def verify_one(
    k: float, m: float, u0: float, b: Biarc, tol: float, *, lazily: bool = False
) -> tuple[float, float, float, float]:
    """:func:`verify` for one candidate: ``(dev0, u0_at, dev1, u1_at)``; an invalid biarc is
    not measured (``inf``, where its ``u`` means nothing), nor, ``lazily``, the second arc of
    a biarc whose first arc is out of the tolerance (NaN)."""
    if not b.ok:
        return math.inf, u0, math.inf, b.split
    u2, v2 = u0 * u0, b.u1 * b.u1
    ax, ay = u0 * (3.0 + k * u2), m * u2 * u0
    bx, by = b.u1 * (3.0 + k * v2), m * v2 * b.u1
    d0, w0 = one_arc_deviation(
        k, m, ax, ay, b.phi0, b.cos_phi0, b.sin_phi0, b.kappa0, b.gx, b.gy, u0, b.split, tol
    )
    if lazily and not d0 <= tol:
        return d0, w0, math.nan, math.nan
    d1, w1 = one_arc_deviation(
        k, m, b.gx, b.gy, b.psi, b.cos_psi, b.sin_psi, b.kappa1, bx, by, b.split, b.u1, tol
    )
    return d0, w0, d1, w1
