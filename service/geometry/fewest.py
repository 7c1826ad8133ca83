"""The ``fewest-arcs`` strategy: greedy longest biarcs with the join point chosen freely.

Walton & Meek's subdivision (§5) joins every biarc at the incentre and splits a failing piece
at its worst point, which spends arcs freely. Here, in the canonical frame of
:mod:`service.geometry.canonical`, the spiral is walked from ``u = 0``: from the current end
point ``A0 = Q(u0)`` the next biarc ends at the *largest* ``u1`` for which *some* biarc of the
one-parameter family between ``(A0, T(u0))`` and ``(Q(u1), T(u1))`` stays within the tolerance.

**The family (Sabin's circle).** For end directions ``φ0``, ``φ1`` and chord direction ``χ``,
the join tangent ``ψ`` ranges over ``(2χ − φ1, 2χ − φ0)`` (the incentre biarc is ``ψ = χ``).
Each arc's chord runs along the mean of its end directions, so the chord lengths solve
``A1 − A0 = L0·e((φ0 + ψ)/2) + L1·e((ψ + φ1)/2)`` and the join point is
``G = A0 + L0·e((φ0 + ψ)/2)``; curvatures are ``κ = 2·sin(turn/2)/L``. ``ψ`` is searched as
``χ − β + λ(α + β)``, ``λ ∈ (0, 1)``, ``α = χ − φ0``, ``β = φ1 − χ``.

**Search, then proof.** Candidates ``(u1, λ)`` are screened on a grid by the radial distance at
a few samples per arc — a *lower* bound on the deviation, so it only discards candidates that
certainly fail — refined in three rounds, and the best are then verified by
:func:`service.geometry.fewest_exact.arc_deviation`, which computes each arc's two-sided
deviation exactly (derivative cascade on the quintic ``(Q − C)·Q'``, plus the polar-graph
conditions that make the radial distance the Hausdorff distance; see that module). Only
verified biarcs are kept, so the tolerance is guaranteed exactly as for ``subdivide``; the
result is G1 by construction and ends at ``Q(1)`` with the end tangent.

The caller compares with ``subdivide`` and keeps whichever has fewer segments, so the count
is never above the paper's.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from . import canonical
from .assemble import FLAT_SWEEP_RAD, Frames, splines
from .errors import GeometryError
from .fewest_exact import arc_deviation, joint_split, radial
from .fewest_tail import best_triarc
from .spiral import Spiral
from .types import ArcSpline, BoolArray, FloatArray, SegmentColumns

#: Screening samples per arc (a lower bound on its deviation; the proof comes after).
SAMPLES = 24
#: Grid of the first round: ``u1 − u0 = (1 − u0)·2^(−j/2)``, ``j = 0 … U_STEPS − 1``.
U_STEPS = 32
#: Samples per arc in the first round, which only brackets the longest piece.
COARSE_SAMPLES = 8
#: Join-parameter grid of the first round, and the size of each refining round's grids.
LAMBDAS = 24
REFINE = 12
#: The first grid around the previous piece's span: this many octaves either side, points.
HINT_OCTAVES = 0.75
HINT_STEPS = 12
#: How many screened candidates are verified exactly at once.
VERIFY = 8

#: Screening aims at these fractions of the tolerance, in turn, until a candidate is proven.
SCREEN_FACTORS = (0.999, 0.99, 0.95, 0.8, 0.5)

_SAMPLE_T = (np.arange(SAMPLES) + 0.5) / SAMPLES
_COARSE_T = (np.arange(COARSE_SAMPLES) + 0.5) / COARSE_SAMPLES
_LAMBDA_GRID = (np.arange(LAMBDAS) + 0.5) / LAMBDAS


@dataclass(frozen=True, slots=True)
class Chain:
    """A G1 arc chain in the canonical frame: ``n`` arcs, ``n + 1`` joints.

    Arc ``i`` starts at joint ``i`` (``jx``, ``jy``, direction ``phi``) with curvature
    ``kappa[i]`` and answers for ``u ∈ [s[i], s[i + 1]]``; its exact deviation is ``dev[i]``,
    reached at ``u_dev[i]``.
    """

    jx: FloatArray
    jy: FloatArray
    phi: FloatArray
    kappa: FloatArray
    s: FloatArray
    dev: FloatArray
    u_dev: FloatArray


@dataclass(frozen=True, slots=True)
class _Biarcs:
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


def _biarcs(k: float, m: float, u0: float, u1: FloatArray, lam: FloatArray) -> _Biarcs:
    ax, ay = canonical.point(k, m, u0)
    dx, dy = canonical.offset(k, m, u0, u1)
    phi0 = np.full_like(u1, float(canonical.direction_rad(k, m, u0 * u0)))
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
    kk, mm = np.full_like(u1, k), np.full_like(u1, m)
    split = joint_split(kk, mm, gx, gy, psi)
    ok &= (split > u0) & (split < u1)
    return _Biarcs(u1, lam, phi0, psi, phi1, kappa0, kappa1, gx, gy, split, ok)


def _screen(
    k: float, m: float, u0: float, b: _Biarcs, samples: FloatArray = _SAMPLE_T
) -> FloatArray:
    """Largest sampled radial distance of each candidate biarc (a lower bound), inf if invalid."""
    split = np.where(b.ok, b.split, 0.5 * (u0 + b.u1))
    ax, ay = canonical.point(k, m, u0)
    t = samples[None, :]
    ua = u0 + (split - u0)[:, None] * t
    ub = split[:, None] + (b.u1 - split)[:, None] * t
    e0 = radial(k, m, ax, ay, b.phi0[:, None], b.kappa0[:, None], ua).max(axis=1)
    e1 = radial(k, m, b.gx[:, None], b.gy[:, None], b.psi[:, None], b.kappa1[:, None], ub)
    worst = np.maximum(e0, e1.max(axis=1))
    return np.where(b.ok, worst, np.inf)


def _verify(k: float, m: float, u0: float, b: _Biarcs, tol: float) -> tuple[FloatArray, ...]:
    """Exact deviations of both arcs of each candidate: ``(dev0, u0_at, dev1, u1_at)``."""
    n = b.u1.shape[0]
    kk, mm = np.full(2 * n, k), np.full(2 * n, m)
    ax, ay = canonical.point(k, m, u0)
    bx, by = canonical.point(k, m, b.u1)
    d = arc_deviation(
        kk,
        mm,
        np.concatenate([np.full(n, float(ax)), b.gx]),
        np.concatenate([np.full(n, float(ay)), b.gy]),
        np.concatenate([b.phi0, b.psi]),
        np.concatenate([b.kappa0, b.kappa1]),
        np.concatenate([b.gx, bx]),
        np.concatenate([b.gy, by]),
        np.concatenate([np.full(n, u0), b.split]),
        np.concatenate([b.split, b.u1]),
        tol,
    )
    value = np.where(np.concatenate([b.ok, b.ok]), d.value, np.inf)
    return value[:n], d.u[:n], value[n:], d.u[n:]


def _take(b: _Biarcs, i: int) -> _Biarcs:
    return _Biarcs(*(np.asarray(getattr(b, f))[i : i + 1] for f in _Biarcs.__slots__))


def _next_biarc(
    k: float, m: float, u0: float, tol: float, hint: float
) -> tuple[_Biarcs, tuple[float, ...]] | None:
    """The verified biarc from ``u0`` reaching the largest ``u1`` found, or None.

    Sampling underestimates the deviation slightly, so screening aims a little below the
    tolerance, and lower still when none of the screened candidates passes the proof.
    ``hint`` is the previous piece's parameter span (0 for none): neighbouring pieces are
    about as long, so the first grid is placed around it.
    """
    for factor in SCREEN_FACTORS:
        found = _search(k, m, u0, tol, factor * tol, hint)
        if found is not None:
            return found
    return None


def _first_round(
    k: float, m: float, u0: float, screen_tol: float, u_grid: FloatArray
) -> tuple[_Biarcs, FloatArray, BoolArray]:
    uu, ll = np.meshgrid(u_grid, _LAMBDA_GRID, indexing="ij")
    b = _biarcs(k, m, u0, uu.ravel(), ll.ravel())
    with np.errstate(invalid="ignore"):  # invalid candidates are NaN, then masked as inf
        dev = _screen(k, m, u0, b, _COARSE_T).reshape(uu.shape)
    return b, dev, dev <= screen_tol


def _search(
    k: float, m: float, u0: float, tol: float, screen_tol: float, hint: float
) -> tuple[_Biarcs, tuple[float, ...]] | None:
    span = 1.0 - u0
    full = u0 + span * 2.0 ** (-np.arange(U_STEPS) / 2.0)
    full[0] = 1.0
    u_grid = full
    if 0.0 < hint < span:
        near = u0 + hint * 2.0 ** np.linspace(-HINT_OCTAVES, HINT_OCTAVES, HINT_STEPS)
        u_grid = np.concatenate([[1.0], near[near < 1.0][::-1]])
    b, dev, fits = _first_round(k, m, u0, screen_tol, u_grid)
    rows = np.flatnonzero(fits.any(axis=1))
    # Outside the hinted window (nothing fits, or the longest candidate below 1 fits): retry
    # on the full geometric grid.
    if u_grid is not full and (rows.size == 0 or (rows.min() == 1 and u_grid.size > 1)):
        u_grid = full
        b, dev, fits = _first_round(k, m, u0, screen_tol, u_grid)
        rows = np.flatnonzero(fits.any(axis=1))
    if rows.size == 0:
        return None
    feasible_u = (b, dev, fits)
    lam_width = 1.0 / LAMBDAS
    for _ in range(2):
        top = rows[np.argmax(u_grid[rows])]
        best_lam = float(b.lam.reshape(dev.shape)[top, np.argmin(dev[top])])
        if u_grid[top] >= 1.0:
            break
        above = u_grid[u_grid > u_grid[top]]
        hi = float(above.min()) if above.size else 1.0
        u_grid = np.linspace(u_grid[top], hi, REFINE + 2)[:-1]
        lams = np.clip(best_lam + lam_width * np.linspace(-1.0, 1.0, REFINE), 1e-3, 1.0 - 1e-3)
        uu, ll = np.meshgrid(u_grid, lams, indexing="ij")
        b = _biarcs(k, m, u0, uu.ravel(), ll.ravel())
        with np.errstate(invalid="ignore"):
            dev = _screen(k, m, u0, b).reshape(uu.shape)
        fits = dev <= screen_tol
        rows = np.flatnonzero(fits.any(axis=1))
        if rows.size == 0:
            break
        feasible_u = (b, dev, fits)
        lam_width *= 0.5
    if feasible_u is None:
        return None
    b, dev, fits = feasible_u
    flat = np.flatnonzero(fits.ravel())
    order = flat[np.lexsort((dev.ravel()[flat], -b.u1[flat]))][:VERIFY]
    picked = _Biarcs(*(np.asarray(getattr(b, f))[order] for f in _Biarcs.__slots__))
    d0, w0, d1, w1 = _verify(k, m, u0, picked, tol)
    good = np.flatnonzero((d0 <= tol) & (d1 <= tol))
    if good.size == 0:
        return None
    i = int(good[0])
    return _take(picked, i), (float(d0[i]), float(w0[i]), float(d1[i]), float(w1[i]))


def fewest_chain(k: float, m: float, tol: float, max_arcs: int) -> Chain | None:
    """Greedy longest verified biarcs over ``[0, 1]``; None if it fails or needs > max_arcs."""
    jx, jy, phi, s = [0.0], [0.0], [0.0], [0.0]
    kappa: list[float] = []
    dev: list[float] = []
    u_dev: list[float] = []
    u0, hint = 0.0, 0.0
    while u0 < 1.0:
        if len(kappa) + 2 > max_arcs:
            return None
        found = _next_biarc(k, m, u0, tol, hint)
        if found is None:
            return None
        b, (d0, w0, d1, w1) = found
        u1 = float(b.u1[0])
        if not u1 > u0:
            return None
        bx, by = canonical.point(k, m, u1)
        jx += [float(b.gx[0]), float(bx)]
        jy += [float(b.gy[0]), float(by)]
        phi += [float(b.psi[0]), float(b.phi1[0])]
        kappa += [float(b.kappa0[0]), float(b.kappa1[0])]
        s += [float(b.split[0]), u1]
        dev += [d0, d1]
        u_dev += [w0, w1]
        hint, u0 = u1 - u0, u1
    chain = Chain(*(np.array(v, dtype=np.float64) for v in (jx, jy, phi, kappa, s, dev, u_dev)))
    return _merge_tail(k, m, chain, tol)


def _merge_tail(k: float, m: float, chain: Chain, tol: float) -> Chain:
    """The chain with its last two biarcs replaced by a proven triarc, if one exists."""
    n = chain.kappa.shape[0]
    if n < 4:
        return chain
    found = best_triarc(k, m, float(chain.s[n - 4]), tol)
    if found is None:
        return chain
    t, dev, u_dev = found
    keep = n - 4
    return Chain(
        jx=np.concatenate([chain.jx[:keep], t.x[0]]),
        jy=np.concatenate([chain.jy[:keep], t.y[0]]),
        phi=np.concatenate([chain.phi[:keep], t.phi[0]]),
        kappa=np.concatenate([chain.kappa[:keep], t.kappa[0]]),
        s=np.concatenate([chain.s[:keep], t.s[0]]),
        dev=np.concatenate([chain.dev[:keep], dev]),
        u_dev=np.concatenate([chain.u_dev[:keep], u_dev]),
    )


def chain_columns(chain: Chain, spiral: Spiral) -> SegmentColumns:
    """World-coordinate rows of a canonical chain, with the conventions of ``assemble``."""
    frames = Frames.of([spiral])
    n = chain.kappa.shape[0]
    i = np.zeros(n + 1, dtype=np.intp)
    joints = frames.point(i, chain.jx, chain.jy)
    joints[0] = frames.origin[0]
    joints[-1] = frames.end_point[0]
    i = i[:n]
    scale = float(frames.scale[0])
    sweep = chain.phi[1:] - chain.phi[:-1]
    is_arc = np.abs(sweep) > FLAT_SWEEP_RAD
    start, end = joints[:-1], joints[1:]
    chord = np.hypot(*(end - start).T)
    with np.errstate(divide="ignore", invalid="ignore"):
        radius_c = 1.0 / np.abs(chain.kappa)
        to_centre = np.where(is_arc, 1.0 / chain.kappa, 0.0)
    nx, ny = -np.sin(chain.phi[:-1]), np.cos(chain.phi[:-1])
    centre = start + frames.vector(i, to_centre * nx, to_centre * ny)
    radius = scale * radius_c
    length = np.where(is_arc, radius * np.abs(sweep), chord)
    start_angle = frames.angle(i, chain.phi[:-1] - np.sign(chain.kappa) * 0.5 * np.pi)
    # A flat arc becomes its chord, which is within its sagitta (≤ length·|sweep|/8) of it.
    sagitta = np.where(is_arc, 0.0, chord * np.abs(sweep) / 8.0)
    return SegmentColumns(
        is_arc=is_arc,
        start=start,
        end=end,
        center=np.where(is_arc[:, None], centre, 0.5 * (start + end)),
        radius=np.where(is_arc, radius, np.inf),
        start_angle_rad=np.where(is_arc, start_angle, 0.0),
        sweep_rad=np.where(is_arc, frames.mirror[0] * sweep, 0.0),
        length=length,
        u_start=chain.s[:-1],
        u_end=chain.s[1:],
        max_deviation=scale * chain.dev + sagitta,
        u_at_max_deviation=chain.u_dev,
    )


def fewest_batch(
    spirals: list[Spiral],
    tolerances: FloatArray,
    target: FloatArray,
    baseline: list[ArcSpline | GeometryError],
    max_segments: int,
) -> list[ArcSpline | GeometryError]:
    """``fewest-arcs`` for each spiral: the greedy chain if it has no more segments than the
    ``baseline`` (``subdivide``'s result or its error) at world tolerance ``target`` (the
    tolerance less the rounding margin), else the baseline."""
    out: list[ArcSpline | GeometryError] = []
    for j, spiral in enumerate(spirals):
        base = baseline[j]
        if not isinstance(base, ArcSpline):
            out.append(base)
            continue
        k, m = (float(v) for v in canonical.coefficients(spiral.turn_angle_rad))
        tol = float(target[j]) / spiral.a
        chain = fewest_chain(k, m, tol, min(max_segments, len(base)))
        if chain is None or chain.kappa.shape[0] > len(base):
            out.append(base)
            continue
        columns = chain_columns(chain, spiral)
        rows = np.zeros(len(columns), dtype=np.intp)
        out.append(splines(columns, rows, [spiral], tolerances[j : j + 1], base.strategy)[0])
    return out
