"""The process pool: how work reaches the worker processes, is bounded, timed, healed, drained.

:class:`WorkerPool` runs picklable functions (those of ``service.jobs``) from the event loop:

- admission is bounded by ``capacity`` units in flight (running or waiting), not by the pool
  size; beyond it :class:`QueueFullError` (the API answers 503 + Retry-After);
- at most ``size`` tasks are handed to the executor at once, so a task starts on an idle
  worker and its time limit measures its running time, not its wait;
- a task past its time limit (:class:`JobTimeoutError`) means a stuck worker: the workers are
  killed and the pool rebuilt, so it never holds a slot for good;
- a dead worker (killed, out of memory) breaks a ``ProcessPoolExecutor`` as a whole: the
  pool is rebuilt and each affected task retried once (they are pure functions); a second
  failure is :class:`PoolUnavailableError`;
- :meth:`WorkerPool.drain` waits for in-flight work, then shuts the workers down.

:class:`Coalescer` sends single jobs that arrive while every worker is busy to a worker
together, as one task: under load one vectorised call of the core serves many requests (and
one round trip to a worker), while an idle service still starts each job at once.

Dependency direction: the API imports this module; this module and ``service.jobs`` import
only the geometry core and the G-code writer, never the web stack.
"""

from __future__ import annotations

import asyncio
import contextlib
import logging
import math
import multiprocessing
import os
import signal
import time
from collections import deque
from collections.abc import Callable, Iterator, Sequence
from concurrent.futures import ProcessPoolExecutor
from concurrent.futures.process import BrokenProcessPool
from typing import Any, Generic, Literal, TypeVar

log = logging.getLogger(__name__)
T = TypeVar("T")
Item = TypeVar("Item")
Arg = TypeVar("Arg")

#: Modules the forkserver imports once, so that every worker starts with them loaded.
PRELOAD = ["service.jobs"]


def _initialize_worker() -> None:
    # Ctrl-C reaches the whole process group; the server drains and stops the workers itself.
    signal.signal(signal.SIGINT, signal.SIG_IGN)


def _warm() -> int:
    """A no-op task that makes the executor start a worker; returns the worker's pid."""
    time.sleep(0.01)  # keeps this worker busy while the next warm task starts another
    return os.getpid()


# -- the pool (runs on the event loop) ----------------------------------------------------


class PoolError(Exception):
    """Base of the pool's refusals; ``retry_after_s`` is set where a retry makes sense."""

    retry_after_s: float | None = None


class QueueFullError(PoolError):
    """Admission refused: ``capacity`` tasks are already in flight."""


class JobTimeoutError(PoolError):
    """A task ran past its time limit (its worker was killed)."""

    def __init__(self, time_limit_s: float) -> None:
        super().__init__(f"the job did not finish within its time limit of {time_limit_s:g} s")
        self.time_limit_s = time_limit_s


class PoolUnavailableError(PoolError):
    """The pool cannot run the task: not started, stopped, or failing repeatedly."""


PoolState = Literal["stopped", "starting", "ready", "rebuilding", "draining"]

#: How long starting (or restarting) the workers may take before the pool gives up.
WARM_TIMEOUT_S = 60.0
#: How often the watchdog looks for a worker that died while the pool was idle.
WATCH_INTERVAL_S = 0.25


class WorkerPool:
    """A bounded, self-healing process pool for the event loop (see the module docstring)."""

    def __init__(
        self,
        size: int,
        capacity: int,
        *,
        start_method: Literal["forkserver", "spawn"] = "forkserver",
        retry_after_s: float = 1.0,
    ) -> None:
        self.size = size
        self.capacity = capacity
        self.retry_after_s = retry_after_s
        self.state: PoolState = "stopped"
        self.rebuilds = 0
        self.in_flight = 0
        self.running = 0
        self._start_method = start_method
        self._executor: ProcessPoolExecutor | None = None
        self._generation = 0
        self._slots = asyncio.Semaphore(size)
        self._lock = asyncio.Lock()
        self._idle = asyncio.Event()
        self._idle.set()
        self._watchdog: asyncio.Task[None] | None = None
        # Results awaited from the workers, by executor generation; those whose workers were
        # replaced before they answered are "lost" (see _rebuild).
        self._waiting: dict[asyncio.Future[Any], int] = {}
        self._lost: set[asyncio.Future[Any]] = set()

    @property
    def ready(self) -> bool:
        """Up and accepting work (the readiness probe)."""
        return self.state == "ready" and not self._broken()

    @property
    def pids(self) -> list[int]:
        """Process ids of the current workers (for diagnostics and tests)."""
        return sorted(getattr(self._executor, "_processes", None) or {})

    @property
    def queue_depth(self) -> int:
        """Admitted tasks waiting for a worker."""
        return self.in_flight - self.running

    # -- lifecycle ---------------------------------------------------------------------

    async def start(self) -> None:
        """Start the workers and wait until each has imported the core."""
        self.state = "starting"
        async with self._lock:
            self._executor = await self._new_executor()
        self.state = "ready"
        self._watchdog = asyncio.create_task(self._watch(), name="worker-pool-watchdog")

    async def drain(self, timeout_s: float) -> None:
        """Stop admitting, wait up to ``timeout_s`` for in-flight tasks, stop the workers."""
        self.state = "draining"
        with contextlib.suppress(TimeoutError):
            await asyncio.wait_for(self._idle.wait(), timeout_s)
        if self._watchdog is not None:
            self._watchdog.cancel()
            with contextlib.suppress(asyncio.CancelledError):
                await self._watchdog
        executor, self._executor = self._executor, None
        if executor is not None:
            await asyncio.to_thread(executor.shutdown, wait=True, cancel_futures=True)
        self.state = "stopped"

    # -- running tasks -----------------------------------------------------------------

    @contextlib.contextmanager
    def admit(self, tasks: int = 1) -> Iterator[None]:
        """Reserve room for ``tasks`` tasks, or refuse at once."""
        if self.state in ("stopped", "starting") or self._executor is None:
            raise PoolUnavailableError("the worker pool is not running")
        if self.in_flight + tasks > self.capacity:
            error = QueueFullError(f"{self.in_flight} tasks in flight (capacity {self.capacity})")
            error.retry_after_s = self.retry_after_s
            raise error
        self.in_flight += tasks
        self._idle.clear()
        try:
            yield
        finally:
            self.in_flight -= tasks
            if self.in_flight == 0:
                self._idle.set()

    async def run(self, fn: Callable[..., T], *args: Any, time_limit_s: float) -> T:
        """Run ``fn(*args)`` in a worker, with ``time_limit_s`` of running time."""
        with self.admit():
            return await self._run_admitted(fn, args, time_limit_s, deadline=None)

    async def run_many(
        self, calls: Sequence[tuple[Callable[..., T], tuple[Any, ...]]], time_limit_s: float
    ) -> list[T | PoolError]:
        """Run several tasks admitted together; ``time_limit_s`` bounds them all, waits included.

        Each task's result, or the :class:`PoolError` it ended with, in order.
        """
        with self.admit(len(calls)):
            deadline = asyncio.get_running_loop().time() + time_limit_s
            outcomes = await asyncio.gather(
                *(self._run_admitted(fn, args, time_limit_s, deadline) for fn, args in calls),
                return_exceptions=True,
            )
        results: list[T | PoolError] = []
        for outcome in outcomes:
            if isinstance(outcome, BaseException) and not isinstance(outcome, PoolError):
                raise outcome
            results.append(outcome)
        return results

    async def _run_admitted(
        self,
        fn: Callable[..., T],
        args: tuple[Any, ...],
        time_limit_s: float,
        deadline: float | None,
    ) -> T:
        try:
            async with asyncio.timeout_at(deadline):
                await self._slots.acquire()
        except TimeoutError:
            raise JobTimeoutError(time_limit_s) from None
        try:
            return await self._execute(fn, args, time_limit_s, deadline)
        finally:
            self._slots.release()

    async def _execute(
        self,
        fn: Callable[..., T],
        args: tuple[Any, ...],
        time_limit_s: float,
        deadline: float | None,
        units: int = 1,
    ) -> T:
        """Run a task in a worker while holding a slot: time limit, rebuild, one retry.

        ``units`` is how many admitted units the task carries (a coalesced task, several).
        """
        loop = asyncio.get_running_loop()
        for _attempt in range(2):
            async with self._lock:  # held while rebuilding: wait for the new workers
                executor, generation = self._executor, self._generation
            if executor is None:
                raise PoolUnavailableError("the worker pool has stopped")
            try:
                future = executor.submit(fn, *args)
            except BrokenProcessPool:
                await self._rebuild(generation)
                continue
            self.running += units
            waiting = asyncio.wrap_future(future)
            self._waiting[waiting] = generation
            try:
                run_deadline = loop.time() + time_limit_s if deadline is None else deadline
                async with asyncio.timeout_at(run_deadline):
                    return await waiting
            except TimeoutError:
                log.warning("a task exceeded its time limit; restarting the workers")
                await self._rebuild(generation, kill=True)
                raise JobTimeoutError(time_limit_s) from None
            except BrokenProcessPool:
                log.warning("a worker process died; restarting the workers, retrying")
                await self._rebuild(generation)
            except asyncio.CancelledError:
                if waiting not in self._lost:
                    raise
                # Its workers were replaced while it waited (see _rebuild): retry.
            finally:
                self.running -= units
                self._waiting.pop(waiting, None)
                self._lost.discard(waiting)
        raise PoolUnavailableError("worker processes died twice while running this job")

    # -- rebuilding --------------------------------------------------------------------

    def _broken(self) -> bool:
        # ProcessPoolExecutor marks itself broken as soon as a worker dies (even when idle);
        # ``_broken`` is private, but public only from Python 3.14 on.
        return bool(getattr(self._executor, "_broken", False))

    async def _new_executor(self) -> ProcessPoolExecutor:
        context = multiprocessing.get_context(self._start_method)
        if self._start_method == "forkserver":
            # Workers fork from a server that has imported numpy and the core already.
            context.set_forkserver_preload([__name__, *PRELOAD])
        executor = ProcessPoolExecutor(
            max_workers=self.size, mp_context=context, initializer=_initialize_worker
        )
        # Executors start workers on demand; one warm task per worker starts them all now.
        warm = [asyncio.wrap_future(executor.submit(_warm)) for _ in range(self.size)]
        try:
            await asyncio.wait_for(asyncio.gather(*warm), WARM_TIMEOUT_S)
        except BaseException:
            _kill_workers(executor)
            executor.shutdown(wait=False, cancel_futures=True)
            raise
        return executor

    async def _rebuild(self, generation: int, *, kill: bool = False) -> None:
        """Replace the executor of ``generation`` (once, however many tasks ask)."""
        async with self._lock:
            if generation != self._generation or self._executor is None:
                return
            previous_state = self.state
            self.state = "rebuilding"
            old = self._executor
            if kill:
                _kill_workers(old)
            old.shutdown(wait=False, cancel_futures=True)
            # A broken executor fails its pending futures, except one submitted in the instant
            # it broke (CPython's check of ``_broken`` in submit() races with the manager
            # thread), which would wait forever. Whatever the old workers still owe is lost.
            for waiting, owner in list(self._waiting.items()):
                if owner == generation and not waiting.done():
                    self._lost.add(waiting)
                    waiting.cancel()
            try:
                self._executor = await self._new_executor()
            except BaseException:
                self._executor = None
                self.state = "stopped"
                log.exception("could not restart the worker processes")
                raise PoolUnavailableError("the worker pool could not be restarted") from None
            self._generation += 1
            self.rebuilds += 1
            self.state = "draining" if previous_state == "draining" else "ready"
            log.info("worker processes restarted (rebuild %d)", self.rebuilds)

    async def _watch(self) -> None:
        """Rebuild a pool whose worker died while no task was there to notice."""
        while True:
            await asyncio.sleep(WATCH_INTERVAL_S)
            if self._broken():
                with contextlib.suppress(PoolUnavailableError):
                    await self._rebuild(self._generation)


class Coalescer(Generic[Item, Arg, T]):
    """Runs ``fn(items, arg) -> results`` for single items, several items per task under load.

    An item waits in a queue; a dispatcher takes a free worker slot, then everything queued
    (up to ``max_items``) as one task. With a worker free, an item goes alone and at once;
    with all busy, the items that pile up meanwhile share the next task. Each item counts as
    one unit of the pool's capacity. A task of ``k`` items gets ``k × time_limit_s``; if it
    fails (time limit, workers lost twice), each of its items gets that error.
    """

    def __init__(
        self,
        pool: WorkerPool,
        fn: Callable[[list[Item], Arg], list[T]],
        arg: Arg,
        *,
        time_limit_s: float,
        max_items: int,
    ) -> None:
        self.pool = pool
        self._fn = fn
        self._arg = arg
        self._time_limit_s = time_limit_s
        self._max_items = max_items
        self._queue: deque[tuple[Item, asyncio.Future[T]]] = deque()
        self._dispatchers = 0
        self._running: set[asyncio.Task[None]] = set()
        #: Tasks sent to the workers so far (fewer than the items when they coalesce).
        self.tasks = 0

    async def run(self, item: Item) -> T:
        """``fn([item, ...], arg)``'s result for ``item``."""
        with self.pool.admit():
            result: asyncio.Future[T] = asyncio.get_running_loop().create_future()
            self._queue.append((item, result))
            if self._dispatchers < self.pool.size:
                self._dispatchers += 1
                task = asyncio.create_task(self._dispatch(), name="coalescer-dispatch")
                self._running.add(task)  # the loop keeps only weak references to tasks
                task.add_done_callback(self._running.discard)
            return await result

    async def _dispatch(self) -> None:
        pool = self.pool
        try:
            while self._queue:
                await pool._slots.acquire()
                try:
                    batch = [
                        self._queue.popleft() for _ in range(min(self._max_items, len(self._queue)))
                    ]
                    batch = [(item, result) for item, result in batch if not result.done()]
                    if batch:
                        await self._run(batch)
                finally:
                    pool._slots.release()
        finally:
            self._dispatchers -= 1

    async def _run(self, batch: list[tuple[Item, asyncio.Future[T]]]) -> None:
        items = [item for item, _ in batch]
        limit = self._time_limit_s * len(items)
        self.tasks += 1
        try:
            results = await self.pool._execute(
                self._fn, (items, self._arg), limit, None, units=len(items)
            )
        except Exception as error:  # PoolError, or a bug in fn: every waiting request gets it
            for _, result in batch:
                if not result.done():
                    result.set_exception(error)
            return
        for (_, result), value in zip(batch, results, strict=True):
            if not result.done():
                result.set_result(value)


def _kill_workers(executor: ProcessPoolExecutor) -> None:
    # ``_processes`` is private; Python 3.14 offers ``kill_workers()`` for this.
    processes = getattr(executor, "_processes", None) or {}
    for process in list(processes.values()):
        with contextlib.suppress(ProcessLookupError, ValueError, AttributeError):
            process.kill()


def chunk_sizes(jobs: int, workers: int, min_jobs: int) -> list[int]:
    """Split ``jobs`` into at most ``workers`` nearly equal chunks of at least ``min_jobs``."""
    if jobs <= 0:
        return []
    count = max(1, min(workers, math.ceil(jobs / min_jobs)))
    base, extra = divmod(jobs, count)
    return [base + (1 if i < extra else 0) for i in range(count)]
