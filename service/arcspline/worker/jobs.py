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

from collections.abc import Sequence
from typing import Any, NamedTuple

import orjson

from arcspline.geometry import (
    COLUMN,
    ArcSpline,
    Curve,
    CurveSpec,
    GeometryError,
    Limits,
    StrategyName,
    approximate,
    approximate_many,
)
from arcspline.outputs import WRITERS
from arcspline.outputs.gcode import GcodeError

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


def encode(spline: ArcSpline, outputs: dict[str, str]) -> Encoded | GeometryError:
    """The ``ApproximateResponse`` body of ``spline`` and its written ``outputs`` as JSON
    bytes (an error if a number is not finite).

    Built from the spline's rows as plain values (``ArcSpline.values``: one conversion for
    the table) and serialised by orjson: no per-segment model objects, which a 1000-spiral
    batch would otherwise spend most of its time building.
    """
    segments = [
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
        for r in spline.values()
    ]
    s = spline.stats
    stats = {
        "arc_count": s.arc_count,
        "line_count": s.line_count,
        "segment_count": s.segment_count,
        "max_deviation": s.max_deviation,
        "u_at_max_deviation": s.u_at_max_deviation,
        "deviation_ratio": s.deviation_ratio,
        "mean_segment_deviation": s.mean_segment_deviation,
        "spiral_length": s.spiral_length,
        "spline_length": s.spline_length,
        "min_radius": s.min_radius,
        "max_radius": s.max_radius,
        "tolerance": spline.tolerance,
        "strategy": spline.strategy,
    }
    head = orjson.dumps({"segments": segments, "stats": stats})
    # orjson writes NaN and Infinity as null, and no number of the segments and statistics
    # may be null but the radii of a spline without arcs: counting nulls proves every number
    # finite at memchr speed, without another pass over the rows.
    if head.count(b"null") != (2 if s.arc_count == 0 else 0):
        return _NOT_FINITE
    texts = orjson.dumps({name: outputs.get(name) for name in JSON_OUTPUTS})
    body = b"".join((head[:-1], b",", texts[1:]))
    return Encoded(body=body, arc_count=s.arc_count, line_count=s.line_count)


#: A result with a NaN or an infinity: JSON cannot carry it, and no response may hold one.
_NOT_FINITE = GeometryError(
    "spiral",
    "cannot be approximated in double precision (its size is negligible next to its "
    "coordinates, or the tolerance is out of scale)",
    kind="precision",
)


def _write(job: Job, curve: Curve, spline: ArcSpline) -> dict[str, str] | GcodeError:
    """Every output the job asks for, by writer name, or the first writer's refusal."""
    try:
        return {name: WRITERS[name].write([(spline, curve)], options) for name, options in job.outputs}
    except GcodeError as error:
        return error


def _finish(job: Job, curve: Curve, spline: ArcSpline) -> JobResult:
    """Write the outputs asked for, and encode."""
    outputs = _write(job, curve, spline)
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


def render(job: Job, limits: Limits) -> Document | GeometryError | GcodeError:
    """The job's first output as a document of its own (no JSON around it)."""
    try:
        curve = job.curve.build()
        spline = approximate(curve, job.tolerance, job.strategy, limits)
        (name, options), *_ = job.outputs
        writer = WRITERS[name]
        text = writer.write([(spline, curve)], options)
    except (GeometryError, GcodeError) as error:
        return error
    return Document(body=text.encode(), media_type=writer.media_type)
