"""A batch answered as NDJSON: one line per job, in order, each sent as soon as its chunk and
every chunk before it are answered (docs/http-api.md, "Batches"). Neither side holds the whole
answer: the chunks run ahead of the line being sent by at most one per worker.
"""

from __future__ import annotations

import asyncio
from collections import deque
from collections.abc import AsyncIterator
from typing import TYPE_CHECKING, Any, TypeVar

from starlette.responses import StreamingResponse

from arcspline.worker.jobs import Budgeted
from arcspline.worker.pool import PoolError

from .errors import problem
from .schemas import NDJSON_MEDIA_TYPE

if TYPE_CHECKING:
    from .batch import Batch

JobT = TypeVar("JobT")


def answer_stream(batch: Batch[JobT], chunk_jobs: int) -> StreamingResponse:
    """The NDJSON answer: one line per job, in order, sent as the chunks finish."""
    return StreamingResponse(_lines(batch, chunk_jobs), media_type=NDJSON_MEDIA_TYPE)


async def _lines(batch: Batch[JobT], chunk_jobs: int) -> AsyncIterator[bytes]:
    """Chunks of ``chunk_jobs`` run ahead of the one being sent by at most one per worker
    (so finished chunks held for their turn stay few); each within the whole budget, and a
    chunk that stops at it is continued by a chunk of its remaining jobs. No total budget:
    nothing holds more than the chunks in flight. ``batch_time_limit_s`` bounds the whole."""
    runtime = batch.runtime
    pool = runtime.running_pool()
    loop = asyncio.get_running_loop()
    deadline = loop.time() + runtime.settings.batch_time_limit_s
    budget = runtime.settings.batch_max_segments
    queue = deque(
        batch.pending[begin : begin + chunk_jobs]
        for begin in range(0, len(batch.pending), chunk_jobs)
    )
    running: deque[tuple[list[tuple[int, JobT]], asyncio.Task[Any]]] = deque()

    def submit(chunk: list[tuple[int, JobT]], front: bool = False) -> None:
        fn, args = batch.call(chunk, budget)
        left_s = max(deadline - loop.time(), 1e-3)
        task = asyncio.ensure_future(pool.run(fn, *args, time_limit_s=left_s, lane="batch"))
        (running.appendleft if front else running.append)((chunk, task))

    sent = 0
    try:
        while True:
            while queue and len(running) <= pool.size:
                submit(queue.popleft())
            lines = []
            while sent < len(batch.entries) and batch.entries[sent] is not None:
                entry = batch.entries[sent]
                assert entry is not None
                batch.entries[sent] = None  # sent: let it go
                lines.append(batch.line(entry) + b"\n")
                sent += 1
            if lines:
                yield b"".join(lines)
            if not running:
                return
            chunk, task = running.popleft()
            try:
                outcome = await task
            except PoolError as error:
                outcome = error
            answered = batch.fill(chunk, outcome)
            if answered == 0 and isinstance(outcome, Budgeted):  # one job past the budget
                i, _job = chunk[0]
                batch.entries[i] = too_large_job(i, budget)
                answered = 1
            if answered < len(chunk):
                submit(chunk[answered:], front=True)
    finally:
        # Ended early (the client left): the tasks ahead are abandoned, not awaited here.
        for _chunk, task in running:
            task.cancel()
            task.add_done_callback(_retrieve)


def _retrieve(task: asyncio.Task[Any]) -> None:
    """Takes an abandoned task's outcome, so that it is not logged as never retrieved."""
    if not task.cancelled():
        task.exception()


def too_large_job(i: int, budget: int) -> dict[str, Any]:
    """The entry of a streamed job that alone needs more than the budget."""
    detail = (
        f"body.jobs.{i}: needs more than the budget of {budget} output segments of a "
        "streamed chunk (ARCSPLINE_BATCH_MAX_SEGMENTS); raise its tolerance"
    )
    return problem("work_too_large", detail, limit=budget)
