"""``POST /v1/approximate`` and ``POST /v1/approximate/batch``."""

from __future__ import annotations

from typing import Any

from fastapi import APIRouter, Request
from pydantic import TypeAdapter
from starlette.responses import Response

from arcspline.worker.jobs import Encoded, Job, approximate_chunk, render

from .batch import answer, json_only, validate
from .contract import OUTPUT_PARAMETER, answers, batch_answers
from .errors import Loc, ProblemError, RawJSONResponse, problem_responses
from .fast_path import run_inline
from .negotiation import BATCH_MEDIA_TYPES, answer_document, fixed_answer, output_of
from .routing import LeanRoute
from .runtime import runtime_of
from .schemas import ApproximateRequest, ApproximateResponse, BatchRequest, BatchResponse
from .translate import curve_outputs, job_problem, to_job

router = APIRouter(tags=["approximation"], route_class=LeanRoute)

_JOB_ADAPTER: TypeAdapter[ApproximateRequest] = TypeAdapter(ApproximateRequest)
#: Jobs per worker task of a streamed batch: small, so the first lines go out early.
STREAM_CHUNK_JOBS = 8


@router.post(
    "/v1/approximate",
    name="approximate",
    summary="Approximate one spiral by arcs: JSON, G-code, DXF or SVG",
    response_model=ApproximateResponse,
    responses={
        **answers("The arc spline (JSON), or the one document asked for"),
        **problem_responses(400, 406, 413, 422, 503, 504),
    },
    openapi_extra={"parameters": [OUTPUT_PARAMETER]},
)
async def approximate(body: ApproximateRequest, request: Request) -> Response:
    """The arc spline of one spiral within the tolerance, its statistics, and G-code if asked
    — or one document alone: the program, a DXF or an SVG of the arcs (``output``)."""
    output = output_of(body.output, request)
    job = to_job(body, ["body"], curve_outputs(body, output, ["body"]))
    runtime = runtime_of(request)
    if output != "json":
        return await answer_document(
            request, render, job, runtime.settings.limits, endpoint="approximate",
            stem="spiral", output=output, problem_of=lambda error: job_problem(error, ["body"]),
        )  # fmt: skip
    singles = runtime.singles()
    result = run_inline(job, runtime.settings, singles.pool, runtime.inline_allowance)
    if result is None:
        # Jobs that arrive while every worker is busy share a worker task (see Coalescer).
        result = await singles.run(job)
    if isinstance(result, Encoded):
        runtime.metrics.job_ok("approximate", result.arc_count, result.line_count)
        return RawJSONResponse(result.body)
    runtime.metrics.job_error("approximate")
    raise ProblemError(job_problem(result, ["body"]))


@router.post(
    "/v1/approximate/batch",
    name="approximate_batch",
    summary="Approximate many spirals",
    response_model=BatchResponse,
    responses={
        **batch_answers("One result per job, in order", "BatchOkResponse"),
        **problem_responses(400, 406, 413, 422, 503),
    },
)
async def approximate_batch(body: BatchRequest, request: Request) -> Response:
    """One result per job, in order: ``ok`` with the body of /v1/approximate, or ``error``.

    Each job is validated and computed on its own, so a bad job becomes an error entry and
    spoils nothing else. The jobs go to the workers in a few large tasks, within the batch's
    work budget — or, streamed (NDJSON), in small ones, each line sent as its task finishes.
    """
    media_type = fixed_answer(request, BATCH_MEDIA_TYPES)
    runtime = runtime_of(request)
    settings = runtime.settings

    def make_job(raw: Any, prefix: Loc) -> Job:
        job = _JOB_ADAPTER.validate_python(raw)
        json_only(job.output, prefix)
        return to_job(job, prefix)

    batch = validate(
        runtime, body.jobs, make_job, approximate_chunk, settings.limits, "batch", "spiral"
    )
    return await answer(batch, media_type, settings.batch_chunk_min_jobs, STREAM_CHUNK_JOBS)
