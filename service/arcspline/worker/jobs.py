"""The jobs the worker processes run: pure functions, picklable in and out.

A job is a curve (as its request gave it, a :class:`~arcspline.geometry.CurveSpec`), a
tolerance, a strategy and the outputs asked for (writer name and options, see
``arcspline.outputs``). The functions here build the curve, approximate it (one job, or a
chunk of jobs through the core's ``approximate_many``), write the outputs and serialise the
response body to JSON, all inside the worker, so that encoding runs in parallel too. A job
the core or a writer refuses returns its error as a value.

Dependency direction: ``arcspline.worker.pool`` runs these; they import only the geometry
core, the outputs and orjson, never the web stack.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable, Sequence
from typing import Any, NamedTuple, TypeVar

import orjson

from arcspline.geometry import (
    COLUMN,
    ArcSpline,
    Curve,
    CurveSpec,
    GeometryError,
    Limits,
    SplineStats,
    StrategyName,
    approximate,
    approximate_many,
)
from arcspline.geometry.path_spline import PathSpline, SubpathSpline
from arcspline.geometry.paths import approximate_path
from arcspline.outputs import WRITERS, Part
from arcspline.outputs.gcode import GcodeError
from arcspline.paths import PathSpec

from .tooling import Tooled, Tooling, tool, write

#: An output asked for: a writer's name (``arcspline.outputs.WRITERS``) and its options.
Output = tuple[str, Any]

#: The outputs a JSON response carries, each under its writer's name (``null`` when not
#: asked for): the fields of the response schema.
JSON_OUTPUTS = ("gcode",)


class Job(NamedTuple):
    """One approximation request, as the worker needs it. (A named tuple: thousands cross
    the process boundary per second, and tuples pickle several times faster.)"""

    curve: CurveSpec
    tolerance: float
    strategy: StrategyName = "subdivide"
    outputs: tuple[Output, ...] = ()


class PathJob(NamedTuple):
    """One path to approximate: its spec (SVG data or the JSON form, built in the worker), a
    tolerance, a strategy, the outputs asked for (one document for the whole path), and the
    offset or machining that turns it into tool-centre paths (:mod:`.tooling`), if any."""

    path: PathSpec
    tolerance: float
    strategy: StrategyName = "subdivide"
    outputs: tuple[Output, ...] = ()
    tooling: Tooling | None = None


class Encoded(NamedTuple):
    """A job's response body, already JSON, with the counts the metrics need."""

    body: bytes
    arc_count: int
    line_count: int


class Document(NamedTuple):
    """A job's one output as the whole response (the preview's picture)."""

    body: bytes
    media_type: str


JobResult = Encoded | GeometryError | GcodeError

_IS_ARC, _SX, _SY, _EX, _EY, _CX, _CY, _RADIUS = (
    COLUMN[name]
    for name in ("is_arc", "start_x", "start_y", "end_x", "end_y", "center_x", "center_y", "radius")
)
_ANGLE, _SWEEP, _LENGTH, _U0, _U1, _DEV, _U_DEV = (
    COLUMN[name]
    for name in (
        "start_angle_rad", "sweep_rad", "length", "u_start", "u_end", "max_deviation",
        "u_at_max_deviation",
    )
)  # fmt: skip


def _segments(rows: list[list[float]]) -> list[dict[str, Any]]:
    """The response's segment objects of table rows (``u_*`` as the rows hold them)."""
    return [
        {
            "type": "arc",
            "start": [r[_SX], r[_SY]],
            "end": [r[_EX], r[_EY]],
            "center": [r[_CX], r[_CY]],
            "radius": r[_RADIUS],
            "direction": "ccw" if r[_SWEEP] > 0.0 else "cw",
            "start_angle_rad": r[_ANGLE],
            "sweep_rad": r[_SWEEP],
            "length": r[_LENGTH],
            "u_start": r[_U0],
            "u_end": r[_U1],
            "max_deviation": r[_DEV],
            "u_at_max_deviation": r[_U_DEV],
        }
        if r[_IS_ARC]
        else {
            "type": "line",
            "start": [r[_SX], r[_SY]],
            "end": [r[_EX], r[_EY]],
            "length": r[_LENGTH],
            "u_start": r[_U0],
            "u_end": r[_U1],
            "max_deviation": r[_DEV],
            "u_at_max_deviation": r[_U_DEV],
        }
        for r in rows
    ]


def _stats(s: SplineStats, tolerance: float, strategy: str) -> dict[str, Any]:
    return {
        "arc_count": s.arc_count,
        "line_count": s.line_count,
        "segment_count": s.segment_count,
        "max_deviation": s.max_deviation,
        "deviation_ratio": s.deviation_ratio,
        "mean_segment_deviation": s.mean_segment_deviation,
        "spline_length": s.spline_length,
        "min_radius": s.min_radius,
        "max_radius": s.max_radius,
        "tolerance": tolerance,
        "strategy": strategy,
    }


def finite_body(
    head: bytes, nulls: int, outputs: dict[str, str], arcs: int, lines: int
) -> Encoded | GeometryError:
    # orjson writes NaN and Infinity as null, and no number of the segments and statistics
    # may be null but the radii of a spline without arcs: counting nulls proves every number
    # finite at memchr speed, without another pass over the rows.
    if head.count(b"null") != nulls:
        return _NOT_FINITE
    texts = orjson.dumps({name: outputs.get(name) for name in JSON_OUTPUTS})
    body = b"".join((head[:-1], b",", texts[1:]))
    return Encoded(body=body, arc_count=arcs, line_count=lines)


def encode(spline: ArcSpline, outputs: dict[str, str]) -> Encoded | GeometryError:
    """The ``ApproximateResponse`` body of ``spline`` and its written ``outputs`` as JSON
    bytes (an error if a number is not finite).

    Built from the spline's rows as plain values (``ArcSpline.values``: one conversion for
    the table) and serialised by orjson: no per-segment model objects, which a 1000-spiral
    batch would otherwise spend most of its time building.
    """
    s = spline.stats
    stats = _stats(s, spline.tolerance, spline.strategy)
    stats["u_at_max_deviation"] = s.u_at_max_deviation
    stats["spiral_length"] = s.spiral_length
    head = orjson.dumps({"segments": _segments(spline.values()), "stats": stats})
    return finite_body(head, 2 if s.arc_count == 0 else 0, outputs, s.arc_count, s.line_count)


def path_segments(sub: SubpathSpline) -> list[dict[str, Any]]:
    """A subpath's segment objects: ``u_*`` are the source segment's own parameter ``t``,
    and ``source_segment`` its index in the subpath."""
    rows = sub.spline.values()
    src = sub.sources()
    for r, j, t0, t1, tm in zip(
        rows, src.segment.tolist(), src.t_start.tolist(), src.t_end.tolist(),
        src.t_at_max_deviation.tolist(), strict=True,
    ):  # fmt: skip
        r[_U0], r[_U1], r[_U_DEV] = t0, t1, tm
        r.append(float(j))
    segments = _segments(rows)
    for seg, r in zip(segments, rows, strict=True):
        seg["source_segment"] = int(r[-1])
    return segments


def path_body(result: PathSpline) -> tuple[list[dict[str, Any]], dict[str, Any], int]:
    """Per subpath its segments and statistics, the statistics of the whole path, and how
    many ``null`` numbers these hold (the radii of a subpath without arcs)."""
    subpaths = []
    nulls = 0
    worst = (0, 0, 0.0, -1.0)
    for i, sub in enumerate(result.subpaths):
        s = sub.spline.stats
        segments = path_segments(sub)
        stats = _stats(s, result.tolerance, result.strategy)
        k = max(range(len(segments)), key=lambda n: segments[n]["max_deviation"])
        at = (segments[k]["source_segment"], segments[k]["u_at_max_deviation"])
        stats["max_deviation_segment"], stats["t_at_max_deviation"] = at
        stats["curve_length"] = s.spiral_length
        if s.max_deviation > worst[3]:
            worst = (i, at[0], at[1], s.max_deviation)
        nulls += 2 if s.arc_count == 0 else 0
        subpaths.append({"closed": sub.closed, "segments": segments, "stats": stats})
    s = result.stats
    overall = _stats(s, result.tolerance, result.strategy)
    overall["max_deviation_subpath"], overall["max_deviation_segment"] = worst[0], worst[1]
    overall["t_at_max_deviation"] = worst[2]
    overall["curve_length"] = s.spiral_length
    overall["subpath_count"] = len(subpaths)
    nulls += 2 if s.arc_count == 0 else 0
    return subpaths, overall, nulls


def encode_path(
    result: PathSpline, outputs: dict[str, str], tooled: Tooled | None = None
) -> Encoded | GeometryError:
    """The ``PathResponse`` body: per subpath its segments and statistics, the statistics of
    the whole path, the written ``outputs`` and, for tool-centre paths, the ``offset`` or
    ``machining`` block."""
    subpaths, overall, nulls = path_body(result)
    block = {} if tooled is None else tooled.block
    head = orjson.dumps({"subpaths": subpaths, "stats": overall, **block})
    s = result.stats
    return finite_body(head, nulls, outputs, s.arc_count, s.line_count)


#: A result with a NaN or an infinity: JSON cannot carry it, and no response may hold one.
_NOT_FINITE = GeometryError(
    "spiral",
    "cannot be approximated in double precision (its size is negligible next to its "
    "coordinates, or the tolerance is out of scale)",
    kind="precision",
)


def write_outputs(
    outputs: tuple[Output, ...], parts: list[Part], tooled: Tooled | None = None
) -> dict[str, str] | GcodeError:
    """Every output asked for, by writer name, or the first writer's refusal (of
    ``tooled``'s tool-centre paths: see :func:`.tooling.write`)."""
    try:
        return {name: write(name, options, parts, tooled) for name, options in outputs}
    except GcodeError as error:
        return error


def _finish(job: Job, curve: Curve, spline: ArcSpline) -> JobResult:
    """Write the outputs asked for, and encode."""
    outputs = write_outputs(job.outputs, [(spline, curve)])
    return outputs if isinstance(outputs, GcodeError) else encode(spline, outputs)


def approximate_one(job: Job, limits: Limits) -> JobResult:
    """One job: the encoded response, or the error that names the offending field."""
    try:
        curve = job.curve.build()
        spline = approximate(curve, job.tolerance, job.strategy, limits)
    except GeometryError as error:
        return error
    return _finish(job, curve, spline)


def approximate_chunk(jobs: Sequence[Job], limits: Limits) -> list[JobResult]:
    """Many jobs in one task, in order: one ``approximate_many`` call per strategy."""
    results: list[JobResult | None] = [None] * len(jobs)
    curves: dict[int, Curve] = {}
    by_strategy: dict[StrategyName, list[int]] = {}
    for i, job in enumerate(jobs):
        try:
            curves[i] = job.curve.build()
        except GeometryError as error:
            results[i] = error
            continue
        by_strategy.setdefault(job.strategy, []).append(i)
    for strategy, indices in by_strategy.items():
        splines = approximate_many(
            [curves[i] for i in indices], [jobs[i].tolerance for i in indices], strategy, limits
        )
        for i, spline in zip(indices, splines, strict=True):
            if isinstance(spline, GeometryError):
                results[i] = spline
            else:
                results[i] = _finish(jobs[i], curves[i], spline)
    done = [r for r in results if r is not None]
    assert len(done) == len(jobs), "every job has a result"
    return done


class _Cut(NamedTuple):
    """A job's approximation as writer parts, and for a path its whole result and its
    tool-centre paths (when asked: the parts are theirs)."""

    parts: list[Part]
    result: PathSpline | None = None
    tooled: Tooled | None = None


def _subpath_name(i: int) -> str:
    return f"path.subpaths[{i}]"


def _parts(job: Job | PathJob, limits: Limits) -> _Cut:
    """The job's approximation (see :class:`_Cut`)."""
    if isinstance(job, PathJob):
        result = approximate_path(job.path.build(), job.tolerance, job.strategy, limits)
        if job.tooling is not None:
            tooled = tool(result, job.tooling, limits, _subpath_name)
            return _Cut(tooled.parts(), tooled.spline, tooled)
        return _Cut([(s.spline, s.curve) for s in result.subpaths], result)
    curve = job.curve.build()
    return _Cut([(approximate(curve, job.tolerance, job.strategy, limits), curve)])


def approximate_path_one(job: PathJob, limits: Limits) -> JobResult:
    """One path: the encoded ``PathResponse``, or the error that names the offending field."""
    try:
        cut = _parts(job, limits)
    except GeometryError as error:
        return error
    assert cut.result is not None
    outputs = write_outputs(job.outputs, cut.parts, cut.tooled)
    if isinstance(outputs, GcodeError):
        return outputs
    return encode_path(cut.result, outputs, cut.tooled)


def approximate_path_chunk(jobs: Sequence[PathJob], limits: Limits) -> list[JobResult]:
    """Many paths in one task, in order (each alone: a path is already one compiled loop)."""
    return [approximate_path_one(job, limits) for job in jobs]


AnyJob = TypeVar("AnyJob", Job, PathJob)


class Budgeted(NamedTuple):
    """A chunk's results within its budget of output segments (docs/http-api.md, "Work
    budget"): every job's, in order, if ``complete``; else those of the jobs before the one
    that would have passed the budget (the rest are not answered)."""

    results: list[JobResult]
    segments: int
    complete: bool


def segments_of(result: JobResult) -> int:
    """The output segments a result holds (none for an error)."""
    return result.arc_count + result.line_count if isinstance(result, Encoded) else 0


def _over_cap(result: JobResult, cap: int, limits: Limits) -> bool:
    """Whether ``result`` hit a segment cap lower than the job's own limit (so the job may
    still fit under that limit, and only the cap refused it)."""
    return (
        isinstance(result, GeometryError)
        and result.kind == "segment_limit"
        and cap < limits.max_segments
    )


def within_budget(
    run: Callable[[list[AnyJob], Limits], list[JobResult]],
    jobs: Sequence[AnyJob],
    limits: Limits,
    budget_segments: int,
) -> Budgeted:
    """``run(jobs, limits)`` such that never more than about ``budget_segments`` output
    segments are computed (and held) at once: the core stops a curve at its segment limit,
    so a curve given a cap computes at most that many.

    First every job in one call, each capped at an equal share of the budget (small jobs,
    the common case, finish there); then, in order, each job that hit its share alone,
    capped at what is left (letting go of the answers after it if they crowd it out: they
    are computed again, one by one). A job that passes what is left ends the chunk there:
    the results are of the jobs before it, and ``complete`` is false.
    """
    count = len(jobs)
    share = min(limits.max_segments, max(1, budget_segments // max(count, 1)))
    answers: list[JobResult | None] = list(run(list(jobs), _capped(limits, share)))
    held = sum(segments_of(r) for r in answers if r is not None)  # in memory now
    results: list[JobResult] = []
    for i, answer in enumerate(answers):
        if answer is None or _over_cap(answer, share, limits):
            if budget_segments - held < limits.max_segments:
                held -= sum(segments_of(r) for r in answers[i + 1 :] if r is not None)
                answers[i + 1 :] = [None] * (count - i - 1)
            # At least one: an error takes none, and a single segment past is noticed.
            cap = max(1, min(limits.max_segments, budget_segments - held))
            (answer,) = run([jobs[i]], _capped(limits, cap))
            held += segments_of(answer)
            if _over_cap(answer, cap, limits) or held > budget_segments:
                break
        results.append(answer)
    complete = len(results) == count and held <= budget_segments
    return Budgeted(results, sum(map(segments_of, results)), complete)


def _capped(limits: Limits, max_segments: int) -> Limits:
    return dataclasses.replace(limits, max_segments=max_segments)


def render(job: Job | PathJob, limits: Limits) -> Document | GeometryError | GcodeError:
    """The job's first output as a document of its own (no JSON around it)."""
    try:
        cut = _parts(job, limits)
        (name, options), *_ = job.outputs
        writer = WRITERS[name]
        text = write(name, options, cut.parts, cut.tooled)
    except (GeometryError, GcodeError) as error:
        return error
    return Document(body=text.encode(), media_type=writer.media_type)
