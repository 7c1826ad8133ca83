"""A pool without worker processes, for the command line: tasks run in a thread of the
calling process.

:class:`InlinePool` is a :class:`~arcspline.worker.pool.WorkerPool` in every way the API
sees (admission, capacity, slots and their lanes, coalescing, drain), but its tasks are the
same functions called directly, in a thread so that the event loop stays free: no process to
start (a one-file command answers in the time of the work itself) and no pickling. What it
gives up: time limits are not enforced (a thread cannot be stopped; the caller waits for the
work), a cancelled task's thread runs on to its end while its slot goes to the next task
(the pool kills its worker instead), a task that crashes the interpreter takes the caller
with it, and tasks share one interpreter (the core holds the GIL), so ``size`` buys
concurrency, not parallelism. The threads are daemons: a process that is interrupted does
not wait for them.
"""

from __future__ import annotations

import asyncio
import contextlib
import functools
import threading
from collections.abc import Callable
from typing import Any, TypeVar

from .pool import WorkerPool

T = TypeVar("T")


class InlinePool(WorkerPool):
    """Tasks in threads of this process (``start_method="inline"``; see the module)."""

    def __init__(self, size: int, capacity: int, *, retry_after_s: float = 1.0) -> None:
        super().__init__(size, capacity, start_method="spawn", retry_after_s=retry_after_s)

    async def start(self) -> None:
        # Nothing to start; draining is the pool's own (it has no workers to stop).
        self.state = "ready"

    async def _execute(
        self,
        fn: Callable[..., T],
        args: tuple[Any, ...],
        time_limit_s: float,
        deadline: float | None,
        units: int = 1,
    ) -> T:
        self.running += units
        try:
            return await _in_daemon_thread(fn, args)
        finally:
            self.running -= units


async def _in_daemon_thread(fn: Callable[..., T], args: tuple[Any, ...]) -> T:
    """``fn(*args)`` in a thread of its own that does not hold the process open: an
    interrupted command (Ctrl-C) exits at once instead of waiting for the work it no longer
    wants (``asyncio.to_thread``'s executor would be joined at exit)."""
    loop = asyncio.get_running_loop()
    answer: asyncio.Future[T] = loop.create_future()

    def deliver(outcome: Callable[[], None]) -> None:
        with contextlib.suppress(RuntimeError):  # the loop has closed: no one is waiting
            loop.call_soon_threadsafe(outcome)

    def settle_result(value: T) -> None:
        if not answer.done():
            answer.set_result(value)

    def settle_error(error: BaseException) -> None:
        if not answer.done():
            answer.set_exception(error)

    def work() -> None:
        try:
            value = fn(*args)
        except BaseException as error:  # delivered to the caller, as to_thread would
            deliver(functools.partial(settle_error, error))
        else:
            deliver(functools.partial(settle_result, value))

    threading.Thread(target=work, name="arcspline-inline", daemon=True).start()
    return await answer
