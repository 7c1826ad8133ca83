"""``POST /v1/paths/approximate``, ``/v1/paths/batch`` and ``/v1/paths/preview``: general
paths (SVG path data or the JSON form), one arc spline per subpath, one program per path."""

from __future__ import annotations

from typing import Any

from fastapi import APIRouter, Request
from pydantic import TypeAdapter

from arcspline.worker.jobs import (
    Document,
    Encoded,
    PathJob,
    approximate_path_chunk,
    approximate_path_one,
    render,
)

from .batch import run_batch
from .errors import (
    Loc,
    ProblemError,
    RawJSONResponse,
    problem_responses,
)
from .path_schemas import PathBatchRequest, PathBatchResponse, PathRequest, PathResponse
from .preview import SVGResponse, svg_responses
from .routing import LeanRoute
from .runtime import runtime_of
from .translate import job_problem, to_path_job

router = APIRouter(tags=["paths"], route_class=LeanRoute)

_JOB_ADAPTER: TypeAdapter[PathRequest] = TypeAdapter(PathRequest)


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

    def make_job(raw: Any, prefix: Loc) -> PathJob:
        return to_path_job(
            _JOB_ADAPTER.validate_python(raw), prefix, settings.path_max_input_segments
        )

    # A path is one compiled loop already: each chunk a job, as the pool allows.
    body_bytes = await run_batch(
        runtime, body.jobs, make_job, approximate_path_chunk, settings.path_limits, 1,
        "paths_batch", "path",
    )  # fmt: skip
    return RawJSONResponse(body_bytes)


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
