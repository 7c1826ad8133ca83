"""The core's entry points: one spiral, or many at once, under explicit limits."""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Literal, NamedTuple, get_args

import numpy as np

from . import canonical
from .assemble import Frames, segment_columns, spiral_lengths, splines
from .assemble_one import assemble_one
from .errors import GeometryError
from .fewest import fewest_batch
from .spiral import Spiral
from .subdivide import IntArray, Kept, merge, subdivide
from .subdivide_one import kept, subdivide_one
from .types import ArcSpline, BoolArray, FloatArray, SegmentColumns

Strategy = Literal["subdivide", "fewest-arcs"]
STRATEGIES: tuple[str, ...] = get_args(Strategy)

_EPS = float(np.finfo(np.float64).eps)

#: World coordinates are ``B0 + a·R·p``: each output coordinate carries a rounding error of a
#: few ulps of the largest coordinate. The core aims below the tolerance by this many ulps of
#: the spiral's coordinate scale, so the guarantee holds for the numbers it hands out.
ROUNDING_MARGIN_ULPS = 32.0

#: An arc's centre and radius round by a few ulps of ``‖C‖ + r``; arcs for which this many
#: ulps still fit the tolerance need no measurement of it.
PLACEMENT_SCREEN_ULPS = 64.0


@dataclass(frozen=True, slots=True)
class Limits:
    """Bounds that keep every request finite.

    ``max_segments`` caps the segments of one arc spline. ``min_relative_tolerance`` is the
    smallest tolerance accepted, as a fraction of the spiral's chord; below it (or below what
    double precision can represent at the spiral's coordinates) the core refuses rather than
    return an answer it cannot vouch for.
    """

    max_segments: int = 10_000
    min_relative_tolerance: float = 1e-10


DEFAULT_LIMITS = Limits()


def _rounding_margin(spiral: Spiral) -> float:
    return ROUNDING_MARGIN_ULPS * _EPS * (spiral.coordinate_scale + spiral.chord)


def min_tolerance(spiral: Spiral, limits: Limits = DEFAULT_LIMITS) -> float:
    """The smallest tolerance the core accepts for ``spiral``.

    The larger of ``limits.min_relative_tolerance × chord`` and four rounding margins, so
    that at least three quarters of the tolerance is left for the approximation itself.
    """
    return max(limits.min_relative_tolerance * spiral.chord, 4.0 * _rounding_margin(spiral))


def _check_tolerance(spiral: Spiral, tolerance: float, limits: Limits) -> None:
    if not (isinstance(tolerance, int | float) and math.isfinite(tolerance) and tolerance > 0):
        raise GeometryError("tolerance", f"must be a finite number > 0, got {tolerance!r}")
    floor = min_tolerance(spiral, limits)
    if tolerance < floor:
        raise GeometryError(
            "tolerance",
            f"{tolerance:.6g} is below the smallest reachable tolerance {floor:.6g} for this "
            f"spiral (chord {spiral.chord:.6g}, coordinates up to {spiral.coordinate_scale:.6g}); "
            "double precision cannot deliver less",
            kind="tolerance_floor",
            limit=floor,
        )


def _check_strategy(strategy: str) -> None:
    if strategy not in STRATEGIES:
        raise GeometryError(
            "strategy", f"unknown strategy {strategy!r}; choose one of {', '.join(STRATEGIES)}"
        )


def approximate(
    spiral: Spiral,
    tolerance: float,
    strategy: Strategy = "subdivide",
    limits: Limits = DEFAULT_LIMITS,
) -> ArcSpline:
    """Approximate ``spiral`` by an arc spline within ``tolerance``.

    Raises :class:`GeometryError` for a tolerance that is not finite and positive, below
    :func:`min_tolerance`, an unknown strategy, or a result that would exceed
    ``limits.max_segments``.
    """
    (result,) = approximate_many([spiral], [tolerance], strategy, limits)
    if isinstance(result, GeometryError):
        raise result
    return result


def approximate_many(
    spirals: Sequence[Spiral],
    tolerances: Sequence[float],
    strategy: Strategy = "subdivide",
    limits: Limits = DEFAULT_LIMITS,
) -> list[ArcSpline | GeometryError]:
    """Approximate many spirals at once, vectorised across spirals (same order as given).

    A spiral whose tolerance or limits fail gets its :class:`GeometryError` in its place;
    the others are unaffected.
    """
    if len(spirals) != len(tolerances):
        raise ValueError("spirals and tolerances differ in length")
    _check_strategy(strategy)
    frames = Frames.of(spirals)
    valid = _valid_tolerances(frames, tolerances, limits)
    results: list[ArcSpline | GeometryError | None] = [None] * len(spirals)
    chosen = list(range(len(spirals)))
    if not valid.all():
        chosen = []
        for j in range(len(spirals)):
            try:
                if not valid[j]:  # the exact reason, or a tolerance the fast test did not take
                    _check_tolerance(spirals[j], tolerances[j], limits)
            except GeometryError as error:
                results[j] = error
                continue
            chosen.append(j)
    if chosen:
        if len(chosen) < len(spirals):
            frames = frames.take(np.array(chosen, dtype=np.intp))
        tol = np.array([tolerances[j] for j in chosen], dtype=np.float64)
        run = _fewest_batch if strategy == "fewest-arcs" else _subdivide_batch
        picked = [spirals[j] for j in chosen]
        for j, result in zip(chosen, run(picked, frames, tol, limits, strategy), strict=True):
            results[j] = result
    return [r for r in results if r is not None]


def _margins(frames: Frames) -> FloatArray:
    """:func:`_rounding_margin` of each spiral."""
    margin: FloatArray = ROUNDING_MARGIN_ULPS * _EPS * (frames.coordinate_scale + frames.chord)
    return margin


def _valid_tolerances(frames: Frames, tolerances: Sequence[float], limits: Limits) -> BoolArray:
    """Which tolerances :func:`_check_tolerance` accepts, for the common case of floats, in
    one vectorised test (the same arithmetic); ``False`` where it must look itself."""
    if not all(type(t) is float for t in tolerances):
        return np.zeros(len(tolerances), dtype=bool)
    tol = np.array(tolerances, dtype=np.float64)
    floor = np.maximum(limits.min_relative_tolerance * frames.chord, 4.0 * _margins(frames))
    with np.errstate(invalid="ignore"):
        valid: BoolArray = np.isfinite(tol) & (tol > 0.0) & (tol >= floor)
    return valid


def _subdivide_batch(
    spirals: list[Spiral],
    frames: Frames,
    tolerances: FloatArray,
    limits: Limits,
    strategy: str,
) -> list[ArcSpline | GeometryError]:
    """Strategy "subdivide": each spiral in floats (``subdivide_one``, ``assemble_one``)
    while the batch is small, the rest with numpy (``subdivide``, ``segment_columns``); the
    two give the same numbers, so the split only decides the cost."""
    n = len(spirals)
    k, m = canonical.coefficients(frames.turn_angle_rad)
    target = (tolerances - _margins(frames)) / frames.scale
    max_biarcs = limits.max_segments // 2
    lengths = spiral_lengths(k, m, frames.scale)
    results: list[ArcSpline | GeometryError | None] = [None] * n
    subdivided: list[Kept] = []  # in floats, to be assembled with numpy
    rest: list[int] = []  # to be subdivided with numpy
    floats = True
    for j in range(n):
        rows = (
            subdivide_one(float(k[j]), float(m[j]), float(target[j]), max_biarcs)
            if floats
            else None
        )
        if rows is None:  # numpy is cheaper from here, or must decide this spiral
            rest.append(j)
            continue
        floats = _floats_cheaper(2 * len(rows) - 1, n - 1 - j)
        spline = assemble_one(
            rows,
            spirals[j],
            float(k[j]),
            float(m[j]),
            float(tolerances[j]),
            float(lengths[j]),
            strategy,
            PLACEMENT_SCREEN_ULPS,
        )
        if spline is None:
            subdivided.append(kept(rows, j))
        else:
            results[j] = spline
    failure = [""] * n
    if rest:
        index = np.array(rest, dtype=np.intp)
        outcome = subdivide(k[index], m[index], target[index], max_biarcs)
        for j, why in zip(rest, outcome.failure, strict=True):
            failure[j] = why
        subdivided.append(outcome.kept._replace(spiral=index[outcome.kept.spiral]))
    if subdivided:
        batch = _Batch(spirals, frames, k, m, tolerances, lengths, strategy, limits)
        _assemble(merge(subdivided), failure, batch, results)
    done = [r for r in results if r is not None]
    assert len(done) == n, "every spiral has a result"
    return done


def _floats_cheaper(pieces: int, remaining: int) -> bool:
    """Whether ``remaining`` more spirals like one of ``pieces`` pieces are cheaper in floats
    than with numpy: a cost model, in the time of one piece in floats (about 7 µs), fitted
    on the build machine (the paper's spiral at 7 to 53 pieces, alone in floats and in numpy
    batches of 2, 8 and 32): a spiral in floats costs its pieces and 3.5 more; numpy's
    subdivision and assembly cost 38 per level (log2 of the pieces) and 0.07 per piece of
    each spiral. Either way the numbers are the same.
    """
    return remaining * (pieces + 3.5 - 0.07 * pieces) <= 38.0 * math.log2(pieces + 1)


class _Batch(NamedTuple):
    """What the numpy assembly needs of a batch, one row per spiral."""

    spirals: list[Spiral]
    frames: Frames
    k: FloatArray
    m: FloatArray
    tolerances: FloatArray
    lengths: FloatArray
    strategy: str
    limits: Limits


def _assemble(
    kept_biarcs: Kept,
    failure: list[str],
    batch: _Batch,
    results: list[ArcSpline | GeometryError | None],
) -> None:
    """The numpy assembly of the spirals ``kept_biarcs`` names and of those that failed
    (``failure``), into ``results``."""
    spirals, tolerances = batch.spirals, batch.tolerances
    failed = [j for j, why in enumerate(failure) if why]
    which = np.union1d(kept_biarcs.spiral, np.array(failed, dtype=np.intp))
    sub = kept_biarcs._replace(spiral=np.searchsorted(which, kept_biarcs.spiral))
    frames = batch.frames if which.size == len(spirals) else batch.frames.take(which)
    columns = segment_columns(sub, batch.k[which], batch.m[which], frames)
    row_spiral = np.repeat(sub.spiral, 2)
    tol = tolerances[which]
    done = splines(columns, row_spiral, batch.lengths[which], tol, batch.strategy)
    count = which.size
    unplaceable = _any_per_spiral(_unplaceable_rows(columns, tol[row_spiral]), row_spiral, count)
    overflowed = _any_per_spiral(~_finite_rows(columns), row_spiral, count)
    for i, j in enumerate(which.tolist()):
        if failure[j]:
            results[j] = _failure(spirals[j], float(tolerances[j]), failure[j], batch.limits)
        elif overflowed[i]:
            results[j] = GeometryError(
                "tolerance",
                "the arc spline overflowed double precision for this spiral",
                kind="precision",
            )
        elif unplaceable[i]:
            results[j] = _unplaceable(float(tolerances[j]), done[i])
        else:
            results[j] = done[i]


def _any_per_spiral(rows: BoolArray, row_spiral: IntArray, n: int) -> BoolArray:
    """Whether any row of each spiral is set."""
    if n == 1:
        return np.array([bool(rows.any())])
    result = np.zeros(n, dtype=bool)
    result[row_spiral[rows]] = True
    return result


def _finite_rows(columns: SegmentColumns) -> BoolArray:
    """A last guard: no result leaves the core with NaN or infinite numbers in it.

    One sum per column first: a sum is finite when every term is (it could overflow only
    past 1e300, far beyond the core's bounds, and then the row-by-row test below decides).
    """
    is_arc = columns.is_arc
    radius = columns.radius if is_arc.all() else np.where(is_arc, columns.radius, 0.0)
    checked = (columns.start, columns.end, columns.max_deviation, columns.center, radius)
    if math.isfinite(sum(float(np.add.reduce(c, axis=None)) for c in checked)):
        return np.ones(len(columns), dtype=bool)
    circle = np.isfinite(columns.center).all(axis=1) & np.isfinite(columns.radius)
    finite: BoolArray = (
        np.isfinite(columns.start).all(axis=1)
        & np.isfinite(columns.end).all(axis=1)
        & np.isfinite(columns.max_deviation)
        & (~columns.is_arc | circle)
    )
    return finite


def _unplaceable_rows(columns: SegmentColumns, tolerance: FloatArray) -> BoolArray:
    """Rows whose deviation plus measured placement error exceeds their tolerance.

    The gap is a few ulps of ``‖C‖ + r``; only rows where ``PLACEMENT_SCREEN_ULPS`` of those
    would not fit are measured (nearly always none), the others certainly fit.
    """
    centre = np.abs(columns.center)
    size = np.maximum(centre[:, 0], centre[:, 1]) + columns.radius
    screen = columns.is_arc & (
        columns.max_deviation + PLACEMENT_SCREEN_ULPS * _EPS * size > tolerance
    )
    rows = np.zeros(len(columns), dtype=bool)
    if screen.any():
        which = np.flatnonzero(screen)
        error = _placement_error(columns, which)
        rows[which] = columns.max_deviation[which] + error > tolerance[which]
    return rows


def _placement_error(columns: SegmentColumns, which: IntArray | None = None) -> FloatArray:
    """How far rounding has moved each arc (rows ``which``, default all), measured: the larger
    of ``|‖S − C‖ − r|`` at its start and end, in extended precision. Centre and radius are
    doubles, each off by ulps of its own size, which for the huge radii of nearly straight
    spirals can exceed a tight tolerance; the end points lie where the method put them, so
    the gap shows the error."""
    rows = np.arange(len(columns)) if which is None else which
    is_arc = columns.is_arc[rows]
    centre = columns.center[rows].astype(np.longdouble)
    radius = np.where(is_arc, columns.radius[rows], 0.0).astype(np.longdouble)
    gaps = [
        np.abs(
            np.sqrt(np.add.reduce(np.square(p[rows].astype(np.longdouble) - centre), 1)) - radius
        )
        for p in (columns.start, columns.end)
    ]
    error: FloatArray = np.where(is_arc, np.maximum(*gaps), 0.0).astype(np.float64)
    return error


def _unplaceable(tolerance: float, spline: ArcSpline) -> GeometryError:
    worst = float(np.max(_placement_error(spline.columns)))
    return GeometryError(
        "tolerance",
        f"{tolerance:.6g} cannot be held in double precision for this spiral: its arcs have "
        f"radii up to {spline.stats.max_radius:.6g}, whose centres and radii round by up to "
        f"{worst:.3g}; raise the tolerance",
        kind="precision",
        limit=4.0 * worst,
    )


def _fewest_batch(
    spirals: list[Spiral],
    frames: Frames,
    tolerances: FloatArray,
    limits: Limits,
    strategy: str,
) -> list[ArcSpline | GeometryError]:
    """Strategy "fewest-arcs" (``arcspline.geometry.fewest``). Subdivision runs first: its result
    (or error) is kept wherever the greedy chain would not have fewer or equal segments."""
    baseline = _subdivide_batch(spirals, frames, tolerances, limits, strategy)
    target = tolerances - _margins(frames)
    return fewest_batch(spirals, tolerances, target, baseline, limits.max_segments)


def _failure(spiral: Spiral, tolerance: float, why: str, limits: Limits) -> GeometryError:
    if why == "segment_limit":
        return GeometryError(
            "tolerance",
            f"{tolerance:.6g} needs more than the limit of {limits.max_segments} segments for "
            "this spiral; raise the tolerance",
            kind="segment_limit",
            limit=float(limits.max_segments),
        )
    return GeometryError(
        "tolerance",
        f"{tolerance:.6g} cannot be reached in double precision for this spiral "
        f"(a piece became too short to split); raise the tolerance",
        kind="precision",
        limit=min_tolerance(spiral, limits),
    )
