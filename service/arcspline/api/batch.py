"""The loop every batch endpoint shares: validate each job on its own, send the good ones to
the workers in a few large chunks, and join the answers in order (``/v1/approximate/batch``
and ``/v1/paths/batch``)."""

from __future__ import annotations

import itertools
from collections.abc import Callable, Sequence
from typing import Any, TypeVar

import orjson
from pydantic import ValidationError

from arcspline.geometry import Limits
from arcspline.worker.jobs import Encoded, JobResult
from arcspline.worker.pool import PoolError, chunk_sizes

from .errors import Loc, ProblemError, pool_problem, problem, problem_kind, validation_problem
from .runtime import Runtime
from .schemas import OutputFormat
from .translate import job_problem

JobT = TypeVar("JobT")


def json_only(output: OutputFormat | None, prefix: Loc) -> None:
    """Refuses a job that asks for a document alone: a batch answers JSON, job by job."""
    if output not in (None, "json"):
        item = {
            "loc": ["output"],
            "msg": "a batch answers JSON only: `json` or none",
            "type": "json_only",
        }
        raise ProblemError(validation_problem([item], prefix))


async def run_batch(
    runtime: Runtime,
    raw_jobs: Sequence[Any],
    make_job: Callable[[Any, Loc], JobT],
    run_chunk: Callable[[list[JobT], Limits], list[JobResult]],
    limits: Limits,
    min_chunk_jobs: int,
    endpoint: str,
    curve: str,
) -> bytes:
    """The batch's body: one entry per job, in order. ``make_job`` validates a raw job and
    builds the worker's job (raising ``ValidationError`` or :class:`ProblemError` for a bad
    one, which becomes its error entry); ``run_chunk`` runs many in one worker task;
    ``curve`` is the request field that holds the curve (for the problems' paths)."""
    settings = runtime.settings
    if len(raw_jobs) > settings.batch_max_jobs:
        detail = (
            f"the batch has {len(raw_jobs)} jobs; at most {settings.batch_max_jobs} are accepted"
        )
        raise ProblemError(problem("too_many_jobs", detail, limit=settings.batch_max_jobs))

    entries: list[Encoded | dict[str, Any] | None] = []
    pending: list[tuple[int, JobT]] = []
    for i, raw in enumerate(raw_jobs):
        prefix: Loc = ["body", "jobs", i]
        try:
            pending.append((i, make_job(raw, prefix)))
            entries.append(None)  # until the worker answers
        except ValidationError as error:
            entries.append(validation_problem(error.errors(), prefix))
        except ProblemError as error:
            entries.append(error.problem)

    pool = runtime.running_pool()
    sizes = chunk_sizes(len(pending), min(pool.size, pool.capacity), min_chunk_jobs)
    bounds = [0, *itertools.accumulate(sizes)]
    chunks = [pending[begin:end] for begin, end in itertools.pairwise(bounds)]
    calls = [(run_chunk, ([job for _, job in chunk], limits)) for chunk in chunks]
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
                else job_problem(result, ["body", "jobs", i], curve)
            )
    return _body(entries, runtime, endpoint)


def _body(entries: list[Encoded | dict[str, Any] | None], runtime: Runtime, endpoint: str) -> bytes:
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
