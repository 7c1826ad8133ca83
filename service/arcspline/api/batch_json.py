"""A batch answered as one JSON document, ``{"results": [...]}``, within the batch's work
budget (docs/http-api.md, "Batches"; docs/deployment.md, "Memory"): the chunks share the
budget, a batch that would pass it is refused before more is computed or held, and the answer
is sent in pieces, never joined whole.
"""

from __future__ import annotations

import asyncio
import itertools
import weakref
from collections.abc import Callable, Iterator, Sequence
from typing import TYPE_CHECKING, Any, TypeVar

from starlette.responses import Response
from starlette.types import Receive, Scope, Send

from arcspline.worker.jobs import Budgeted
from arcspline.worker.pool import PoolError, chunk_sizes

from .errors import ProblemError, problem
from .schemas import NDJSON_MEDIA_TYPE

if TYPE_CHECKING:
    from .batch import Batch

JobT = TypeVar("JobT")

#: Bytes per body message of a JSON batch: the event loop copies and (with gzip, in a
#: thread) compresses one piece at a time, never the whole answer at once.
PIECE_BYTES = 1 << 20


async def answer_json(batch: Batch[JobT], min_chunk_jobs: int) -> Response:
    """``{"results": [...]}``, the whole batch within ``batch_max_segments``: the chunks
    (a few, large) share the budget by their number of jobs, and a chunk that would pass its
    share ends the batch with ``work_too_large`` before more is computed or held. At most
    ``Runtime.json_answers`` such answers are computed or sent at once (the others wait,
    within the batch's time limit), so the budget bounds the server's memory too."""
    runtime = batch.runtime
    settings = runtime.settings
    lane = runtime.json_answers
    loop = asyncio.get_running_loop()
    deadline = loop.time() + settings.batch_time_limit_s
    try:
        async with asyncio.timeout_at(deadline):
            await lane.acquire()
    except TimeoutError:
        raise ProblemError(_waited_too_long(settings.batch_time_limit_s)) from None
    try:
        document = await _compute(batch, min_chunk_jobs, deadline)
        return PiecesResponse(document, release=lane.release)
    except BaseException:
        lane.release()
        raise


def _waited_too_long(time_limit_s: float) -> dict[str, Any]:
    detail = (
        f"the batch waited its whole time limit of {time_limit_s:g} s for other batches' "
        f"answers to be sent; retry, or ask for `Accept: {NDJSON_MEDIA_TYPE}`"
    )
    return problem("time_limit", detail, limit=time_limit_s)


async def _compute(batch: Batch[JobT], min_chunk_jobs: int, deadline: float) -> Iterator[bytes]:
    """The JSON answer's parts, once every chunk is answered within the budget."""
    settings = batch.runtime.settings
    budget = settings.batch_max_segments
    pool = batch.runtime.running_pool()
    total = len(batch.pending)
    sizes = chunk_sizes(total, min(pool.size, pool.capacity), min_chunk_jobs)
    bounds = [0, *itertools.accumulate(sizes)]
    chunks = [batch.pending[begin:end] for begin, end in itertools.pairwise(bounds)]
    calls = [batch.call(chunk, budget * len(chunk) // total) for chunk in chunks]
    time_limit_s = max(deadline - asyncio.get_running_loop().time(), 1e-3)
    outcomes = await pool.run_many(calls, time_limit_s=time_limit_s)
    for k, outcome in enumerate(outcomes):
        if isinstance(outcome, Budgeted) and not outcome.complete:
            outcomes[k] = await _continue(batch, chunks[k], outcome, outcomes, deadline)
    if any(isinstance(o, Budgeted) and not o.complete for o in outcomes):
        raise ProblemError(_over_budget(outcomes, total, budget))
    for chunk, outcome in zip(chunks, outcomes, strict=True):
        batch.fill(chunk, outcome)
    outcomes.clear()  # the entries hold the answers now; each goes once it is sent
    return _document(batch)


async def _continue(
    batch: Batch[JobT],
    chunk: Sequence[tuple[int, JobT]],
    outcome: Budgeted,
    outcomes: list[Budgeted | PoolError],
    deadline: float,
) -> Budgeted:
    """A chunk that passed its share, continued with what the others left of the budget
    (so jobs spread unevenly over the chunks are not refused for it)."""
    used = sum(o.segments for o in outcomes if isinstance(o, Budgeted))
    left = batch.runtime.settings.batch_max_segments - used
    if left <= 0:
        return outcome
    pool = batch.runtime.running_pool()
    fn, args = batch.call(chunk[len(outcome.results) :], left)
    time_limit_s = max(deadline - asyncio.get_running_loop().time(), 1e-3)
    rest: Budgeted = await pool.run(fn, *args, time_limit_s=time_limit_s, lane="batch")
    return Budgeted(outcome.results + rest.results, outcome.segments + rest.segments, rest.complete)


def _over_budget(outcomes: list[Budgeted | PoolError], jobs: int, budget: int) -> dict[str, Any]:
    """The ``work_too_large`` problem: the budget, what the batch would need (a lower bound,
    and an estimate from the jobs answered), and how to split it."""
    answered = [o for o in outcomes if isinstance(o, Budgeted)]
    done = sum(len(o.results) for o in answered)
    used = sum(o.segments for o in answered)
    per_job = max(used / done if done else 0.0, 1.0)
    fit = max(1, int(budget // per_job))
    detail = (
        f"the batch needs more than its budget of {budget} output segments "
        f"(ARCSPLINE_BATCH_MAX_SEGMENTS): {done} of its {jobs} jobs took {used} segments, "
        f"about {per_job:.0f} each, so all would take about {per_job * jobs:.0f}; raise the "
        f"tolerance, send at most {fit} such jobs per batch, or ask for "
        f"`Accept: {NDJSON_MEDIA_TYPE}` (a stream has no total budget)"
    )
    return problem("work_too_large", detail, limit=budget)


def _document(batch: Batch[Any]) -> Iterator[bytes]:
    """The JSON answer's parts, made one entry at a time as they are sent."""
    yield b'{"results":['
    for i, entry in enumerate(batch.entries):
        assert entry is not None, "every job has an answer"
        batch.entries[i] = None  # sent: let it go
        yield (b"," if i else b"") + batch.line(entry)
    yield b"]}"


class PiecesResponse(Response):
    """A JSON body sent in pieces of about :data:`PIECE_BYTES` (its ``Content-Length``
    known), made from ``parts`` as it goes: no copy of the whole body is ever made, and the
    event loop serves other requests between pieces."""

    media_type = "application/json"

    def __init__(self, parts: Iterator[bytes], release: Callable[[], None]) -> None:
        self._pieces = list(_pieces(parts))
        super().__init__(b"")
        self.headers["content-length"] = str(sum(map(len, self._pieces)))
        # ``release`` once sent, or once this response is dropped unsent (a middleware
        # answered instead): never twice, never not at all.
        self._release = weakref.finalize(self, release)

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        try:
            start = {"type": "http.response.start", "status": self.status_code}
            await send({**start, "headers": self.raw_headers})
            pieces, self._pieces = self._pieces, []
            last = len(pieces) - 1
            for k, piece in enumerate(pieces):
                pieces[k] = b""  # sent: let it go
                more = k < last
                await send({"type": "http.response.body", "body": piece, "more_body": more})
        finally:
            self._release()


def _pieces(parts: Iterator[bytes]) -> Iterator[bytes]:
    """``parts`` joined into pieces of about :data:`PIECE_BYTES`."""
    group: list[bytes] = []
    size = 0
    for part in parts:
        group.append(part)
        size += len(part)
        if size >= PIECE_BYTES:
            yield b"".join(group)
            group, size = [], 0
    if group:
        yield b"".join(group)
