"""``POST /v1/paths/approximate``, ``/v1/paths/batch`` and ``/v1/paths/preview``: general
paths (SVG path data or the JSON form), one arc spline per subpath, one program per path."""

from __future__ import annotations

import itertools
from typing import Any

from fastapi import APIRouter, Request
from pydantic import TypeAdapter, ValidationError

from arcspline.outputs.gcode import GcodeError, GcodeOptions
from arcspline.worker.jobs import (
    Document,
    Encoded,
    JobResult,
    Output,
    PathJob,
    approximate_path_chunk,
    approximate_path_one,
    render,
)
from arcspline.worker.pool import PoolError, chunk_sizes

from .approximate import batch_body
from .errors import (
    Loc,
    ProblemError,
    RawJSONResponse,
    gcode_problem,
    pool_problem,
    problem,
    problem_responses,
    validation_problem,
)
from .path_schemas import PathBatchRequest, PathBatchResponse, PathRequest, PathResponse
from .preview import SVGResponse, svg_responses
from .routing import LeanRoute
from .runtime import runtime_of
from .translate import job_problem

router = APIRouter(tags=["paths"], route_class=LeanRoute)

_JOB_ADAPTER: TypeAdapter[PathRequest] = TypeAdapter(PathRequest)


def to_path_job(
    request: PathRequest, prefix: Loc, max_segments: int, outputs: tuple[Output, ...] | None = None
) -> PathJob:
    """The worker's job for ``request`` (G-code options the writer refuses raise a 422)."""
    if outputs is None:
        outputs = ()
        if request.gcode is not None:
            try:
                outputs = (("gcode", GcodeOptions(**request.gcode.model_dump())),)
            except GcodeError as error:
                raise ProblemError(gcode_problem(error, prefix)) from None
    return PathJob(request.spec(max_segments), request.tolerance, request.strategy, outputs)


@router.post(
    "/v1/paths/approximate",
    name="approximate_path",
    summary="Approximate a path (any curves, corners, subpaths) by arcs and lines",
    response_model=PathResponse,
    responses=problem_responses(400, 413, 422, 503, 504),
)
async def approximate_path(body: PathRequest, request: Request) -> RawJSONResponse:
    """One arc spline per subpath, each segment with its source, certified statistics, and
    one G-code program for the whole path if asked."""
    runtime = runtime_of(request)
    settings = runtime.settings
    job = to_path_job(body, ["body"], settings.path_max_input_segments)
    result = await runtime.running_pool().run(
        approximate_path_one, job, settings.path_limits, time_limit_s=settings.job_time_limit_s
    )
    if isinstance(result, Encoded):
        runtime.metrics.job_ok("paths", result.arc_count, result.line_count)
        return RawJSONResponse(result.body)
    runtime.metrics.job_error("paths")
    raise ProblemError(job_problem(result, ["body"], "path"))


@router.post(
    "/v1/paths/batch",
    name="approximate_paths_batch",
    summary="Approximate many paths",
    response_model=PathBatchResponse,
    responses=problem_responses(400, 413, 422, 503),
)
async def approximate_paths_batch(body: PathBatchRequest, request: Request) -> RawJSONResponse:
    """One result per job, in order: ``ok`` with the body of /v1/paths/approximate, or
    ``error``; a bad job spoils nothing else."""
    runtime = runtime_of(request)
    settings = runtime.settings
    if len(body.jobs) > settings.batch_max_jobs:
        detail = (
            f"the batch has {len(body.jobs)} jobs; at most {settings.batch_max_jobs} are accepted"
        )
        raise ProblemError(problem("too_many_jobs", detail, limit=settings.batch_max_jobs))
    entries: list[Encoded | dict[str, Any] | None] = []
    pending: list[tuple[int, PathJob]] = []
    for i, raw in enumerate(body.jobs):
        prefix: Loc = ["body", "jobs", i]
        try:
            job = _JOB_ADAPTER.validate_python(raw)
            pending.append((i, to_path_job(job, prefix, settings.path_max_input_segments)))
            entries.append(None)
        except ValidationError as error:
            entries.append(validation_problem(error.errors(), prefix))
        except ProblemError as error:
            entries.append(error.problem)
    pool = runtime.running_pool()
    sizes = chunk_sizes(len(pending), min(pool.size, pool.capacity), 1)
    bounds = [0, *itertools.accumulate(sizes)]
    chunks = [pending[begin:end] for begin, end in itertools.pairwise(bounds)]
    calls = [
        (approximate_path_chunk, ([job for _, job in chunk], settings.path_limits))
        for chunk in chunks
    ]
    outcomes = await pool.run_many(calls, time_limit_s=settings.batch_time_limit_s)
    for chunk, outcome in zip(chunks, outcomes, strict=True):
        if isinstance(outcome, PoolError):
            failure, _ = pool_problem(outcome)
            for i, _job in chunk:
                entries[i] = failure
            continue
        results: list[JobResult] = outcome
        for (i, _job), result in zip(chunk, results, strict=True):
            entries[i] = (
                result
                if isinstance(result, Encoded)
                else job_problem(result, ["body", "jobs", i], "path")
            )
    return RawJSONResponse(batch_body(entries, runtime, "paths_batch"))


@router.post(
    "/v1/paths/preview",
    name="preview_path",
    summary="Draw a path's approximation (SVG)",
    response_class=SVGResponse,
    responses=svg_responses(),
)
async def preview_path(body: PathRequest, request: Request) -> SVGResponse:
    """Every subpath, its arcs with their centres, the deviation magnified (``gcode``
    ignored)."""
    runtime = runtime_of(request)
    settings = runtime.settings
    job = to_path_job(body, ["body"], settings.path_max_input_segments, outputs=(("svg", None),))
    result = await runtime.running_pool().run(
        render, job, settings.path_limits, time_limit_s=settings.job_time_limit_s
    )
    if not isinstance(result, Document):
        raise ProblemError(job_problem(result, ["body"], "path"))
    return SVGResponse(result.body)
