"""The loop every batch endpoint shares: validate each job on its own, send the good ones to
the workers in chunks, and answer one entry per job, in order (``/v1/approximate/batch`` and
``/v1/paths/batch``) — as one JSON document within the batch's work budget, or as NDJSON,
one line per job as the chunks finish (docs/http-api.md, "Batches").
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any, Generic, TypeVar

import orjson
from pydantic import ValidationError
from starlette.responses import Response

from arcspline.geometry import Limits
from arcspline.worker.jobs import Budgeted, Encoded, JobResult, within_budget
from arcspline.worker.pool import PoolError

from .batch_json import answer_json
from .batch_stream import answer_stream
from .errors import Loc, ProblemError, pool_problem, problem, problem_kind, validation_problem
from .runtime import Runtime
from .schemas import NDJSON_MEDIA_TYPE, OutputFormat
from .translate import job_problem

JobT = TypeVar("JobT")
Entry = Encoded | dict[str, Any]
RunChunk = Callable[[list[JobT], Limits], list[JobResult]]


def json_only(output: OutputFormat | None, prefix: Loc) -> None:
    """Refuses a job that asks for a document alone: a batch answers JSON, job by job."""
    if output not in (None, "json"):
        item = {
            "loc": ["output"],
            "msg": "a batch answers JSON only: `json` or none",
            "type": "json_only",
        }
        raise ProblemError(validation_problem([item], prefix))


@dataclass
class Batch(Generic[JobT]):
    """A batch's jobs once validated: an entry already for each bad job, the good ones by
    index, and how they run (``curve``: the request field that holds the curve)."""

    runtime: Runtime
    entries: list[Entry | None]
    pending: list[tuple[int, JobT]]
    run_chunk: RunChunk[JobT]
    limits: Limits
    endpoint: str
    curve: str

    def fill(self, chunk: Sequence[tuple[int, JobT]], outcome: Budgeted | PoolError) -> int:
        """Each answered job's entry from the chunk's ``outcome``; how many were answered."""
        if isinstance(outcome, PoolError):
            failure, _ = pool_problem(outcome)
            for i, _job in chunk:
                self.entries[i] = failure
            return len(chunk)
        for (i, _job), result in zip(chunk, outcome.results, strict=False):
            self.entries[i] = (
                result
                if isinstance(result, Encoded)
                else job_problem(result, ["body", "jobs", i], self.curve)
            )
        return len(outcome.results)

    def call(self, chunk: Sequence[tuple[int, JobT]], budget_segments: int) -> Any:
        """The pool task of ``chunk`` within ``budget_segments``."""
        jobs = [job for _, job in chunk]
        return (within_budget, (self.run_chunk, jobs, self.limits, budget_segments))

    def line(self, entry: Entry) -> bytes:
        """One entry of ``results`` as JSON (the workers' bytes, never re-parsed), counted."""
        if isinstance(entry, Encoded):
            self.runtime.metrics.job_ok(self.endpoint, entry.arc_count, entry.line_count)
            return b'{"status":"ok","result":' + entry.body + b"}"
        self.runtime.metrics.job_error(self.endpoint)
        self.runtime.metrics.error(problem_kind(entry))
        return b'{"status":"error","error":' + orjson.dumps(entry) + b"}"


def validate(
    runtime: Runtime,
    raw_jobs: Sequence[Any],
    make_job: Callable[[Any, Loc], JobT],
    run_chunk: RunChunk[JobT],
    limits: Limits,
    endpoint: str,
    curve: str,
) -> Batch[JobT]:
    """Every job validated on its own by ``make_job`` (raising ``ValidationError`` or
    :class:`ProblemError` for a bad one, which becomes its error entry)."""
    settings = runtime.settings
    if len(raw_jobs) > settings.batch_max_jobs:
        detail = (
            f"the batch has {len(raw_jobs)} jobs; at most {settings.batch_max_jobs} are accepted"
        )
        raise ProblemError(problem("too_many_jobs", detail, limit=settings.batch_max_jobs))
    entries: list[Entry | None] = []
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
    return Batch(runtime, entries, pending, run_chunk, limits, endpoint, curve)


async def answer(
    batch: Batch[JobT], media_type: str, min_chunk_jobs: int, stream_chunk_jobs: int
) -> Response:
    """The batch's answer in ``media_type`` (the route's negotiated one, ``fixed_answer``):
    NDJSON in chunks of ``stream_chunk_jobs``, or one JSON document in as few chunks of at
    least ``min_chunk_jobs`` as the workers allow."""
    if media_type == NDJSON_MEDIA_TYPE:
        return answer_stream(batch, stream_chunk_jobs)
    return await answer_json(batch, min_chunk_jobs)
