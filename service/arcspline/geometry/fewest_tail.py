"""Merging the last two biarcs of a ``fewest-arcs`` chain into three arcs (a "triarc").

Greedy longest biarcs leave a short last biarc; the last two biarcs then span about one and a
half biarcs' worth of spiral, which three arcs whose middle joint lies *off* the spiral can
often cover. (The walk tries it from the start of a biarc that ends near the spiral's end,
before the last step: see :func:`arcspline.geometry.fewest.fewest_chains`.) The triarc from
``A = Q(u_a)`` (spiral tangent ``φ_a``) to ``B = Q(1)`` (``φ_1``) has three free parameters:

* its first joint ``J1 = Q(v) + δ·N(v)``, anywhere in the ±tolerance band (``N`` the spiral's
  unit normal); arc 0 is the arc tangent to ``φ_a`` at ``A`` through ``J1``, so it arrives with
  direction ``ψ1 = 2χ0 − φ_a`` (``χ0`` the direction of ``J1 − A``);
* the join parameter ``λ`` of the biarc from ``(J1, ψ1)`` to ``(B, φ_1)`` (Sabin's family, as in
  :mod:`arcspline.geometry.fewest`).

The search minimises the sampled deviation (a lower bound) over a grid refined by pattern
search; the winner is kept only if :func:`arcspline.geometry.fewest_exact.arc_deviation` proves
all three arcs within the tolerance, so the guarantee is the same as for the biarcs.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

from . import canonical
from .fewest_biarc import numpy_divide
from .fewest_exact import (
    arc_deviation,
    joint_split,
    one_arc_deviation,
    one_joint_split,
    screen_radial,
    split_guess,
)
from .types import BoolArray, FloatArray

_SAMPLES = 8
_T = (np.arange(_SAMPLES) + 0.5) / _SAMPLES
#: Samples per arc on the first grid, which only picks the pattern search's start.
_COARSE_SAMPLES = 5
_COARSE_T = (np.arange(_COARSE_SAMPLES) + 0.5) / _COARSE_SAMPLES
#: Pattern-search rounds and points per axis of each round.
_ROUNDS = 8
_AXIS = 4
_SHRINK = 0.55
#: The first grid's points along ``v``, ``δ`` and ``λ``.
#: The first joint starts on the spiral (``δ = 0``): on 200 random spirals 79 of the 81
#: proven triarcs started from such a point of the former ``δ ∈ {−tol, 0, tol}`` grid. A third
#: of its cost; on 2000 random spirals 7 counts changed by one arc, 4 down and 3 up. The
#: pattern search moves the joint off the spiral.
_GRID = (6, 1, 7)
#: Rows whose screened deviation is below this fraction of the tolerance stop refining (the
#: proof follows); rows above this multiple after the first grid are given up (on 400 random
#: spirals every triarc that was proven started below 1.9 times the tolerance).
_GOOD = 0.97
_HOPELESS = 2.5
_HOPELESS_DECAY = 0.6
#: One spiral's winner is built and proven in floats (:func:`triarc_one`), the same numbers.
PROVE_ONE_IN_FLOATS = True


def _lattice(*axes: FloatArray) -> FloatArray:
    """Every combination of the axes' values, one per row (the first axis slowest)."""
    return np.stack([a.ravel() for a in np.meshgrid(*axes, indexing="ij")], axis=1)


#: The first grid in units of the span, the tolerance and λ; the pattern search's moves.
_UNIT = _lattice(
    np.linspace(0.15, 0.7, _GRID[0]),
    np.zeros(_GRID[1]),
    np.linspace(0.05, 0.95, _GRID[2]),
)
_CUBE = _lattice(*(np.linspace(-1.0, 1.0, _AXIS),) * 3)


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
    k: FloatArray,
    m: FloatArray,
    ua: FloatArray,
    v: FloatArray,
    delta: FloatArray,
    lam: FloatArray,
    exact: bool = True,
) -> Triarc:
    """Candidate triarcs, one per element (all arguments of the same shape); ``exact=False``
    (screening) guesses the joints' split parameters by a few Newton steps."""
    return _directed_triarcs(k, m, ua, v, delta, lam, exact)[0]


def _directed_triarcs(
    k: FloatArray,
    m: FloatArray,
    ua: FloatArray,
    v: FloatArray,
    delta: FloatArray,
    lam: FloatArray,
    exact: bool,
) -> tuple[Triarc, FloatArray, FloatArray]:
    """:func:`_triarcs`, with the cosines and sines of the three arcs' start directions
    (``(N, 3)``, for screening). The arguments broadcast: a row's own values (``k``, ``m``,
    ``ua`` of shape ``(n, 1)``) are computed once for its candidates (``(n, G)``); the result
    has one element per candidate, row after row."""
    ax, ay = canonical.point(k, m, ua)
    phi_a = canonical.direction_rad(k, m, ua * ua)
    one = np.ones_like(k)
    phi_b = canonical.direction_rad(k, m, one)
    bx, by = canonical.point(k, m, one)
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
    c0, s0 = np.cos(h0), np.sin(h0)
    with np.errstate(divide="ignore", invalid="ignore"):
        len0 = (dx * np.sin(h1) - dy * np.cos(h1)) / den
        len1 = (c0 * dy - s0 * dx) / den
        kappa1 = 2.0 * np.sin(0.5 * (psi2 - psi1)) / len0
        kappa2 = 2.0 * np.sin(0.5 * (phi_b - psi2)) / len1
    gx, gy = jx + len0 * c0, jy + len0 * s0
    cos1, sin1, cos2, sin2 = np.cos(psi1), np.sin(psi1), np.cos(psi2), np.sin(psi2)
    if exact:
        s1 = joint_split(k, m, jx, jy, psi1)
        s2 = joint_split(k, m, gx, gy, psi2)
    else:
        s1 = split_guess(k, m, jx, jy, cos1, sin1, ua, one, start=v)
        s2 = split_guess(k, m, gx, gy, cos2, sin2, ua, one)
    ok = (den > 0.0) & (len0 > 0.0) & (len1 > 0.0) & (s1 > ua) & (s2 > s1) & (s2 < 1.0)
    ok &= np.isfinite(kappa1) & np.isfinite(kappa2)
    shape = np.broadcast_shapes(k.shape, v.shape)

    def joined(*parts: FloatArray) -> FloatArray:
        out = np.empty((*shape, len(parts)))
        for j, part in enumerate(parts):
            out[..., j] = part
        return out.reshape(-1, len(parts))

    triarc = Triarc(
        x=joined(ax, jx, gx, bx),
        y=joined(ay, jy, gy, by),
        phi=joined(phi_a, psi1, psi2, phi_b),
        kappa=joined(kappa0, kappa1, kappa2),
        s=joined(ua, s1, s2, one),
        ok=ok.ravel(),
    )
    return triarc, joined(np.cos(phi_a), cos1, cos2), joined(np.sin(phi_a), sin1, sin2)


def _sampled(
    k: FloatArray,
    m: FloatArray,
    t: Triarc,
    cos_phi: FloatArray,
    sin_phi: FloatArray,
    samples: FloatArray,
) -> FloatArray:
    """Largest sampled radial distance of each candidate (inf if invalid)."""
    s = np.where(t.ok[:, None], t.s, np.linspace(0.0, 1.0, 4)[None, :])
    worst = np.zeros(t.ok.shape[0])
    # Samples on the first axis, for numpy's fast maximum over it (see fewest._screen_grid).
    for i in range(3):
        u = s[:, i] + (s[:, i + 1] - s[:, i]) * samples[:, None]
        e = screen_radial(
            k, m, t.x[:, i], t.y[:, i], -sin_phi[:, i], cos_phi[:, i], t.kappa[:, i], u
        )
        worst = np.maximum(worst, e.max(axis=0))
    return np.where(t.ok, worst, np.inf)


def _build(
    k: FloatArray, m: FloatArray, ua: FloatArray, grid: FloatArray, samples: FloatArray = _T
) -> tuple[Triarc, FloatArray]:
    """Triarcs and scores of candidates ``grid`` (rows, G, 3) = (v, δ, λ) for each row."""
    g = grid.shape[1]
    row = (slice(None), None)
    # Invalid candidates come out non-finite: masked as inf.
    with np.errstate(invalid="ignore", divide="ignore"):
        t, cos_phi, sin_phi = _directed_triarcs(
            k[row], m[row], ua[row], grid[..., 0], grid[..., 1], grid[..., 2], False
        )
        kk, mm = np.repeat(k, g), np.repeat(m, g)
        score = _sampled(kk, mm, t, cos_phi, sin_phi, samples)
    return t, score.reshape(-1, g)


def best_triarcs(
    k: FloatArray, m: FloatArray, ua: FloatArray, tol: FloatArray
) -> list[tuple[Triarc, FloatArray, FloatArray] | None]:
    """Per row, a proven triarc over ``[ua, 1]`` within ``tol``: ``(triarc, dev, u_dev)``."""
    n = k.size
    span = 1.0 - ua
    rows = np.arange(n)
    scale = np.stack([span, tol, np.ones(n)], axis=1)
    offset = np.stack([ua, np.zeros(n), np.zeros(n)], axis=1)
    grid = offset[:, None, :] + scale[:, None, :] * _UNIT[None, :, :]
    _, score = _build(k, m, ua, grid, _COARSE_T)
    best = np.argmin(score, axis=1)
    centre = grid[rows, best]
    best_score = score[rows, best]
    width = np.stack([span * 0.07, tol * 0.5, np.full(n, 0.1)], axis=1)
    for round_ in range(_ROUNDS):
        # Refine only rows still above the target and not hopeless (see the constants).
        hopeless = 1.0 + (_HOPELESS - 1.0) * _HOPELESS_DECAY**round_
        act = np.flatnonzero((best_score > _GOOD * tol) & (best_score < hopeless * tol))
        if act.size == 0:
            break
        grid = centre[act, None, :] + width[act, None, :] * _CUBE[None, :, :]
        lo = (ua[act] + 1e-9 * span[act])[:, None]
        hi = (1.0 - 1e-9 * span[act])[:, None]
        grid[..., 0] = np.clip(grid[..., 0], lo, hi)
        _, score = _build(k[act], m[act], ua[act], grid)
        best = np.argmin(score, axis=1)
        top = score[np.arange(act.size), best]
        better = top < best_score[act]
        up = act[better]
        centre[up] = grid[np.flatnonzero(better), best[better]]
        best_score[up] = top[better]
        width *= _SHRINK
    if n == 1 and PROVE_ONE_IN_FLOATS:
        return [_prove_one(float(k[0]), float(m[0]), float(ua[0]), centre[0].tolist(),
                           float(best_score[0]), float(tol[0]))]  # fmt: skip
    with np.errstate(invalid="ignore", divide="ignore"):
        t = _triarcs(k, m, ua, centre[:, 0], centre[:, 1], centre[:, 2])
    ok = t.ok & (best_score <= 0.999 * tol)
    d = arc_deviation(
        np.repeat(k, 3),
        np.repeat(m, 3),
        t.x[:, :3].ravel(),
        t.y[:, :3].ravel(),
        t.phi[:, :3].ravel(),
        t.kappa.ravel(),
        t.x[:, 1:].ravel(),
        t.y[:, 1:].ravel(),
        t.s[:, :3].ravel(),
        t.s[:, 1:].ravel(),
        np.repeat(tol, 3),
    )
    value, where = d.value.reshape(n, 3), d.u.reshape(n, 3)
    ok &= np.all(value <= tol[:, None], axis=1)
    out: list[tuple[Triarc, FloatArray, FloatArray] | None] = []
    for r in range(n):
        if not ok[r]:
            out.append(None)
            continue
        row = Triarc(*(getattr(t, f)[r : r + 1] for f in Triarc.__slots__))
        out.append((row, value[r], where[r]))
    return out


def _prove_one(
    k: float, m: float, ua: float, centre: list[float], score: float, tol: float
) -> tuple[Triarc, FloatArray, FloatArray] | None:
    """The end of :func:`best_triarcs` for one row, in floats: the winner's triarc and the
    exact deviations of its three arcs (the first that fails spares the rest)."""
    t = triarc_one(k, m, ua, *centre)
    if not (t.ok and score <= 0.999 * tol):
        return None
    value, where = [], []
    for i in range(3):
        d, u = one_arc_deviation(
            k, m, t.x[i], t.y[i], t.phi[i], t.cos_phi[i], t.sin_phi[i], t.kappa[i],
            t.x[i + 1], t.y[i + 1], t.s[i], t.s[i + 1], tol,
        )  # fmt: skip
        if not d <= tol:
            return None
        value.append(d)
        where.append(u)
    row = Triarc(
        x=np.array([t.x]), y=np.array([t.y]), phi=np.array([t.phi]), kappa=np.array([t.kappa]),
        s=np.array([t.s]), ok=np.array([True]),
    )  # fmt: skip
    return row, np.array(value), np.array(where)


class TriarcOne(NamedTuple):
    """:class:`Triarc` of one candidate in floats, with its arcs' start directions' cosines
    and sines (numpy's, for the proof)."""

    x: tuple[float, float, float, float]
    y: tuple[float, float, float, float]
    phi: tuple[float, float, float, float]
    kappa: tuple[float, float, float]
    s: tuple[float, float, float, float]
    ok: bool
    cos_phi: tuple[float, float, float]
    sin_phi: tuple[float, float, float]


def triarc_one(k: float, m: float, ua: float, v: float, delta: float, lam: float) -> TriarcOne:
    """:func:`_triarcs` (``exact=True``) for one candidate, in floats, operation for operation;
    arctangents, sines, cosines and ``hypot`` are numpy's own, so the numbers are the
    arrays' bit for bit (tests/geometry/test_fewest_tail.py)."""
    wa, wv = ua * ua, v * v
    ax, ay = ua * (3.0 + k * wa), m * wa * ua
    bx, by = 1.0 * (3.0 + k * 1.0), m * 1.0 * 1.0
    phi_a, phi_b, tv = np.arctan2(
        [m * wa, m * 1.0, m * wv], [1.0 + k * wa, 1.0 + k * 1.0, 1.0 + k * wv]
    ).tolist()
    sin_tv, cos_tv = float(np.sin(tv)), float(np.cos(tv))
    nx, ny = -sin_tv, cos_tv
    h = v - ua
    sigma = v * v + v * ua + ua * ua
    cx, cy = h * (3.0 + k * sigma) + delta * nx, h * m * sigma + delta * ny
    h = 1.0 - v
    sigma = 1.0 * 1.0 + 1.0 * v + v * v
    dx, dy = h * (3.0 + k * sigma) - delta * nx, h * m * sigma - delta * ny
    chi0, chi = np.arctan2([cy, dy], [cx, dx]).tolist()
    chord0 = float(np.hypot(cx, cy))
    psi1 = 2.0 * chi0 - phi_a
    jx, jy = ax + cx, ay + cy
    alpha, beta = chi - psi1, phi_b - chi
    psi2 = chi - beta + lam * (alpha + beta)
    h0, h1 = 0.5 * (psi1 + psi2), 0.5 * (psi2 + phi_b)
    sin_a0, half_turn, s1, s0, half_1, half_2, sin_psi1, sin_psi2, sin_phi_a = np.sin(
        [chi0 - phi_a, 0.5 * (phi_b - psi1), h1, h0, 0.5 * (psi2 - psi1), 0.5 * (phi_b - psi2),
         psi1, psi2, phi_a]
    ).tolist()  # fmt: skip
    c1, c0, cos_psi1, cos_psi2, cos_phi_a = np.cos([h1, h0, psi1, psi2, phi_a]).tolist()
    kappa0 = numpy_divide(2.0 * sin_a0, chord0)
    len0 = numpy_divide(dx * s1 - dy * c1, half_turn)
    len1 = numpy_divide(c0 * dy - s0 * dx, half_turn)
    kappa1 = numpy_divide(2.0 * half_1, len0)
    kappa2 = numpy_divide(2.0 * half_2, len1)
    gx, gy = jx + len0 * c0, jy + len0 * s0
    split1 = one_joint_split(k, m, jx, jy, cos_psi1, sin_psi1)
    split2 = one_joint_split(k, m, gx, gy, cos_psi2, sin_psi2)
    ok = half_turn > 0.0 and len0 > 0.0 and len1 > 0.0 and split1 > ua and split2 > split1
    ok = ok and split2 < 1.0 and math.isfinite(kappa1) and math.isfinite(kappa2)
    return TriarcOne(
        x=(ax, jx, gx, bx),
        y=(ay, jy, gy, by),
        phi=(phi_a, psi1, psi2, phi_b),
        kappa=(kappa0, kappa1, kappa2),
        s=(ua, split1, split2, 1.0),
        ok=ok,
        cos_phi=(cos_phi_a, cos_psi1, cos_psi2),
        sin_phi=(sin_phi_a, sin_psi1, sin_psi2),
    )
