"""Merging the last two biarcs of a ``fewest-arcs`` chain into three arcs (a "triarc").

Greedy longest biarcs leave a short last biarc; the last two biarcs then span about one and a
half biarcs' worth of spiral, which three arcs whose middle joint lies *off* the spiral can
often cover. The triarc from ``A = Q(u_a)`` (spiral tangent ``φ_a``) to ``B = Q(1)`` (``φ_1``)
has three free parameters:

* its first joint ``J1 = Q(v) + δ·N(v)``, anywhere in the ±tolerance band (``N`` the spiral's
  unit normal); arc 0 is the arc tangent to ``φ_a`` at ``A`` through ``J1``, so it arrives with
  direction ``ψ1 = 2χ0 − φ_a`` (``χ0`` the direction of ``J1 − A``);
* the join parameter ``λ`` of the biarc from ``(J1, ψ1)`` to ``(B, φ_1)`` (Sabin's family, as in
  :mod:`service.geometry.fewest`).

The search minimises the sampled deviation (a lower bound) over a grid refined by pattern
search; the winner is kept only if :func:`service.geometry.fewest_exact.arc_deviation` proves
all three arcs within the tolerance, so the guarantee is the same as for the biarcs.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from . import canonical
from .fewest_exact import arc_deviation, joint_split, radial
from .types import BoolArray, FloatArray

_SAMPLES = 16
_T = (np.arange(_SAMPLES) + 0.5) / _SAMPLES
#: Pattern-search rounds and points per axis of each round.
_ROUNDS = 8
_AXIS = 5


@dataclass(frozen=True, slots=True)
class Triarc:
    """Three G1 arcs from ``Q(u_a)`` to ``Q(1)``: joints 0…3 (``x``, ``y``, ``phi``: shape
    ``(n, 4)``), curvatures ``kappa`` and split parameters ``s`` (``(n, 3)``, ``(n, 4)``)."""

    x: FloatArray
    y: FloatArray
    phi: FloatArray
    kappa: FloatArray
    s: FloatArray
    ok: BoolArray


def _triarcs(
    k: float, m: float, ua: float, v: FloatArray, delta: FloatArray, lam: FloatArray
) -> Triarc:
    n = v.shape[0]
    ax, ay = (float(c) for c in canonical.point(k, m, ua))
    phi_a = float(canonical.direction_rad(k, m, ua * ua))
    phi_b = float(canonical.direction_rad(k, m, 1.0))
    bx, by = (float(c) for c in canonical.point(k, m, 1.0))
    tv = canonical.direction_rad(k, m, v * v)
    nx, ny = -np.sin(tv), np.cos(tv)
    ox, oy = canonical.offset(k, m, ua, v)
    cx, cy = ox + delta * nx, oy + delta * ny
    chi0 = np.arctan2(cy, cx)
    psi1 = 2.0 * chi0 - phi_a
    kappa0 = 2.0 * np.sin(chi0 - phi_a) / np.hypot(cx, cy)
    jx, jy = ax + cx, ay + cy
    dx, dy = canonical.offset(k, m, v, 1.0)
    dx, dy = dx - delta * nx, dy - delta * ny
    chi = np.arctan2(dy, dx)
    alpha, beta = chi - psi1, phi_b - chi
    psi2 = chi - beta + lam * (alpha + beta)
    h0, h1 = 0.5 * (psi1 + psi2), 0.5 * (psi2 + phi_b)
    den = np.sin(0.5 * (phi_b - psi1))
    with np.errstate(divide="ignore", invalid="ignore"):
        len0 = (dx * np.sin(h1) - dy * np.cos(h1)) / den
        len1 = (np.cos(h0) * dy - np.sin(h0) * dx) / den
        kappa1 = 2.0 * np.sin(0.5 * (psi2 - psi1)) / len0
        kappa2 = 2.0 * np.sin(0.5 * (phi_b - psi2)) / len1
    gx, gy = jx + len0 * np.cos(h0), jy + len0 * np.sin(h0)
    kk, mm = np.full(n, k), np.full(n, m)
    s1 = joint_split(kk, mm, jx, jy, psi1)
    s2 = joint_split(kk, mm, gx, gy, psi2)
    ok = (den > 0.0) & (len0 > 0.0) & (len1 > 0.0) & (s1 > ua) & (s2 > s1) & (s2 < 1.0)
    ok &= np.isfinite(kappa1) & np.isfinite(kappa2)
    full = np.full(n, 1.0)
    return Triarc(
        x=np.stack([full * ax, jx, gx, full * bx], axis=1),
        y=np.stack([full * ay, jy, gy, full * by], axis=1),
        phi=np.stack([full * phi_a, psi1, psi2, full * phi_b], axis=1),
        kappa=np.stack([kappa0, kappa1, kappa2], axis=1),
        s=np.stack([full * ua, s1, s2, full], axis=1),
        ok=ok,
    )


def _screen(k: float, m: float, t: Triarc) -> FloatArray:
    with np.errstate(invalid="ignore"):  # invalid candidates are NaN, then masked as inf
        return _sampled(k, m, t)


def _sampled(k: float, m: float, t: Triarc) -> FloatArray:
    s = np.where(t.ok[:, None], t.s, np.linspace(0.0, 1.0, 4)[None, :])
    worst = np.zeros(t.ok.shape[0])
    for i in range(3):
        u = s[:, i, None] + (s[:, i + 1] - s[:, i])[:, None] * _T[None, :]
        e = radial(
            k, m, t.x[:, i, None], t.y[:, i, None], t.phi[:, i, None], t.kappa[:, i, None], u
        )
        worst = np.maximum(worst, e.max(axis=1))
    return np.where(t.ok, worst, np.inf)


def best_triarc(
    k: float, m: float, ua: float, tol: float
) -> tuple[Triarc, FloatArray, FloatArray] | None:
    """A proven triarc over ``[ua, 1]`` within ``tol``: ``(triarc, dev (3,), u_dev (3,))``."""
    span = 1.0 - ua
    v_axis = ua + span * np.linspace(0.15, 0.7, 8)
    d_axis = tol * np.linspace(-1.0, 1.0, 5)
    l_axis = np.linspace(0.05, 0.95, 9)
    vv, dd, ll = (a.ravel() for a in np.meshgrid(v_axis, d_axis, l_axis, indexing="ij"))
    score = _screen(k, m, _triarcs(k, m, ua, vv, dd, ll))
    best = int(np.argmin(score))
    centre = np.array([vv[best], dd[best], ll[best]])
    width = np.array([span * 0.07, tol * 0.5, 0.1])
    steps = np.linspace(-1.0, 1.0, _AXIS)
    best_score = float(score[best])
    for _ in range(_ROUNDS):
        grids = [centre[i] + width[i] * steps for i in range(3)]
        vv, dd, ll = (a.ravel() for a in np.meshgrid(*grids, indexing="ij"))
        vv = np.clip(vv, ua + 1e-9 * span, 1.0 - 1e-9 * span)
        score = _screen(k, m, _triarcs(k, m, ua, vv, dd, ll))
        best = int(np.argmin(score))
        if score[best] < best_score:
            best_score = float(score[best])
            centre = np.array([vv[best], dd[best], ll[best]])
        width *= 0.5
    if not best_score <= 0.999 * tol:
        return None
    t = _triarcs(k, m, ua, centre[:1], centre[1:2], centre[2:])
    if not t.ok[0]:
        return None
    d = arc_deviation(
        np.full(3, k),
        np.full(3, m),
        t.x[0, :3],
        t.y[0, :3],
        t.phi[0, :3],
        t.kappa[0],
        t.x[0, 1:],
        t.y[0, 1:],
        t.s[0, :3],
        t.s[0, 1:],
        tol,
    )
    if not np.all(d.value <= tol):
        return None
    return t, d.value, d.u
