"""The jobs the worker processes run: pure functions, picklable in and out.

A job is a spiral (by its parameters or its control points), a tolerance, a strategy and
optional G-code options. The functions here build the core's spiral, approximate it (one job,
or a chunk of jobs through the core's vectorised ``approximate_many``), add the G-code program
and serialise the response body to JSON, all inside the worker, so that encoding runs in
parallel too. A job the core or the G-code writer refuses returns its error as a value.

Dependency direction: ``arcspline.worker.pool`` runs these; they import only the geometry core,
the G-code writer, numpy and orjson, never the web stack.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import NamedTuple

import numpy as np
import orjson

from arcspline.geometry import (
    COLUMN,
    ArcSpline,
    GeometryError,
    Limits,
    Spiral,
    StrategyName,
    approximate,
    approximate_many,
)
from arcspline.outputs.gcode import GcodeError, GcodeOptions, write_program

# Named tuples rather than frozen dataclasses: thousands of these cross the process boundary
# per second, and tuples pickle several times faster (no per-field __setstate__).


class ParametersSpec(NamedTuple):
    """A spiral given by the paper's five parameters (§1)."""

    start: tuple[float, float]
    start_tangent: tuple[float, float]
    turn_angle_deg: float
    end_curvature: float


class ControlPointsSpec(NamedTuple):
    """A spiral given by its four Bézier control points."""

    control_points: tuple[tuple[float, float], ...]


SpiralSpec = ParametersSpec | ControlPointsSpec


class Job(NamedTuple):
    """One approximation request, as the worker needs it."""

    spiral: SpiralSpec
    tolerance: float
    strategy: StrategyName = "subdivide"
    gcode: GcodeOptions | None = None


class Encoded(NamedTuple):
    """A job's response body, already JSON, with the counts the metrics need."""

    body: bytes
    arc_count: int
    line_count: int


JobResult = Encoded | GeometryError | GcodeError


def build_spiral(spec: SpiralSpec) -> Spiral:
    """The core's spiral for ``spec``; raises :class:`GeometryError` for an invalid one."""
    if isinstance(spec, ControlPointsSpec):
        return Spiral.from_control_points(spec.control_points)
    return Spiral.from_parameters(
        start=spec.start,
        start_tangent=spec.start_tangent,
        turn_angle_deg=spec.turn_angle_deg,
        end_curvature=spec.end_curvature,
    )


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


def encode(spline: ArcSpline, gcode: str | None) -> Encoded | GeometryError:
    """The ``ApproximateResponse`` body of ``spline`` as JSON bytes (an error if not finite).

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
    body = orjson.dumps({"segments": segments, "stats": stats, "gcode": gcode})
    # orjson writes NaN and Infinity as null, and no number of this body may be null but the
    # radii of a spline without arcs: counting nulls before the program proves every number
    # finite at memchr speed, without another pass over the columns.
    nulls = body.count(b"null", 0, body.rfind(b'"gcode":'))
    if nulls != (2 if s.arc_count == 0 else 0):
        return _NOT_FINITE
    return Encoded(body=body, arc_count=s.arc_count, line_count=s.line_count)


#: A result with a NaN or an infinity: JSON cannot carry it, and no response may hold one.
_NOT_FINITE = GeometryError(
    "spiral",
    "cannot be approximated in double precision (its size is negligible next to its "
    "coordinates, or the tolerance is out of scale)",
    kind="precision",
)


def _finite(spline: ArcSpline) -> ArcSpline | GeometryError:
    """``spline``, or an error if any number of it is not finite.

    The core vouches for its results; this guard keeps NaN and Infinity out of the responses
    even so, should a degenerate input slip through.
    """
    c, s = spline.columns, spline.stats
    arcs = c.is_arc
    columns = (c.start, c.end, c.length, c.u_start, c.u_end, c.max_deviation, c.u_at_max_deviation)
    stats = (s.max_deviation, s.deviation_ratio, s.mean_segment_deviation, s.spiral_length)
    finite = (
        all(bool(np.isfinite(column).all()) for column in columns)
        and bool(np.isfinite(c.center[arcs]).all() and np.isfinite(c.radius[arcs]).all())
        and bool(np.isfinite(c.start_angle_rad).all() and np.isfinite(c.sweep_rad).all())
        and all(math.isfinite(value) for value in (*stats, s.spline_length))
    )
    return spline if finite else _NOT_FINITE


def _finish(job: Job, spiral: Spiral, spline: ArcSpline) -> JobResult:
    """Add the G-code program if asked for, and encode."""
    if job.gcode is None:
        return encode(spline, None)
    if isinstance(finite := _finite(spline), GeometryError):
        return finite
    try:
        program = write_program(spline, spiral, job.gcode)
    except GcodeError as error:
        return error
    return encode(spline, program)


def approximate_one(job: Job, limits: Limits) -> JobResult:
    """One job: the encoded response, or the error that names the offending field."""
    try:
        spiral = build_spiral(job.spiral)
        spline = approximate(spiral, job.tolerance, job.strategy, limits)
    except GeometryError as error:
        return error
    return _finish(job, spiral, spline)


def approximate_chunk(jobs: Sequence[Job], limits: Limits) -> list[JobResult]:
    """Many jobs in one task, in order: one ``approximate_many`` call per strategy."""
    results: list[JobResult | None] = [None] * len(jobs)
    spirals: dict[int, Spiral] = {}
    by_strategy: dict[StrategyName, list[int]] = {}
    for i, job in enumerate(jobs):
        try:
            spirals[i] = build_spiral(job.spiral)
        except GeometryError as error:
            results[i] = error
            continue
        by_strategy.setdefault(job.strategy, []).append(i)
    for strategy, indices in by_strategy.items():
        splines = approximate_many(
            [spirals[i] for i in indices], [jobs[i].tolerance for i in indices], strategy, limits
        )
        for i, spline in zip(indices, splines, strict=True):
            if isinstance(spline, GeometryError):
                results[i] = spline
            else:
                results[i] = _finish(jobs[i], spirals[i], spline)
    done = [r for r in results if r is not None]
    assert len(done) == len(jobs), "every job has a result"
    return done


def preview_spline(job: Job, limits: Limits) -> tuple[Spiral, ArcSpline] | GeometryError:
    """The spiral and its arc spline, for drawing (no G-code, no JSON)."""
    try:
        spiral = build_spiral(job.spiral)
        spline = _finite(approximate(spiral, job.tolerance, job.strategy, limits))
    except GeometryError as error:
        return error
    return spline if isinstance(spline, GeometryError) else (spiral, spline)
