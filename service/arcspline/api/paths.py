"""``POST /v1/paths/approximate``, ``/v1/paths/batch`` and ``/v1/paths/preview``: general
paths (SVG path data or the JSON form), one arc spline per subpath, one program per path."""

from __future__ import annotations

from typing import Any

from fastapi import APIRouter, Request
from pydantic import TypeAdapter
from starlette.responses import Response

from arcspline.outputs.svg import MEDIA_TYPE as SVG_MEDIA_TYPE
from arcspline.worker.jobs import (
    Encoded,
    PathJob,
    approximate_path_chunk,
    approximate_path_one,
    render,
)

from .batch import answer, json_only, validate
from .contract import OUTPUT_PARAMETER, answers, batch_answers
from .errors import Loc, ProblemError, RawJSONResponse, problem_responses
from .negotiation import BATCH_MEDIA_TYPES, answer_document, fixed_answer, output_of
from .path_schemas import PathBatchRequest, PathBatchResponse, PathRequest, PathResponse
from .preview import SVGResponse, draw, svg_responses
from .routing import LeanRoute
from .runtime import runtime_of
from .translate import curve_outputs, job_problem, path_preview, to_path_job

router = APIRouter(tags=["paths"], route_class=LeanRoute)

_JOB_ADAPTER: TypeAdapter[PathRequest] = TypeAdapter(PathRequest)


@router.post(
    "/v1/paths/approximate",
    name="approximate_path",
    summary="Approximate a path (any curves, corners, subpaths): JSON, G-code, DXF or SVG",
    response_model=PathResponse,
    responses={
        **answers("One arc spline per subpath (JSON), or the one document asked for"),
        **problem_responses(400, 406, 413, 422, 503, 504),
    },
    openapi_extra={"parameters": [OUTPUT_PARAMETER]},
)
async def approximate_path(body: PathRequest, request: Request) -> Response:
    """One arc spline per subpath, each segment with its source, certified statistics, and
    one G-code program for the whole path if asked — or one document alone: the program, a
    DXF or an SVG of the whole path (``output``)."""
    output = output_of(body.output, request)
    runtime = runtime_of(request)
    settings = runtime.settings
    outputs = curve_outputs(body, output, ["body"])
    job = to_path_job(body, ["body"], settings.path_max_input_segments, outputs)
    if output != "json":
        return await answer_document(
            request, render, job, settings.path_limits, endpoint="paths", stem="path",
            output=output, problem_of=lambda error: job_problem(error, ["body"], "path"),
        )  # fmt: skip
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
    responses={
        **batch_answers("One result per job, in order", "PathBatchOkResponse"),
        **problem_responses(400, 406, 413, 422, 503),
    },
)
async def approximate_paths_batch(body: PathBatchRequest, request: Request) -> Response:
    """One result per job, in order: ``ok`` with the body of /v1/paths/approximate, or
    ``error``; a bad job spoils nothing else."""
    media_type = fixed_answer(request, BATCH_MEDIA_TYPES)
    runtime = runtime_of(request)
    settings = runtime.settings

    def make_job(raw: Any, prefix: Loc) -> PathJob:
        job = _JOB_ADAPTER.validate_python(raw)
        json_only(job.output, prefix)
        return to_path_job(job, prefix, settings.path_max_input_segments)

    batch = validate(
        runtime, body.jobs, make_job, approximate_path_chunk, settings.path_limits,
        "paths_batch", "path",
    )  # fmt: skip
    # A path is one compiled loop already: each chunk a job, as the pool allows (streamed:
    # each path alone).
    return await answer(batch, media_type, 1, 1)


@router.post(
    "/v1/paths/preview",
    name="preview_path",
    summary="Draw a path's approximation (SVG)",
    response_class=SVGResponse,
    responses=svg_responses(),
)
async def preview_path(body: PathRequest, request: Request) -> SVGResponse:
    """Every subpath, its arcs with their centres, the deviation magnified (``gcode`` and
    ``output`` ignored); with ``offset`` or ``machining``, the tool-centre paths in cutting
    order over the contours, and the width the tool sweeps."""
    fixed_answer(request, (SVG_MEDIA_TYPE,))
    settings = runtime_of(request).settings
    outputs = (path_preview(body),)
    job = to_path_job(body, ["body"], settings.path_max_input_segments, outputs=outputs)
    return await draw(
        request, render, job, settings.path_limits, endpoint="paths_preview",
        problem_of=lambda error: job_problem(error, ["body"], "path"),
    )  # fmt: skip
