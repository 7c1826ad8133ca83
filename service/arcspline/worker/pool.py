"""The process pool: how work reaches the worker processes, is bounded, timed, healed, drained.

:class:`WorkerPool` runs picklable functions (those of ``arcspline.worker.jobs``) in worker
processes from the event loop. Each worker is a process with a socket to the server; the
event loop writes a task to an idle worker's socket, and the socket's protocol
(:class:`_Worker`) sets the task's answer the moment its last byte arrives, in the loop's
I/O callback — no reader task has to be woken first — and tells the pool when the socket's
end-of-file says the worker has died. No threads are involved (``ProcessPoolExecutor`` takes
two per pool and, with them, the GIL on every task), and a worker can be killed and replaced
alone:

- admission is bounded by ``capacity`` units in flight (running or waiting), not by the pool
  size; beyond it :class:`QueueFullError` (the API answers 503 + Retry-After);
- a task waits for an idle worker; its time limit measures its running time, not its wait;
- two lanes share the workers: a waiting task of a single request (``lane="single"``) takes
  the next free worker before any waiting batch chunk (``lane="batch"``), so that singles
  wait for at most one chunk, not for the batches queued before them (docs/http-api.md,
  "Cancellation, drain and fairness");
- a task whose caller is cancelled (its client disconnected, or the drain ended) kills its
  worker, which is replaced: no worker computes what no one waits for;
- a task past its time limit (:class:`JobTimeoutError`) means a stuck worker: that worker is
  killed and replaced, so it never holds a slot for good;
- a worker that dies (killed, out of memory) is replaced, and its task retried once on
  another (tasks are pure functions); a second death is :class:`PoolUnavailableError`;
- :attr:`WorkerPool.ready` is false while a worker is being replaced;
- :meth:`WorkerPool.drain` waits for in-flight work, then stops the workers.

:class:`Coalescer` sends single jobs that arrive while every worker is busy to a worker
together, as one task: under load one compiled loop of the core serves many requests (and
one round trip to a worker), while an idle service still starts each job at once. A
coalesced task runs on while any of its requests waits for it; once all have gone, it is
cancelled (and its worker killed) like any other.

Dependency direction: the API imports this module; this module and
``arcspline.worker.jobs`` import only the geometry core and the outputs, never the web stack.
"""

from __future__ import annotations

import asyncio
import contextlib
import itertools
import logging
import math
import multiprocessing
import pickle
import signal
import socket
import struct
import typing
from collections import deque
from collections.abc import Callable, Sequence
from multiprocessing.connection import Connection
from multiprocessing.process import BaseProcess
from typing import Any, Generic, Literal, TypeVar

log = logging.getLogger(__name__)
T = TypeVar("T")
Item = TypeVar("Item")
Arg = TypeVar("Arg")

#: Modules the forkserver imports once, so that every worker starts with them loaded and warm
#: (``warm`` runs a job of each kind on import).
PRELOAD = ["arcspline.worker.warm"]
#: How long starting a worker may take before the pool gives up on it.
START_TIMEOUT_S = 60.0
#: How long a stopping worker may take to exit before it is killed.
STOP_TIMEOUT_S = 5.0

_READY = b"ready"


def warm() -> None:
    """A job of each kind (``arcspline.worker.warm``), run where it is called."""
    from arcspline.worker.warm import warm as run

    run()


# -- inside a worker process --------------------------------------------------------------


def _worker_main(conn: Connection) -> None:
    """A worker's life: announce readiness, then run tasks until told to stop (``None``)."""
    # Ctrl-C reaches the whole process group; the server drains and stops the workers itself.
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    for module in PRELOAD:
        __import__(module)
    # Once more in this process: a worker forked from the warm forkserver shares its memory
    # copy-on-write, and its first job would pay the page faults of every page it writes to
    # (measured: each worker's first request 2-3x the later ones).
    warm()
    conn.send_bytes(_READY)
    while True:
        try:
            task = pickle.loads(conn.recv_bytes())
        except EOFError:  # the server has gone
            return
        if task is None:
            return
        fn, args = task
        try:
            answer: tuple[bool, Any] = (True, fn(*args))
        except Exception as error:  # a bug in fn: the server re-raises it (a 500)
            answer = (False, error)
        try:
            message = pickle.dumps(answer, pickle.HIGHEST_PROTOCOL)
        except Exception as error:  # an unpicklable result or exception
            message = pickle.dumps((False, RuntimeError(f"unpicklable answer: {error!r}")))
        conn.send_bytes(message)


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


PoolState = Literal["stopped", "starting", "ready", "draining"]
#: Who waits for a task: a single request, or a batch (whose chunks yield to singles).
Lane = Literal["single", "batch"]


class _WorkerDiedError(Exception):
    """The worker running a task died before it answered."""


class _Worker(asyncio.Protocol):
    """The server's end of one worker process: its socket's protocol.

    It reads the worker's messages (frames of ``multiprocessing.Connection``) as they
    arrive: the first says the worker is ready, each later one answers the task in
    ``answer``. The socket's end (the worker has died or stopped) goes to ``on_death``.
    The protocol exists before its connection, so no message can arrive before it.
    """

    def __init__(self, process: BaseProcess, on_death: Callable[[_Worker], None]) -> None:
        self.process = process
        self._on_death = on_death
        self._transport: asyncio.Transport | None = None
        self._buffer = bytearray()
        #: The answer awaited from this worker, while it runs a task.
        self.answer: asyncio.Future[tuple[bool, Any]] | None = None
        #: Set once the pool has given the worker up (killed, dead or stopping).
        self.retired = False
        self.ready: asyncio.Future[None] = asyncio.get_running_loop().create_future()

    def connection_made(self, transport: asyncio.BaseTransport) -> None:
        # uvloop's transports do not subclass asyncio.Transport, but they are streams.
        self._transport = typing.cast(asyncio.Transport, transport)

    def data_received(self, data: bytes) -> None:
        buffer = self._buffer
        buffer += data
        while True:
            header = 4
            if len(buffer) < header:
                return
            (size,) = struct.unpack_from("!i", buffer)
            if size == -1:  # a message of 2 GiB or more
                header = 12
                if len(buffer) < header:
                    return
                (size,) = struct.unpack_from("!Q", buffer, 4)
            if len(buffer) < header + size:
                return
            message = bytes(buffer[header : header + size])
            del buffer[: header + size]
            self._deliver(message)

    def _deliver(self, message: bytes) -> None:
        if not self.ready.done():
            self.ready.set_result(None)
            return
        answer = self.answer
        if answer is not None and not answer.done():
            answer.set_result(pickle.loads(message))

    def connection_lost(self, exc: Exception | None) -> None:
        self._on_death(self)

    def send(self, message: bytes) -> None:
        """Write ``message`` (framed) to the worker; buffered by the transport if need be."""
        if self._transport is not None:
            self._transport.write(message)

    @property
    def closing(self) -> bool:
        return self._transport is None or self._transport.is_closing()

    def close(self) -> None:
        if self._transport is not None:
            self._transport.close()


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
        #: Workers replaced so far (after a death or a time limit).
        self.restarts = 0
        self.in_flight = 0
        self.running = 0
        self._context: Any = multiprocessing.get_context(start_method)
        if start_method == "forkserver":
            # Workers fork from a server that has imported the core and warmed it (warm.py).
            self._context.set_forkserver_preload([__name__, *PRELOAD])
        self._workers: list[_Worker] = []
        # Idle workers; one that died while waiting here is skipped when taken.
        self._idle_workers: asyncio.Queue[_Worker] = asyncio.Queue()
        self._starting = 0
        # One slot per worker: a task holds one from before it takes a worker until it ends.
        self._slots = _Slots(size)
        self._idle = asyncio.Event()
        self._idle.set()
        self._background: set[asyncio.Task[None]] = set()

    @property
    def ready(self) -> bool:
        """Up and accepting work, every worker alive (the readiness probe)."""
        return self.state == "ready" and self._starting == 0

    @property
    def pids(self) -> list[int]:
        """Process ids of the live workers (for diagnostics and tests)."""
        return sorted(w.process.pid for w in self._workers if w.process.pid is not None)

    @property
    def queue_depth(self) -> int:
        """Admitted units waiting for a worker."""
        return self.in_flight - self.running

    # -- lifecycle ---------------------------------------------------------------------

    async def start(self) -> None:
        """Start the workers and wait until each has imported the core."""
        self.state = "starting"
        self._starting += self.size
        await asyncio.gather(*(self._spawn() for _ in range(self.size)))
        self.state = "ready"

    async def drain(self, timeout_s: float) -> None:
        """Stop admitting, wait up to ``timeout_s`` for in-flight tasks, stop the workers."""
        self.state = "draining"
        with contextlib.suppress(TimeoutError):
            await asyncio.wait_for(self._idle.wait(), timeout_s)
        background = list(self._background)
        for task in background:
            task.cancel()
        await asyncio.gather(*background, return_exceptions=True)
        workers, self._workers = self._workers, []
        for worker in workers:
            self._retire(worker)
            with contextlib.suppress(OSError, RuntimeError):
                worker.send(_frame(pickle.dumps(None)))
        await asyncio.to_thread(_join_all, [w.process for w in workers])
        for worker in workers:
            worker.close()
        self.state = "stopped"

    # -- running tasks -----------------------------------------------------------------

    def admit(self, units: int = 1) -> _Admission:
        """Reserve room for ``units`` (requests or tasks), or refuse at once; a context
        manager that gives the room back."""
        if self.state in ("stopped", "starting"):
            raise PoolUnavailableError("the worker pool is not running")
        if self.in_flight + units > self.capacity:
            error = QueueFullError(f"{self.in_flight} in flight (capacity {self.capacity})")
            error.retry_after_s = self.retry_after_s
            raise error
        self.in_flight += units
        self._idle.clear()
        return _Admission(self, units)

    def _leave(self, units: int) -> None:
        self.in_flight -= units
        if self.in_flight == 0:
            self._idle.set()

    async def run(
        self, fn: Callable[..., T], *args: Any, time_limit_s: float, lane: Lane = "single"
    ) -> T:
        """Run ``fn(*args)`` in a worker, with ``time_limit_s`` of running time (a batch's
        chunk sent alone says ``lane="batch"``)."""
        with self.admit():
            return await self._run_admitted(fn, args, time_limit_s, None, lane)

    async def run_many(
        self,
        calls: Sequence[tuple[Callable[..., T], tuple[Any, ...]]],
        time_limit_s: float,
        lane: Lane = "batch",
    ) -> list[T | PoolError]:
        """Run several tasks admitted together; ``time_limit_s`` bounds them all, waits included.

        Each task's result, or the :class:`PoolError` it ended with, in order.
        """
        with self.admit(len(calls)):
            deadline = asyncio.get_running_loop().time() + time_limit_s
            outcomes = await asyncio.gather(
                *(self._run_admitted(fn, args, time_limit_s, deadline, lane) for fn, args in calls),
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
        lane: Lane,
    ) -> T:
        try:
            async with asyncio.timeout_at(deadline):
                await self._take_slot(lane)
        except TimeoutError:
            raise JobTimeoutError(time_limit_s) from None
        try:
            return await self._execute(fn, args, time_limit_s, deadline)
        finally:
            self._give_slot()

    async def _take_slot(self, lane: Lane = "single") -> None:
        await self._slots.take(lane)

    def _give_slot(self) -> None:
        self._slots.give()

    @property
    def free_slots(self) -> int:
        """Workers no task has claimed: tasks sent now would run at once."""
        return self._slots.free

    async def _execute(
        self,
        fn: Callable[..., T],
        args: tuple[Any, ...],
        time_limit_s: float,
        deadline: float | None,
        units: int = 1,
    ) -> T:
        """Run a task on an idle worker while holding a slot: time limit, one retry.

        ``units`` is how many admitted units the task carries (a coalesced task, several).
        """
        loop = asyncio.get_running_loop()
        message = _frame(pickle.dumps((fn, args), pickle.HIGHEST_PROTOCOL))
        for _attempt in range(2):
            worker = await self._idle_worker()
            answer = worker.answer = loop.create_future()
            # Buffered by the transport: the idle worker reads it at once.
            worker.send(message)
            self.running += units
            try:
                run_deadline = loop.time() + time_limit_s if deadline is None else deadline
                async with asyncio.timeout_at(run_deadline):
                    ok, value = await answer
            except TimeoutError:
                log.warning(
                    "a task exceeded its time limit of %g s; replacing its worker", time_limit_s
                )
                self._replace(worker, kill=True)
                raise JobTimeoutError(time_limit_s) from None
            except _WorkerDiedError:
                log.warning("a worker process died during a task; replacing it, retrying")
                continue
            except BaseException:
                # Cancelled while the worker runs: its answer would come to no one.
                self._replace(worker, kill=True)
                raise
            finally:
                self.running -= units
            worker.answer = None
            self._release(worker)
            if not ok:
                raise value
            result: T = value
            return result
        raise PoolUnavailableError("worker processes died twice while running this job")

    # -- workers -----------------------------------------------------------------------

    async def _idle_worker(self) -> _Worker:
        """An idle worker (one exists, or is starting, for each slot held)."""
        while True:
            if self._idle_workers.empty():
                try:
                    async with asyncio.timeout(START_TIMEOUT_S):
                        worker = await self._idle_workers.get()
                except TimeoutError:
                    raise PoolUnavailableError("no worker process could be started") from None
            else:
                worker = self._idle_workers.get_nowait()
            if worker.retired:
                continue
            if worker.closing or not worker.process.is_alive():
                # Dead while idle, and the event loop has not heard yet (say, killed with
                # the others by the OOM killer): not a failure of the task about to be sent.
                self._on_death(worker)
                continue
            return worker

    def _release(self, worker: _Worker) -> None:
        if not worker.retired:
            self._idle_workers.put_nowait(worker)

    async def _spawn(self) -> None:
        """Start one worker and wait for it to say it is ready (``_starting`` counted it).

        A worker that does not start is tried again, after a growing pause, until one does
        (or the pool drains); meanwhile the pool is not ready.
        """
        try:
            for attempt in itertools.count():
                if attempt:
                    await asyncio.sleep(min(2.0**attempt, 30.0))
                ours, theirs = socket.socketpair()
                child = Connection(theirs.detach())
                process = self._context.Process(
                    target=_worker_main, args=(child,), daemon=True, name="arcspline-worker"
                )
                worker = _Worker(process, self._on_death)
                try:
                    # Quick (the forkserver forks; the child imports on its own time), and
                    # not awaited, so that a cancelled start cannot lose a process.
                    process.start()
                    # The factory runs within this call, so it sees this iteration's worker.
                    await asyncio.get_running_loop().create_unix_connection(
                        lambda: worker,  # noqa: B023
                        sock=ours,
                    )
                except BaseException:
                    ours.close()
                    if process.pid is not None:
                        process.kill()
                    raise
                finally:
                    child.close()
                self._workers.append(worker)
                try:
                    await asyncio.wait_for(asyncio.shield(worker.ready), START_TIMEOUT_S)
                except (TimeoutError, _WorkerDiedError):
                    log.error("a worker process did not start (attempt %d)", attempt + 1)
                    self._retire(worker, kill=True)
                    continue
                except BaseException:
                    self._retire(worker, kill=True)
                    raise
                self._release(worker)
                return
        finally:
            self._starting -= 1

    def _on_death(self, worker: _Worker) -> None:
        if worker.retired:
            return
        self._retire(worker)
        worker.close()
        if not worker.ready.done():
            worker.ready.set_exception(_WorkerDiedError())
            return
        if worker.answer is not None and not worker.answer.done():
            worker.answer.set_exception(_WorkerDiedError())
        self._respawn()

    def _replace(self, worker: _Worker, *, kill: bool) -> None:
        if not worker.retired:
            self._retire(worker, kill=kill)
            self._respawn()

    def _respawn(self) -> None:
        if self.state in ("draining", "stopped"):
            return
        self.restarts += 1
        self._starting += 1  # not ready from now until the new worker is
        self._background_task(self._spawn())

    def _retire(self, worker: _Worker, *, kill: bool = False) -> None:
        """Forget a worker, and kill it if asked."""
        worker.retired = True
        if worker in self._workers:
            self._workers.remove(worker)
        if kill:
            with contextlib.suppress(ProcessLookupError, ValueError, AttributeError):
                worker.process.kill()
            self._background_task(_reap(worker))

    def _background_task(self, coroutine: Any) -> None:
        task = asyncio.create_task(coroutine)
        self._background.add(task)  # the loop keeps only weak references to tasks
        task.add_done_callback(self._background.discard)


class _Slots:
    """The workers' slots, handed to waiting tasks lane by lane: ``single`` first, then
    ``batch``, each in the order it asked (a semaphore with two queues)."""

    __slots__ = ("_waiting", "free")

    def __init__(self, size: int) -> None:
        self.free = size
        self._waiting: dict[Lane, deque[asyncio.Future[None]]] = {
            "single": deque(),
            "batch": deque(),
        }

    async def take(self, lane: Lane) -> None:
        # A task waits only while no slot is free, so a free slot means no one waits.
        if self.free:
            self.free -= 1
            return
        granted: asyncio.Future[None] = asyncio.get_running_loop().create_future()
        waiting = self._waiting[lane]
        waiting.append(granted)
        try:
            await granted
        except BaseException:
            if granted.done() and not granted.cancelled():
                self.give()  # handed over, then cancelled: the next one's
            else:
                waiting.remove(granted)
            raise

    def give(self) -> None:
        for waiting in self._waiting.values():  # "single", then "batch"
            while waiting:
                granted = waiting.popleft()
                if not granted.done():
                    granted.set_result(None)
                    return
        self.free += 1


class _Admission:
    """Room reserved by :meth:`WorkerPool.admit` (a class, not a generator: it is on the path
    of every request)."""

    __slots__ = ("pool", "units")

    def __init__(self, pool: WorkerPool, units: int) -> None:
        self.pool, self.units = pool, units

    def __enter__(self) -> None:
        return None

    def __exit__(self, *_: object) -> None:
        self.pool._leave(self.units)


async def _reap(worker: _Worker) -> None:
    """Collect a killed worker's exit status and close its socket, off the event loop."""
    try:
        await asyncio.to_thread(worker.process.join, STOP_TIMEOUT_S)
    finally:
        worker.close()


def _frame(payload: bytes) -> bytes:
    """``payload`` as ``multiprocessing.Connection.send_bytes`` frames it (for the worker)."""
    if len(payload) > 0x7FFFFFFF:
        return struct.pack("!iQ", -1, len(payload)) + payload
    return struct.pack("!i", len(payload)) + payload


def _join_all(processes: list[BaseProcess]) -> None:
    for process in processes:
        process.join(STOP_TIMEOUT_S)
        if process.is_alive():
            process.kill()
            process.join()


class Coalescer(Generic[Item, Arg, T]):
    """Runs ``fn(items, arg) -> results`` for single items, several items per task under load.

    An item waits in a queue; a dispatcher takes a free worker slot, then its share of what
    is queued (up to ``max_items``) as one task: all of it when no other worker is free,
    else an even split with the free ones, so that no worker idles while another has a
    long task. With a worker free, an item goes alone and at once; with all busy, the items
    that pile up meanwhile share the next task. Each item counts as
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
                await pool._take_slot("single")
                try:
                    # Shared with the workers still free, so that none idles while this
                    # task runs (their dispatchers take the rest).
                    share = -(-len(self._queue) // (1 + pool.free_slots))
                    batch = [self._queue.popleft() for _ in range(min(self._max_items, share))]
                    batch = [(item, result) for item, result in batch if not result.done()]
                    if batch:
                        await self._run(batch)
                finally:
                    pool._give_slot()
        finally:
            self._dispatchers -= 1

    async def _run(self, batch: list[tuple[Item, asyncio.Future[T]]]) -> None:
        items = [item for item, _ in batch]
        limit = self._time_limit_s * len(items)
        self.tasks += 1
        dispatcher = asyncio.current_task()
        assert dispatcher is not None
        waiting = len(batch)
        running = abandoned = False

        def forget(_result: asyncio.Future[T]) -> None:
            # A request that has gone (cancelled: its client disconnected) waits no more;
            # the task is cancelled, its worker killed, once none of its requests waits.
            nonlocal waiting, abandoned
            waiting -= 1
            if waiting == 0 and running and not abandoned:
                abandoned = True
                dispatcher.cancel()

        for _item, result in batch:
            result.add_done_callback(forget)
        try:
            running = True
            results = await self.pool._execute(
                self._fn, (items, self._arg), limit, None, units=len(items)
            )
        except asyncio.CancelledError:
            if abandoned and dispatcher.uncancel() == 0:
                return  # ours: the dispatcher goes on with the queue
            raise
        except Exception as error:  # PoolError, or a bug in fn: every waiting request gets it
            for _, result in batch:
                if not result.done():
                    result.set_exception(error)
            return
        finally:
            running = False
        for (_, result), value in zip(batch, results, strict=True):
            if not result.done():
                result.set_result(value)


def chunk_sizes(jobs: int, workers: int, min_jobs: int) -> list[int]:
    """Split ``jobs`` into at most ``workers`` nearly equal chunks of at least ``min_jobs``."""
    if jobs <= 0:
        return []
    count = max(1, min(workers, math.ceil(jobs / min_jobs)))
    base, extra = divmod(jobs, count)
    return [base + (1 if i < extra else 0) for i in range(count)]
