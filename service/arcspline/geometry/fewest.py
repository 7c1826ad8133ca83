"""The ``fewest-arcs`` strategy: greedy longest biarcs with the join point chosen freely.

Walton & Meek's subdivision (§5) joins every biarc at the incentre and splits a failing piece
at its worst point, which spends arcs freely. Here, in the canonical frame of
:mod:`arcspline.geometry.canonical`, the spiral is walked from ``u = 0``: from the current end
point ``A0 = Q(u0)`` the next biarc ends at the *largest* ``u1`` for which *some* biarc of the
one-parameter family between ``(A0, T(u0))`` and ``(Q(u1), T(u1))`` stays within the tolerance.

**The family (Sabin's circle)** is parametrised by the join parameter ``λ ∈ (0, 1)``
(:mod:`arcspline.geometry.fewest_biarc`, which builds the biarcs and measures them).

**Search, then proof.** Candidates ``(u1, λ)`` are screened by the radial distance at a few
samples per arc (an estimate from below of the deviation; it only discards candidates). Spans
and join parameters change slowly along a spiral, so each step starts from the previous one:
a grid of ``u1`` within ±0.4 octave of the previous span against ``λ`` within ±0.12 of the
previous ``λ`` (the first piece scans a half-octave grid over ``(u0, 1]`` with three ``λ``, down
to two octaves below ``subdivide``'s first biarc, and a piece to the spiral's end gets a finer
``λ`` scan because it ends the walk). Two rounds then
refine the bracket between the longest fit and the next value tried, with ``λ`` narrowing
around the best, and the screened deviations either side of the boundary are interpolated to
where they reach the target. Only then is anything proven: the interpolated end, the longest
screened fit and, where both fail, a ladder of slightly shorter pieces are verified by
:func:`arcspline.geometry.fewest_exact.arc_deviation`, which computes each arc's two-sided
deviation exactly (derivative cascade on the quintic ``(Q − C)·Q'``, plus the polar-graph
conditions that make the radial distance the Hausdorff distance; see that module). Only
verified biarcs are kept, so the tolerance is guaranteed exactly as for ``subdivide``; the
result is G1 by construction and ends at ``Q(1)`` with the end tangent. A few candidates (a
single spiral's step) are proven one arc at a time in floats, in order, stopping at the first
proven one (:mod:`arcspline.geometry.fewest_exact_one`, the same numbers as the array proof).

**Newton's step.** Far from the spiral's end (the previous span fits ``NEWTON_REACH`` more
times), a step first tries :mod:`arcspline.geometry.fewest_newton`: Newton's method on
``(log(u1 − u0), λ)`` for the biarc whose two arcs both deviate by just under the tolerance,
each iterate measured exactly by the same proof, with Broyden's update of a Jacobian carried
along the walk — two exact evaluations a step on the paper's example at 1e-5, against three
screening grids and a proof; one spiral's step runs in floats. A row it leaves (no proven
iterate near the tolerance) takes the grids above. Rows take Newton steps one after another
while they stay far from the end, so that a batch's searches run together.

**Tail merge.** Greedy longest pieces leave a short last biarc; the last two biarcs are then
replaced by three arcs whose first joint lies off the spiral, when such a "triarc" is proven
within the tolerance (:mod:`arcspline.geometry.fewest_tail`). This is what makes odd counts
possible (the paper's example: 2/3/7/15/31 segments at 0.1 … 1e-5, against 4/8/12/26/54).
The triarc needs only the start of the last-but-one biarc, so it is tried as soon as a step
ends near the spiral's end (:func:`fewest_chains`): one spiral then skips its last step.

**Batches.** :func:`fewest_chains` walks all spirals of a batch in lockstep: every greedy step
of every spiral is one set of numpy operations, as in :mod:`arcspline.geometry.subdivide`; one
spiral's search and proofs keep their bookkeeping in floats (:func:`_search_one`). Either way
a spiral's chain is the same, bit for bit, whatever else is in its batch.

The caller (:func:`fewest_batch`) compares with ``subdivide`` and keeps whichever has fewer
segments (``subdivide`` only where the walk fails or needs more), so the count is never above the
paper's, and ``subdivide``'s errors (segment limit, precision) are reported unchanged.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from . import canonical
from .assemble import FLAT_SWEEP_RAD, Frames, splines
from .errors import GeometryError
from .fewest_biarc import (
    LAMBDA_MARGIN,
    NO_BIARC,
    SabinBiarcs,
    numpy_divide,
    sabin_biarc_one,
    sabin_biarcs,
    verify,
    verify_one,
)
from .fewest_exact import one_arc_deviation, screen_radial
from .fewest_newton import NEWTON_JACOBIAN, Devs, newton_step
from .fewest_tail import best_triarcs
from .spiral import Spiral
from .types import ArcSpline, BoolArray, FloatArray, SegmentColumns

#: Screening samples per arc (a lower bound on its deviation; the proof comes after).
SAMPLES = 8
#: Grid of the first round without a hint: ``u1 − u0 = (1 − u0)·2^(−j/2)``,
#: ``j = 0 … U_STEPS − 1``, against ``LAMBDAS`` join parameters over ``(0, 1)``.
U_STEPS = 32
LAMBDAS = 12
#: The first piece's scan of that grid: join parameters ``0.5 ± SCAN_WIDTH``.
SCAN_LAMBDAS = 3
SCAN_WIDTH = 0.2
#: Join parameters tried on a piece to the spiral's end.
END_LAMBDAS = 24
#: Samples per arc in the first round, which only brackets the longest piece.
COARSE_SAMPLES = 6
#: The first grid around the previous piece's span: this many octaves either side, points;
#: and around the previous piece's join parameter: this far either side, points. (Along a
#: spiral both change slowly: the paper's example at 1e-5 has spans within 10 % of the last
#: one and ``λ`` within 0.01 of it.)
HINT_OCTAVES = 0.4
HINT_STEPS = 8
HINT_LAMBDA = 0.12
HINT_LAMBDAS = 7
#: Refining rounds between the longest fit and the next grid value: ``u1`` points, ``λ`` points.
REFINE_ROUNDS = 2
REFINE = 5
REFINE_LAMBDAS = 5
#: The pieces proven where neither the interpolated crossing nor the longest screened fit
#: is: these fractions of the longest screened span.
LADDER = np.array([0.998, 0.994, 0.985, 0.96, 0.9])

#: Up to this many candidates (rows × rungs) are proven one arc at a time in floats, rung
#: after rung until one is proven; more go to numpy all at once. Either way the same result.
PROVE_IN_FLOATS = 8

#: A single row's search keeps its bookkeeping in floats (:func:`_search_one`, the same result).
SEARCH_ONE_IN_FLOATS = True

#: Screening aims at these fractions of the tolerance, in turn, until a candidate is proven.
SCREEN_FACTORS = (0.999, 0.99, 0.95, 0.8, 0.5)

#: A step ending within this many of its spans from the spiral's end tries the tail merge
#: from its start (see :func:`fewest_chains`). Within one span, the next step nearly always
#: ends the walk; 2^0.4 (where the next step scans the end) tried 13 % more triarcs on 200
#: random spirals for the same chains: +8 % time on a batch, against +4 % with 1.
CLOSE_REACH = 1.0
#: Rows whose previous span fits this many times more before the spiral's end take the Newton
#: step first; nearer the end its iterates tend to pass the end and the grids decide. (With
#: one spiral's Newton step in floats, 2 beats 4 on the paper's example: 1e-3 5.9 -> 4.4 ms,
#: 1e-5 10.9 -> 8.8 ms and 32 -> 31 arcs; 1 and 1.5 gain nothing more.)
NEWTON_REACH = 2.0
_SAMPLE_T = (np.arange(SAMPLES) + 0.5) / SAMPLES
_COARSE_T = (np.arange(COARSE_SAMPLES) + 0.5) / COARSE_SAMPLES
_LAMBDA_GRID = (np.arange(LAMBDAS) + 0.5) / LAMBDAS
_SCAN_LAMBDA_GRID = 0.5 + SCAN_WIDTH * np.linspace(-1.0, 1.0, SCAN_LAMBDAS)
_END_LAMBDA_GRID = (np.arange(END_LAMBDAS) + 0.5) / END_LAMBDAS
_HINT_SCALE = 2.0 ** np.linspace(HINT_OCTAVES, -HINT_OCTAVES, HINT_STEPS)
_HINT_LAMBDA_GRID = HINT_LAMBDA * np.linspace(-1.0, 1.0, HINT_LAMBDAS)
_U_STEP_GRID = 2.0 ** (-np.arange(U_STEPS) / 2.0)
# Both ends included: the upper one may fit with the finer join parameters.
_REFINE_GRID = np.linspace(0.0, 1.0, REFINE + 1)
_REFINE_LAMBDA_GRID = np.linspace(-1.0, 1.0, REFINE_LAMBDAS)


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


def chain_columns(
    chains: list[Chain], spirals: list[Spiral]
) -> tuple[SegmentColumns, npt.NDArray[np.intp]]:
    """World-coordinate rows of canonical chains (one per spiral), with the conventions of
    ``assemble``, and the spiral of each row. Elementwise, so a chain's rows do not depend
    on the others."""
    frames = Frames.of(spirals)
    sizes = np.array([c.kappa.shape[0] for c in chains], dtype=np.intp)
    i = np.repeat(np.arange(len(chains)), sizes)
    ij = np.repeat(np.arange(len(chains)), sizes + 1)
    joints = frames.point(
        ij,
        np.concatenate([c.jx for c in chains]),
        np.concatenate([c.jy for c in chains]),
    )
    last = np.cumsum(sizes + 1) - 1
    joints[last - sizes] = frames.origin
    joints[last] = frames.end_point
    starts = np.delete(np.arange(joints.shape[0]), last)
    phi_all = np.concatenate([c.phi for c in chains])
    phi_start, phi_end = phi_all[starts], phi_all[starts + 1]
    kappa = np.concatenate([c.kappa for c in chains])
    s_all = np.concatenate([c.s for c in chains])
    scale = frames.scale[i]
    sweep = phi_end - phi_start
    is_arc = np.abs(sweep) > FLAT_SWEEP_RAD
    start, end = joints[starts], joints[starts + 1]
    chord = np.hypot(*(end - start).T)
    with np.errstate(divide="ignore", invalid="ignore"):
        radius_c = 1.0 / np.abs(kappa)
        to_centre = np.where(is_arc, 1.0 / kappa, 0.0)
    nx, ny = -np.sin(phi_start), np.cos(phi_start)
    centre = start + frames.vector(i, to_centre * nx, to_centre * ny)
    radius = scale * radius_c
    length = np.where(is_arc, radius * np.abs(sweep), chord)
    start_angle = frames.angle(i, phi_start - np.sign(kappa) * 0.5 * np.pi)
    # A flat arc becomes its chord, which is within its sagitta (≤ length·|sweep|/8) of it.
    sagitta = np.where(is_arc, 0.0, chord * np.abs(sweep) / 8.0)
    columns = SegmentColumns(
        is_arc=is_arc,
        start=start,
        end=end,
        center=np.where(is_arc[:, None], centre, 0.5 * (start + end)),
        radius=np.where(is_arc, radius, np.inf),
        start_angle_rad=np.where(is_arc, start_angle, 0.0),
        sweep_rad=np.where(is_arc, frames.mirror[i] * sweep, 0.0),
        length=length,
        u_start=s_all[starts],
        u_end=s_all[starts + 1],
        max_deviation=scale * np.concatenate([c.dev for c in chains]) + sagitta,
        u_at_max_deviation=np.concatenate([c.u_dev for c in chains]),
    )
    return columns, i


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
    counts = [len(b) if isinstance(b, ArcSpline) else 0 for b in baseline]
    # Two segments are the least possible: one arc matching both end tangents needs a chord
    # that bisects the turn θ, while the spiral's chord turns at most 0.75·θ/2 from T0.
    todo = [j for j, count in enumerate(counts) if count > 2]
    out = list(baseline)
    if not todo:
        return out
    theta = np.array([spirals[j].turn_angle_rad for j in todo], dtype=np.float64)
    k, m = canonical.coefficients(theta)
    scale = np.array([spirals[j].a for j in todo], dtype=np.float64)
    limit = np.array([min(max_segments, counts[j]) for j in todo], dtype=np.intp)
    # Subdivide's first biarc is one of Sabin's family: some biarc reaches that far.
    first_span = np.array([baseline[j].u_end(1) for j in todo])  # type: ignore[union-attr]
    chains = fewest_chains(k, m, target[todo] / scale, limit, first_span)
    won = [
        (j, chain)
        for j, chain in zip(todo, chains, strict=True)
        if chain is not None and chain.kappa.shape[0] <= len(baseline[j])  # type: ignore[arg-type]
    ]
    if not won:
        return out
    picked = [spirals[j] for j, _ in won]
    columns, rows = chain_columns([c for _, c in won], picked)
    strategy = baseline[won[0][0]].strategy  # type: ignore[union-attr]
    index = [j for j, _ in won]
    # The spiral's length is the baseline's (the same spiral), not measured again.
    lengths = np.array([baseline[j].stats.spiral_length for j in index])  # type: ignore[union-attr]
    for j, spline in zip(
        index, splines(columns, rows, lengths, tolerances[index], strategy), strict=True
    ):
        out[j] = spline
    return out


# -- the same greedy walk, in lockstep over a batch of spirals ------------------------------


@dataclass(frozen=True, slots=True)
class _Round:
    """Screened candidates of a batch of rows: grid ``(r, W)``, λ ``(r, L)``, dev ``(r, W, L)``."""

    grid: FloatArray
    lams: FloatArray
    dev: FloatArray
    fits: BoolArray


def _evaluate(
    k: FloatArray,
    m: FloatArray,
    u0: FloatArray,
    grid: FloatArray,
    lams: FloatArray,
    screen_tol: FloatArray,
    samples: FloatArray = _COARSE_T,
) -> _Round:
    # Broadcast (rows, u1, λ): what depends on u1 alone is computed once per grid value.
    col = (slice(None), None, None)
    with np.errstate(invalid="ignore", divide="ignore"):
        b = sabin_biarcs(k[col], m[col], u0[col], grid[:, :, None], lams[:, None, :], exact=False)
        dev = _screen_grid(k, m, u0, b, samples)
    return _Round(grid, lams, dev, dev <= screen_tol[:, None, None])


def _evaluate_with_end(
    k: FloatArray,
    m: FloatArray,
    u0: FloatArray,
    grid: FloatArray,
    lams: FloatArray,
    screen_tol: FloatArray,
) -> tuple[_Round, _Round]:
    """The end's round (``u1 = 1`` against ``END_LAMBDAS`` join parameters) and the round of
    ``(grid, lams)``, from one numpy pass over both sets of candidates (paired along one axis).
    Every candidate's numbers are those :func:`_evaluate` gives it (elementwise)."""
    r, w = grid.shape
    lam_end = np.broadcast_to(_END_LAMBDA_GRID, (r, END_LAMBDAS))
    u1 = np.concatenate([np.ones((r, END_LAMBDAS)), np.repeat(grid, lams.shape[1], axis=1)], 1)
    lam = np.concatenate([lam_end, np.tile(lams, (1, w))], axis=1)
    col = (slice(None), None, None)
    with np.errstate(invalid="ignore", divide="ignore"):
        b = sabin_biarcs(k[col], m[col], u0[col], u1[:, :, None], lam[:, :, None], exact=False)
        dev = _screen_grid(k, m, u0, b, _COARSE_T)
    end = dev[:, :END_LAMBDAS, 0].reshape(r, 1, END_LAMBDAS)
    rest = dev[:, END_LAMBDAS:, 0].reshape(r, w, lams.shape[1])
    tol = screen_tol[:, None, None]
    return (
        _Round(np.ones((r, 1)), lam_end, end, end <= tol),
        _Round(grid, lams, rest, rest <= tol),
    )


def _subset(rnd: _Round, rows: BoolArray) -> _Round:
    return _Round(rnd.grid[rows], rnd.lams[rows], rnd.dev[rows], rnd.fits[rows])


def _screen_grid(
    k: FloatArray, m: FloatArray, u0: FloatArray, b: SabinBiarcs, samples: FloatArray
) -> FloatArray:
    """Largest sampled radial distance of each candidate biarc (a lower bound on its
    deviation), inf if invalid; candidates broadcast over ``(rows, u1, λ)``.

    The samples lie on a first axis: numpy's maximum over a leading axis runs elementwise
    over whole slabs, over a short trailing one element by element (30 times slower)."""
    k3, m3, u03 = (v[:, None, None] for v in (k, m, u0))
    ok = b.ok  # (rows, u1, λ), like psi
    split = np.where(ok, b.split, 0.5 * (u03 + b.u1))
    t = samples[:, None, None, None]
    ax, ay = canonical.point(k3, m3, u03)
    ua = u03 + (split - u03) * t
    ub = split + (b.u1 - split) * t
    n0x, n0y = -np.sin(b.phi0), np.cos(b.phi0)
    n1x, n1y = -np.sin(b.psi), np.cos(b.psi)
    e0 = screen_radial(k3, m3, ax, ay, n0x, n0y, b.kappa0, ua).max(axis=0)
    e1 = screen_radial(k3, m3, b.gx, b.gy, n1x, n1y, b.kappa1, ub).max(axis=0)
    result: FloatArray = np.where(ok, np.maximum(e0, e1), np.inf)
    return result


def _top(rnd: _Round) -> tuple[FloatArray, FloatArray, BoolArray]:
    """Per row: the longest fitting ``u1``, the best ``λ`` there, and whether any fits."""
    feasible: BoolArray = np.any(rnd.fits, axis=2)
    masked = np.where(feasible, rnd.grid, -np.inf)
    at = np.argmax(masked, axis=1)
    rows = np.arange(at.size)
    best = np.argmin(rnd.dev[rows, at], axis=1)
    has: BoolArray = np.any(feasible, axis=1)
    return rnd.grid[rows, at], rnd.lams[rows, best], has


def _crossing(rnd: _Round, u_top: FloatArray, screen_tol: FloatArray) -> FloatArray:
    """Per row of an ascending grid: where the screened deviation (best ``λ``) reaches the
    target between the longest fit and the next grid value, by linear interpolation (a chord
    of the convex growth of the deviation, so it errs short); ``u_top`` at the grid's end."""
    r, w, _ = rnd.dev.shape
    rows = np.arange(r)
    at = np.argmax(np.where(np.any(rnd.fits, axis=2), rnd.grid, -np.inf), axis=1)
    nxt = np.minimum(at + 1, w - 1)
    d_top = rnd.dev[rows, at].min(axis=1)
    d_next = rnd.dev[rows, nxt].min(axis=1)
    with np.errstate(invalid="ignore", divide="ignore"):
        t = np.clip((screen_tol - d_top) / (d_next - d_top), 0.0, 1.0)
    t = np.where(np.isfinite(t) & (nxt > at), t, 0.0)
    result: FloatArray = u_top + (rnd.grid[rows, nxt] - u_top) * t
    return result


def _first_scan(u0: FloatArray, floor: FloatArray) -> FloatArray:
    """The geometric scan ``u0 + (1 − u0)·2^(−j/2)`` of rows whose first piece is known to
    reach ``floor`` (``subdivide``'s first biarc, which is one of Sabin's family, so some biarc
    reaches it within the tolerance): the scan stops two octaves (a factor 64 in deviation)
    below it, where the longest screened fit has never been found. Every row's grid ends at its
    own cut: values below it repeat the cut (the same candidate, which changes no choice), so
    a row's results do not depend on how far another row's grid goes. ``floor = u0`` means
    unknown: the whole grid."""
    span = 1.0 - u0
    cut = u0 + (floor - u0) * 0.25
    with np.errstate(divide="ignore"):
        need = np.ceil(2.0 * np.log2(span / (cut - u0))) + 1.0
    width = int(min(U_STEPS, need.max(initial=0.0)))
    grid = u0[:, None] + span[:, None] * _U_STEP_GRID[None, :width]
    grid[:, 0] = 1.0
    if width < U_STEPS:
        # Rounding may leave a row's last value an ulp above its cut: the cut itself ends
        # every row's grid, alone or in a batch.
        grid = np.concatenate([grid, cut[:, None]], axis=1)
    result: FloatArray = np.maximum(grid, cut[:, None])
    return result


def _search_many(
    k: FloatArray,
    m: FloatArray,
    u0: FloatArray,
    tol: FloatArray,
    screen_tol: FloatArray,
    hint: FloatArray,
    lam_hint: FloatArray,
    floor: FloatArray,
) -> tuple[BoolArray, SabinBiarcs, tuple[FloatArray, ...]]:
    """From each row's ``u0`` (own spiral, tolerance, previous span ``hint`` and join parameter
    ``lam_hint``), the verified biarc reaching the largest ``u1`` found: a first grid around
    the hints (or a geometric grid over ``(u0, 1]`` and three ``λ``, cut below ``floor``, see
    :func:`_first_scan`), refining rounds, then the proof of the best candidates."""
    n = k.size
    if n == 1 and SEARCH_ONE_IN_FLOATS:
        return _search_one(k, m, u0, tol, screen_tol, hint, lam_hint, floor)
    hint, lam_hint = hint.copy(), lam_hint.copy()
    span = 1.0 - u0
    full = u0[:, None] + span[:, None] * _U_STEP_GRID[None, :]
    full[:, 0] = 1.0
    near = np.minimum(u0[:, None] + hint[:, None] * _HINT_SCALE[None, :], 1.0)
    hinted = (hint > 0.0) & (hint < span)
    lam_full = np.broadcast_to(_LAMBDA_GRID, (n, LAMBDAS))
    lam_scan = np.broadcast_to(_SCAN_LAMBDA_GRID, (n, SCAN_LAMBDAS))
    lam_near = np.clip(
        lam_hint[:, None] + _HINT_LAMBDA_GRID[None, :],
        LAMBDA_MARGIN,
        1.0 - LAMBDA_MARGIN,
    )

    u_top, lam_top, has = np.zeros(n), np.full(n, 0.5), np.zeros(n, dtype=bool)
    width = np.full(n, 1.0 / LAMBDAS)
    # Every u1 each row has tried (NaN pads the rows a round left out).
    tried = np.empty((n, 0))

    def note(rows: npt.NDArray[np.intp], grid: FloatArray) -> None:
        nonlocal tried
        more = np.full((n, grid.shape[1]), np.nan)
        more[rows] = grid
        tried = np.concatenate([tried, more], axis=1)

    def take(rows: npt.NDArray[np.intp], rnd: _Round, w: float) -> None:
        if rows.size == 0:
            return
        top_u, top_l, ok = _top(rnd)
        # A retry keeps the hinted round's fit where that reaches further.
        better = ok & (~has[rows] | (top_u > u_top[rows]))
        up = rows[better]
        u_top[up], lam_top[up], has[up], width[up] = top_u[better], top_l[better], True, w
        note(rows, rnd.grid)

    def first(rows: npt.NDArray[np.intp], grid: FloatArray, lams: FloatArray, w: float) -> None:
        if rows.size:
            take(rows, _evaluate(k[rows], m[rows], u0[rows], grid, lams, screen_tol[rows]), w)

    def reach_end(rows: npt.NDArray[np.intp], rnd: _Round) -> BoolArray:
        _, top_l, ok = _top(rnd)
        u_top[rows[ok]], lam_top[rows[ok]], has[rows[ok]] = 1.0, top_l[ok], True
        return ok

    # The spiral's end is worth a finer scan of the join parameter: reaching it ends the walk.
    # A row's first piece seldom reaches it: there, the end's scan shares a numpy pass with
    # the scan below (a pass costs more than its candidates).
    longest = u0 + hint * 2.0**HINT_OCTAVES
    ends = np.flatnonzero((hint > 0.0) & (~hinted | (longest >= 1.0)))
    if ends.size:
        lam_end = np.broadcast_to(_END_LAMBDA_GRID, (ends.size, END_LAMBDAS))
        ones = np.ones((ends.size, 1))
        reach_end(ends, _evaluate(k[ends], m[ends], u0[ends], ones, lam_end, screen_tol[ends]))
    fresh = np.flatnonzero(hint <= 0.0)
    if fresh.size:
        grid = _first_scan(u0[fresh], floor[fresh])
        at_end, scanned = _evaluate_with_end(
            k[fresh], m[fresh], u0[fresh], grid, lam_scan[fresh], screen_tol[fresh]
        )
        rest = ~reach_end(fresh, at_end)
    # Rows without a hint scan the geometric grid with a few join parameters; the bracket of
    # the longest fit then serves as their hint.
    scan = np.flatnonzero(~hinted & ~has)
    if fresh.size:
        take(fresh[rest], _subset(scanned, rest), SCAN_WIDTH)
    later = scan[hint[scan] > 0.0]
    first(later, full[later], lam_scan[later], SCAN_WIDTH)
    hinted &= ~has
    hint[scan] = np.where(has[scan], (u_top[scan] - u0[scan]) * 2.0**0.25, 0.0)
    lam_hint[scan] = lam_top[scan]
    hinted[scan] = has[scan] & (u_top[scan] < 1.0)
    has[scan] &= u_top[scan] >= 1.0
    near = np.minimum(u0[:, None] + hint[:, None] * _HINT_SCALE[None, :], 1.0)
    lam_near = np.clip(
        lam_hint[:, None] + _HINT_LAMBDA_GRID[None, :],
        LAMBDA_MARGIN,
        1.0 - LAMBDA_MARGIN,
    )
    hrows = np.flatnonzero(hinted)
    first(
        hrows,
        np.concatenate([np.ones((hrows.size, 1)), near[hrows]], axis=1),
        lam_near[hrows],
        2.0 * HINT_LAMBDA / (HINT_LAMBDAS - 1),
    )
    # Retry on the full grid where nothing fits or the hinted grid's longest piece fits
    # (unless that grid reached the spiral's end, in which case the bracket is closed).
    longest = u0 + hint * 2.0**HINT_OCTAVES
    retry = hinted & (~has | ((u_top == near[:, 0]) & (longest < 1.0)))
    retry[scan] = False
    again = np.flatnonzero(retry)
    first(again, full[again], lam_full[again], 1.0 / LAMBDAS)

    refining = has & (u_top < 1.0)
    u_star = u_top.copy()
    steps, lam_steps = _REFINE_GRID, _REFINE_LAMBDA_GRID
    for _ in range(REFINE_ROUNDS):
        rows = np.flatnonzero(refining)
        if rows.size == 0:
            break
        # The next value above the longest fit among all tried (grids differ between rows).
        seen = tried[rows]
        above = np.where(seen > u_top[rows, None], seen, np.inf).min(axis=1, initial=np.inf)
        hi = np.where(np.isfinite(above), above, 1.0)
        grid = u_top[rows, None] + (hi - u_top[rows])[:, None] * steps[None, :]
        lams = np.clip(
            lam_top[rows, None] + width[rows, None] * lam_steps[None, :],
            LAMBDA_MARGIN,
            1.0 - LAMBDA_MARGIN,
        )
        rnd = _evaluate(k[rows], m[rows], u0[rows], grid, lams, screen_tol[rows], _SAMPLE_T)
        top_u, top_l, ok = _top(rnd)
        # Rows whose refined window has no fit keep their earlier (still valid) candidates.
        keep = rows[ok]
        u_top[keep], lam_top[keep] = top_u[ok], top_l[ok]
        u_star[keep] = _crossing(rnd, top_u, screen_tol[rows])[ok]
        note(rows, grid)
        refining[rows] = ok & (top_u < 1.0)
        width[rows] *= 2.0 / (REFINE_LAMBDAS - 1)

    # The sampled screen slightly underestimates; rather than search again with a lower
    # target, the proof tries the longest fit and a ladder of slightly shorter pieces: the
    # first rungs for every row, the rest only where those fail.
    # The interpolated crossing goes first: the proof, not the screen, decides.
    first_u = np.stack([u_star, u_top, u0 + (u_top - u0) * LADDER[0]], axis=1)
    found, chosen, devs = _prove(k, m, u0, tol, first_u, lam_top, has)
    redo = np.flatnonzero(has & ~found)
    if redo.size:
        more_u = u0[redo, None] + (u_top - u0)[redo, None] * LADDER[None, 1:]
        f2, c2, d2 = _prove(k[redo], m[redo], u0[redo], tol[redo], more_u, lam_top[redo], has[redo])
        found[redo] = f2
        for name in SabinBiarcs.__slots__:
            np.asarray(getattr(chosen, name))[redo] = getattr(c2, name)
        for mine, theirs in zip(devs, d2, strict=True):
            mine[redo] = theirs
    return found, chosen, devs


def _search_one(
    k: FloatArray,
    m: FloatArray,
    u0: FloatArray,
    tol: FloatArray,
    screen_tol: FloatArray,
    hint: FloatArray,
    lam_hint: FloatArray,
    floor: FloatArray,
) -> tuple[BoolArray, SabinBiarcs, tuple[FloatArray, ...]]:
    """:func:`_search_many` of one row, its bookkeeping in floats (:func:`_top_one`,
    :func:`_crossing_one`): the same rounds, the same numbers (each round's arrays are
    numpy's, with one row), the same result."""
    start, target = float(u0[0]), float(screen_tol[0])
    h, lam_h = float(hint[0]), float(lam_hint[0])
    span = 1.0 - start
    full = start + span * _U_STEP_GRID
    full[0] = 1.0
    hinted = 0.0 < h < span
    u_top, lam_top, has, width = 0.0, 0.5, False, 1.0 / LAMBDAS
    tried: list[float] = []

    def near_grid(h: float, lam_h: float) -> tuple[FloatArray, FloatArray]:
        near = np.minimum(start + h * _HINT_SCALE, 1.0)
        lams = np.clip(lam_h + _HINT_LAMBDA_GRID, LAMBDA_MARGIN, 1.0 - LAMBDA_MARGIN)
        return near, lams

    def take(rnd: _Round, w: float) -> None:
        nonlocal u_top, lam_top, has, width
        top_u, top_l, ok = _top_one(rnd, target)
        if ok and (not has or top_u > u_top):
            u_top, lam_top, has, width = top_u, top_l, True, w
        tried.extend(rnd.grid[0].tolist())

    def first(grid: FloatArray, lams: FloatArray, w: float) -> None:
        take(_evaluate(k, m, u0, grid[None, :], lams[None, :], screen_tol), w)

    def reach_end(rnd: _Round) -> bool:
        nonlocal u_top, lam_top, has
        _, top_l, ok = _top_one(rnd, target)
        if ok:
            u_top, lam_top, has = 1.0, top_l, True
        return ok

    near, lam_near = near_grid(h, lam_h)
    scanned = None
    if h > 0.0 and (not hinted or start + h * 2.0**HINT_OCTAVES >= 1.0):
        ones = np.ones((1, 1))
        reach_end(_evaluate(k, m, u0, ones, _END_LAMBDA_GRID[None, :], screen_tol))
    elif h <= 0.0:
        grid = _first_scan(u0, floor)
        at_end, scanned = _evaluate_with_end(k, m, u0, grid, _SCAN_LAMBDA_GRID[None, :], screen_tol)
        reach_end(at_end)
    scan = not hinted and not has
    if scan and scanned is not None:
        take(scanned, SCAN_WIDTH)
    elif scan:
        first(full, _SCAN_LAMBDA_GRID, SCAN_WIDTH)
    hinted = hinted and not has
    if scan:
        h = (u_top - start) * 2.0**0.25 if has else 0.0
        lam_h = lam_top
        hinted = has and u_top < 1.0
        has = has and u_top >= 1.0
        near, lam_near = near_grid(h, lam_h)
    if hinted:
        first(np.concatenate([[1.0], near]), lam_near, 2.0 * HINT_LAMBDA / (HINT_LAMBDAS - 1))
    longest = start + h * 2.0**HINT_OCTAVES
    if hinted and not scan and (not has or (u_top == near[0] and longest < 1.0)):
        first(full, _LAMBDA_GRID, 1.0 / LAMBDAS)

    refining = has and u_top < 1.0
    u_star = u_top
    for _ in range(REFINE_ROUNDS):
        if not refining:
            break
        above = min((u for u in tried if u > u_top), default=math.inf)
        hi = above if math.isfinite(above) else 1.0
        grid = u_top + (hi - u_top) * _REFINE_GRID
        lams = np.clip(lam_top + width * _REFINE_LAMBDA_GRID, LAMBDA_MARGIN, 1.0 - LAMBDA_MARGIN)
        rnd = _evaluate(k, m, u0, grid[None, :], lams[None, :], screen_tol, _SAMPLE_T)
        top_u, top_l, ok = _top_one(rnd, target)
        if ok:
            u_top, lam_top = top_u, top_l
            u_star = _crossing_one(rnd, top_u, target)
        tried.extend(grid.tolist())
        refining = ok and top_u < 1.0
        width *= 2.0 / (REFINE_LAMBDAS - 1)

    rungs = np.array([[u_star, u_top, start + (u_top - start) * float(LADDER[0])]])
    lam, fits = np.array([lam_top]), np.array([has])
    result = _prove(k, m, u0, tol, rungs, lam, fits)
    if has and not result[0][0]:
        more = start + (u_top - start) * LADDER[None, 1:]
        result = _prove(k, m, u0, tol, more, lam, fits)
    return result


def _top_one(rnd: _Round, target: float) -> tuple[float, float, bool]:
    """:func:`_top` of a one-row round, in floats."""
    dev: list[list[float]] = rnd.dev[0].tolist()
    grid: list[float] = rnd.grid[0].tolist()
    at = _longest_fit(grid, dev, target)
    row = max(at, 0)  # numpy's argmax where nothing fits
    return grid[row], float(rnd.lams[0, _argmin(dev[row])]), at >= 0


def _longest_fit(grid: list[float], dev: list[list[float]], target: float) -> int:
    """Index of the largest ``u1`` with a fitting ``λ`` (numpy's first maximum), -1 if none."""
    at, longest = -1, -math.inf
    for j, (u, row) in enumerate(zip(grid, dev, strict=True)):
        if u > longest and any(d <= target for d in row):
            at, longest = j, u
    return at


def _argmin(values: list[float]) -> int:
    """``np.argmin``: the first NaN, else the first minimum."""
    best = 0
    for j, v in enumerate(values):
        if v != v:
            return j
        if v < values[best]:
            best = j
    return best


def _nanmin(values: list[float]) -> float:
    """``np.min``: NaN if any value is NaN."""
    return values[_argmin(values)]


def _crossing_one(rnd: _Round, u_top: float, target: float) -> float:
    """:func:`_crossing` of a one-row round, in floats."""
    dev: list[list[float]] = rnd.dev[0].tolist()
    grid: list[float] = rnd.grid[0].tolist()
    at = max(_longest_fit(grid, dev, target), 0)
    nxt = min(at + 1, len(grid) - 1)
    d_top, d_next = _nanmin(dev[at]), _nanmin(dev[nxt])
    t = numpy_divide(target - d_top, d_next - d_top)
    t = t if t != t else min(max(t, 0.0), 1.0)
    t = t if math.isfinite(t) and nxt > at else 0.0
    return u_top + (grid[nxt] - u_top) * t


def _prove(
    k: FloatArray,
    m: FloatArray,
    u0: FloatArray,
    tol: FloatArray,
    cand_u: FloatArray,
    lam_top: FloatArray,
    has: BoolArray,
) -> tuple[BoolArray, SabinBiarcs, tuple[FloatArray, ...]]:
    """Per row the first of the piece ends ``cand_u`` (rows, rungs) whose biarc with join
    parameter ``lam_top`` is proven within ``tol``."""
    n, rep = cand_u.shape
    if n == 1 and rep <= PROVE_IN_FLOATS:
        return _prove_one(float(k[0]), float(m[0]), float(u0[0]), float(tol[0]),
                          cand_u[0].tolist(), float(lam_top[0]), bool(has[0]))  # fmt: skip
    cand_l = np.repeat(lam_top[:, None], rep, axis=1)
    cand_ok = np.repeat(has[:, None], rep, axis=1)
    kk, mm, u00, tt = (np.repeat(v, rep) for v in (k, m, u0, tol))
    uu = np.where(cand_ok, cand_u, 1.0).ravel()
    with np.errstate(invalid="ignore", divide="ignore"):
        b = sabin_biarcs(kk, mm, u00, uu, cand_l.ravel())
        usable = cand_ok.ravel() & b.ok
        if n * rep <= PROVE_IN_FLOATS:
            d0, w0, d1, w1 = _verify_lazily(kk, mm, u00, b, tt, usable.reshape(n, rep))
        else:
            d0, w0, d1, w1 = verify(kk, mm, u00, b, tt)
    good = ((d0 <= tt) & (d1 <= tt) & usable).reshape(n, rep)
    pick = np.arange(n) * rep + np.argmax(good, axis=1)
    chosen = SabinBiarcs(*(np.asarray(getattr(b, f))[pick] for f in SabinBiarcs.__slots__))
    found: BoolArray = np.asarray(good.any(axis=1))
    # Rows without a proven rung have no deviations (the lazy proof does not measure them all).
    devs = tuple(np.where(found, d[pick], np.nan) for d in (d0, w0, d1, w1))
    return found, chosen, devs


def _prove_one(
    k: float, m: float, u0: float, tol: float, cand_u: list[float], lam: float, has: bool
) -> tuple[BoolArray, SabinBiarcs, tuple[FloatArray, ...]]:
    """:func:`_prove` of one row in floats: each rung's biarc is built only when the rungs
    before it have failed (:func:`_verify_lazily`'s order), the same numbers."""
    tried: set[float] = set()
    for u1 in cand_u if has else ():
        if u1 in tried:  # the same biarc fails again (the crossing may be the longest fit)
            continue
        tried.add(u1)
        b = sabin_biarc_one(k, m, u0, u1, lam)
        if not b.ok:
            continue
        d0, w0, d1, w1 = verify_one(k, m, u0, b, tol, lazily=True)
        if d0 <= tol and d1 <= tol:
            devs = tuple(np.array([d]) for d in (d0, w0, d1, w1))
            return np.array([True]), SabinBiarcs.of([b]), devs
    # No rung proven: the row's biarc and deviations mean nothing (as for the arrays).
    return (
        np.array([False]),
        SabinBiarcs.of([NO_BIARC]),
        tuple(np.full(1, np.nan) for _ in range(4)),
    )


def _verify_lazily(
    k: FloatArray, m: FloatArray, u0: FloatArray, b: SabinBiarcs, tol: FloatArray, usable: BoolArray
) -> tuple[FloatArray, ...]:
    """``verify`` of a few candidates (rows × rungs), one arc at a time in floats, in order,
    stopping at each row's first proven rung: the rungs after it, and the second arc of a rung
    whose first arc fails, stay unmeasured (NaN, never proven). Where measured, the numbers
    are those of ``verify``."""
    d0, w0, d1, w1 = (np.full(b.u1.shape[0], np.nan) for _ in range(4))
    ax, ay = canonical.point(k, m, u0)
    bx, by = canonical.point(k, m, b.u1)
    columns = (
        *(k, m, u0, tol, ax, ay, bx, by, b.gx, b.gy, b.split, b.u1),
        *(b.phi0, np.cos(b.phi0), np.sin(b.phi0), b.kappa0),
        *(b.psi, np.cos(b.psi), np.sin(b.psi), b.kappa1),
    )
    values = list(zip(*(np.asarray(c).tolist() for c in columns), strict=True))
    rungs = usable.shape[1]
    proven: set[int] = set()
    for i in np.flatnonzero(usable).tolist():
        row = i // rungs
        if row in proven:
            continue
        kk, mm, uu, tt, xa, ya, xb, yb, gx, gy, split, u1 = values[i][:12]
        phi0, c0, s0, kappa0, psi, c1, s1, kappa1 = values[i][12:]
        d0[i], w0[i] = one_arc_deviation(
            kk, mm, xa, ya, phi0, c0, s0, kappa0, gx, gy, uu, split, tt
        )
        if d0[i] <= tt:
            d1[i], w1[i] = one_arc_deviation(
                kk, mm, gx, gy, psi, c1, s1, kappa1, xb, yb, split, u1, tt
            )
            if d1[i] <= tt:
                proven.add(row)
    return d0, w0, d1, w1


def fewest_chains(
    k: FloatArray,
    m: FloatArray,
    tol: FloatArray,
    max_arcs: npt.NDArray[np.intp],
    first_span: FloatArray | None = None,
) -> list[Chain | None]:
    """Greedy longest verified biarcs over ``[0, 1]`` for each spiral, then the tail merge.

    The walk runs in lockstep over the batch; a spiral's chain is None where it fails or
    would need more than ``max_arcs`` arcs. A step whose previous span fits ``NEWTON_REACH``
    more times before the end tries ``newton_step`` from that piece first; the grids of
    :func:`_search_many` take the first step, the pieces near the end and any row the Newton
    step leaves.

    **Tail merge.** Where a step ends within ``CLOSE_REACH`` of its span from the spiral's end
    (so the next step will likely reach the end), the biarc just found and the rest of the
    spiral are tried as one triarc from that biarc's start: proven, it closes the chain (the
    chain the tail merge would give after the next step, or a shorter one). A single spiral
    tries it at once and skips the last step; a batch goes on walking in lockstep and tries
    every row's such points in order after the walk (one call for all rows, not one per
    step): the same chains. Rows closed by none get the tail merge of their last two biarcs.
    """
    # A far step (Newton's) is never checked for the tail merge: it must never end near the end.
    if CLOSE_REACH > NEWTON_REACH:
        raise ValueError("CLOSE_REACH must not exceed NEWTON_REACH")
    n = k.size
    parts: list[list[list[float]]] = [[[0.0], [0.0], [0.0], [], [0.0], [], []] for _ in range(n)]
    failed = np.zeros(n, dtype=bool)
    u0, hint, lam_hint = np.zeros(n), np.zeros(n), np.full(n, 0.5)
    floor = np.zeros(n) if first_span is None else first_span
    jacobian = np.tile(np.array(NEWTON_JACOBIAN), (n, 1, 1))
    # Per row: the arc counts before each biarc that ended near the spiral's end, not yet
    # tried as a triarc's start (a batch tries them after the walk), and the last one tried.
    close_at: list[list[int]] = [[] for _ in range(n)]
    last_tried = [-1] * n
    closed = np.zeros(n, dtype=bool)

    def record(rows: npt.NDArray[np.intp], found: BoolArray, b: SabinBiarcs, devs: Devs) -> None:
        pick = np.flatnonzero(found)
        at = rows[pick]
        bx, by = canonical.point(k[at], m[at], b.u1[pick])
        d0, w0, d1, w1 = (d[pick] for d in devs)
        columns = (b.u1, b.gx, b.gy, b.psi, b.phi1, b.kappa0, b.kappa1, b.split, b.lam)
        u1s, gxs, gys, psis, phi1s, k0s, k1s, splits, lams = (c[pick].tolist() for c in columns)
        for i, r in enumerate(at.tolist()):
            u1 = u1s[i]
            jx, jy, phi, kappa, s, dev, u_dev = parts[r]
            jx += [gxs[i], float(bx[i])]
            jy += [gys[i], float(by[i])]
            phi += [psis[i], phi1s[i]]
            kappa += [k0s[i], k1s[i]]
            s += [splits[i], u1]
            dev += [float(d0[i]), float(d1[i])]
            u_dev += [float(w0[i]), float(w1[i])]
            hint[r], u0[r], lam_hint[r] = u1 - u0[r], u1, lams[i]
            if len(kappa) + (2 if u1 < 1.0 else 0) > max_arcs[r] or not u1 > s[-3]:
                failed[r] = True

    def close(pairs: list[tuple[int, int]]) -> None:
        """For each ``(row, keep)`` in order, the row's chain from its first ``keep`` arcs on
        replaced by a proven triarc from that joint to the spiral's end, unless an earlier pair
        has closed the row or no triarc is proven."""
        rows = np.array([r for r, _ in pairs])
        u_a = np.array([parts[r][4][keep] for r, keep in pairs])
        tails = best_triarcs(k[rows], m[rows], u_a, tol[rows])
        for (r, keep), tail in zip(pairs, tails, strict=True):
            last_tried[r] = keep
            if tail is None or closed[r]:
                continue
            t, dev, u_dev = tail
            pieces = (t.x[0], t.y[0], t.phi[0], t.kappa[0], t.s[0], dev, u_dev)
            for part, piece in zip(parts[r], pieces, strict=True):
                del part[keep:]  # arcs, or joints: the triarc's first is the chain's ``keep``
                part += piece.tolist()
            u0[r], closed[r], failed[r] = 1.0, True, False

    def stepped_to(rows: npt.NDArray[np.intp]) -> npt.NDArray[np.intp]:
        """After a step of each of ``rows``: where it ends within ``CLOSE_REACH`` of its span
        from the spiral's end, the tail merge may start at the step's start (one spiral tries
        it at once). The rows that walk on."""
        rows = rows[~failed[rows] & (u0[rows] < 1.0)]
        near = rows[u0[rows] + hint[rows] * CLOSE_REACH >= 1.0].tolist()
        for r in near:
            close_at[r].append(len(parts[r][3]) - 2)
        if n == 1 and near:
            close([(r, close_at[r].pop()) for r in near])
        return rows[~closed[rows]]

    active = np.arange(n)
    while active.size:
        # Far from the spiral's end, Newton's method from the previous piece comes first, step
        # after step while the row stays far (a far step never ends near the end). Then one
        # search for every row whose Newton step missed, that Newton's method does not take,
        # or whose Newton steps have just brought it near the end: rows at different steps
        # search together. Each row's own sequence of steps is the same either way.
        stepped = np.zeros(n, dtype=bool)  # the row's last Newton step this round was found
        walking = active
        while walking.size:
            far = u0[walking] + hint[walking] * NEWTON_REACH < 1.0
            newton = walking[(hint[walking] > 0.0) & far]
            if newton.size == 0:
                break
            found, b, devs, jacobian[newton] = newton_step(
                k[newton],
                m[newton],
                u0[newton],
                tol[newton],
                hint[newton],
                lam_hint[newton],
                jacobian[newton],
            )
            record(newton, found, b, devs)
            stepped[newton] = found
            walking = newton[found & ~failed[newton]]
        ran = stepped_to(active[stepped[active]])
        pending = np.sort(np.concatenate([active[~stepped[active]], ran]))
        searched = []
        for factor in SCREEN_FACTORS:
            if pending.size == 0:
                break
            found, b, devs = _search_many(
                k[pending],
                m[pending],
                u0[pending],
                tol[pending],
                factor * tol[pending],
                hint[pending],
                lam_hint[pending],
                floor[pending],
            )
            record(pending, found, b, devs)
            searched.append(pending[found])
            pending = pending[~found]
        failed[pending] = True
        active = stepped_to(np.sort(np.concatenate([np.empty(0, dtype=np.intp), *searched])))
    # What is left to try, in each row's order (all in one call): its points near the end,
    # then the merge of its last two biarcs (unless that was one of them).
    pairs = []
    for r in range(n):
        arcs = len(parts[r][3])
        last = [arcs - 4] if not failed[r] and arcs >= 4 else []
        tries = close_at[r] + [j for j in last if j not in close_at[r] and j != last_tried[r]]
        pairs += [(r, keep) for keep in tries] if not closed[r] else []
    if pairs:
        close(pairs)
    return [
        None if failed[r] else Chain(*(np.array(v, dtype=np.float64) for v in parts[r]))
        for r in range(n)
    ]
