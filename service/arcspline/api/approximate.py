"""``POST /v1/approximate`` and ``POST /v1/approximate/batch``."""

from __future__ import annotations

import itertools
from typing import Any

import orjson
from fastapi import APIRouter, Request
from pydantic import TypeAdapter, ValidationError

from arcspline.worker.jobs import Encoded, Job, JobResult, approximate_chunk
from arcspline.worker.pool import PoolError, chunk_sizes

from .errors import (
    ProblemError,
    RawJSONResponse,
    pool_problem,
    problem,
    problem_kind,
    problem_responses,
    validation_problem,
)
from .routing import LeanRoute
from .runtime import Runtime, runtime_of
from .schemas import ApproximateRequest, ApproximateResponse, BatchRequest, BatchResponse
from .translate import job_problem, to_job

router = APIRouter(tags=["approximation"], route_class=LeanRoute)

_JOB_ADAPTER: TypeAdapter[ApproximateRequest] = TypeAdapter(ApproximateRequest)


@router.post(
    "/v1/approximate",
    name="approximate",
    summary="Approximate one spiral by arcs",
    response_model=ApproximateResponse,
    responses=problem_responses(400, 413, 422, 503, 504),
)
async def approximate(body: ApproximateRequest, request: Request) -> RawJSONResponse:
    """The arc spline of one spiral within the tolerance, its statistics, and G-code if asked."""
    runtime = runtime_of(request)
    # Jobs that arrive while every worker is busy share a worker task (see Coalescer).
    result = await runtime.singles().run(to_job(body, ["body"]))
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
    responses=problem_responses(400, 413, 422, 503),
)
async def approximate_batch(body: BatchRequest, request: Request) -> RawJSONResponse:
    """One result per job, in order: ``ok`` with the body of /v1/approximate, or ``error``.

    Each job is validated and computed on its own, so a bad job becomes an error entry and
    spoils nothing else. The jobs go to the workers in a few large tasks.
    """
    runtime = runtime_of(request)
    settings = runtime.settings
    if len(body.jobs) > settings.batch_max_jobs:
        detail = (
            f"the batch has {len(body.jobs)} jobs; at most {settings.batch_max_jobs} are accepted"
        )
        raise ProblemError(problem("too_many_jobs", detail, limit=settings.batch_max_jobs))

    entries: list[Encoded | dict[str, Any] | None] = []
    pending: list[tuple[int, Job]] = []
    for i, raw in enumerate(body.jobs):
        prefix: list[str | int] = ["body", "jobs", i]
        try:
            job = _JOB_ADAPTER.validate_python(raw)
            pending.append((i, to_job(job, prefix)))
            entries.append(None)  # until the worker answers
        except ValidationError as error:
            entries.append(validation_problem(error.errors(), prefix))
        except ProblemError as error:
            entries.append(error.problem)

    pool = runtime.running_pool()
    sizes = chunk_sizes(len(pending), min(pool.size, pool.capacity), settings.batch_chunk_min_jobs)
    bounds = [0, *itertools.accumulate(sizes)]
    chunks = [pending[begin:end] for begin, end in itertools.pairwise(bounds)]
    calls = [(approximate_chunk, ([job for _, job in chunk], settings.limits)) for chunk in chunks]
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
                result if isinstance(result, Encoded) else job_problem(result, ["body", "jobs", i])
            )
    return RawJSONResponse(batch_body(entries, runtime, "batch"))


def batch_body(
    entries: list[Encoded | dict[str, Any] | None], runtime: Runtime, endpoint: str
) -> bytes:
    """``{"results": [...]}`` from the workers' bytes, joined once (never re-parsed)."""
    metrics = runtime.metrics
    parts: list[bytes] = [b'{"results":[']
    arcs = lines = ok = 0
    for i, entry in enumerate(entries):
        if i:
            parts.append(b",")
        assert entry is not None, "every job has an answer"
        if isinstance(entry, Encoded):
            parts += (b'{"status":"ok","result":', entry.body, b"}")
            arcs, lines, ok = arcs + entry.arc_count, lines + entry.line_count, ok + 1
        else:
            parts += (b'{"status":"error","error":', orjson.dumps(entry), b"}")
            metrics.job_error(endpoint)
            metrics.error(problem_kind(entry))
    parts.append(b"]}")
    metrics.job_ok(endpoint, arcs, lines, ok)
    return b"".join(parts)
