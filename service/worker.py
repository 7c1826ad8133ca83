"""The process pool: the jobs it runs, and how it starts, admits, times out, rebuilds and drains.

Two halves, one concept. The *job functions* (``approximate_one``, ``approximate_chunk``,
``preview_spline``) run inside worker processes: pure, picklable in and out, they call the
geometry core and the G-code writer and serialise the response body there, so JSON encoding
runs in parallel too. :class:`WorkerPool` runs them from the event loop:

- admission is bounded by ``capacity`` tasks in flight (running or waiting), not by the pool
  size; beyond it :class:`QueueFullError` (the API answers 503 + Retry-After);
- at most ``size`` tasks are handed to the executor at once, so a task starts on an idle
  worker and its time limit measures its running time, not its wait;
- a task past its time limit (:class:`JobTimeoutError`) means a stuck worker: the workers are
  killed and the pool rebuilt, so it never holds a slot for good;
- a dead worker (killed, out of memory) breaks a ``ProcessPoolExecutor`` as a whole: the
  pool is rebuilt and each affected task retried once (they are pure functions); a second
  failure is :class:`PoolUnavailableError`;
- :meth:`WorkerPool.drain` waits for in-flight work, then shuts the workers down.

Dependency direction: the API imports this module; this module imports only the geometry
core and the G-code writer, never the web stack.
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
from collections.abc import Callable, Iterator, Sequence
from concurrent.futures import ProcessPoolExecutor
from concurrent.futures.process import BrokenProcessPool
from dataclasses import dataclass
from typing import Any, Literal, TypeVar

import numpy as np
import orjson

from service.gcode import GcodeError, GcodeOptions, write_program
from service.geometry import (
    ArcSpline,
    GeometryError,
    Limits,
    Spiral,
    Strategy,
    approximate,
    approximate_many,
)

log = logging.getLogger(__name__)
T = TypeVar("T")

# -- job functions (run in the worker processes) ----------------------------------------


@dataclass(frozen=True, slots=True)
class ParametersSpec:
    """A spiral given by the paper's five parameters (§1)."""

    start: tuple[float, float]
    start_tangent: tuple[float, float]
    turn_angle_deg: float
    end_curvature: float


@dataclass(frozen=True, slots=True)
class ControlPointsSpec:
    """A spiral given by its four Bézier control points."""

    control_points: tuple[tuple[float, float], ...]


SpiralSpec = ParametersSpec | ControlPointsSpec


@dataclass(frozen=True, slots=True)
class Job:
    """One approximation request, as the worker needs it."""

    spiral: SpiralSpec
    tolerance: float
    strategy: Strategy = "subdivide"
    gcode: GcodeOptions | None = None


@dataclass(frozen=True, slots=True)
class Encoded:
    """A job's response body, already JSON, with the counts the metrics need."""

    body: bytes
    arc_count: int
    line_count: int


JobResult = Encoded | GeometryError | GcodeError


def build_spiral(spec: SpiralSpec) -> Spiral:
    """The core's spiral for ``spec``; raises :class:`GeometryError` for an invalid one."""
    if isinstance(spec, ControlPointsSpec):
        return Spiral.from_control_points(spec.control_points)
    return Spiral.from_parameters(
        start=spec.start,
        start_tangent=spec.start_tangent,
        turn_angle_deg=spec.turn_angle_deg,
        end_curvature=spec.end_curvature,
    )


def encode(spline: ArcSpline, gcode: str | None) -> Encoded:
    """The ``ApproximateResponse`` body of ``spline`` as JSON bytes.

    Built from the columns' ``tolist()`` (one conversion per column, not per value) and
    serialised by orjson: no per-segment model objects, which a 1000-spiral batch would
    otherwise spend most of its time building.
    """
    c = spline.columns
    rows = zip(
        c.is_arc.tolist(),
        c.start.tolist(),
        c.end.tolist(),
        c.center.tolist(),
        c.radius.tolist(),
        c.start_angle_rad.tolist(),
        c.sweep_rad.tolist(),
        c.length.tolist(),
        c.u_start.tolist(),
        c.u_end.tolist(),
        c.max_deviation.tolist(),
        c.u_at_max_deviation.tolist(),
        strict=True,
    )
    segments = [
        {
            "type": "arc",
            "start": start,
            "end": end,
            "center": center,
            "radius": radius,
            "direction": "ccw" if sweep > 0.0 else "cw",
            "start_angle_rad": angle,
            "sweep_rad": sweep,
            "length": length,
            "u_start": u0,
            "u_end": u1,
            "max_deviation": dev,
            "u_at_max_deviation": u_dev,
        }
        if is_arc
        else {
            "type": "line",
            "start": start,
            "end": end,
            "length": length,
            "u_start": u0,
            "u_end": u1,
            "max_deviation": dev,
            "u_at_max_deviation": u_dev,
        }
        for is_arc, start, end, center, radius, angle, sweep, length, u0, u1, dev, u_dev in rows
    ]
    s = spline.stats
    stats = {
        "arc_count": s.arc_count,
        "line_count": s.line_count,
        "segment_count": s.segment_count,
        "max_deviation": s.max_deviation,
        "u_at_max_deviation": s.u_at_max_deviation,
        "deviation_ratio": s.deviation_ratio,
        "mean_segment_deviation": s.mean_segment_deviation,
        "spiral_length": s.spiral_length,
        "spline_length": s.spline_length,
        "min_radius": s.min_radius,
        "max_radius": s.max_radius,
        "tolerance": spline.tolerance,
        "strategy": spline.strategy,
    }
    body = orjson.dumps({"segments": segments, "stats": stats, "gcode": gcode})
    return Encoded(body=body, arc_count=s.arc_count, line_count=s.line_count)


def _finite(spline: ArcSpline) -> ArcSpline | GeometryError:
    """``spline``, or an error if any number of it is not finite.

    The core vouches for its results; this guard keeps NaN and Infinity (which JSON cannot
    carry) out of every response even so, should a degenerate input slip through.
    """
    c, s = spline.columns, spline.stats
    arcs = c.is_arc
    columns = (c.start, c.end, c.length, c.u_start, c.u_end, c.max_deviation, c.u_at_max_deviation)
    stats = (s.max_deviation, s.deviation_ratio, s.mean_segment_deviation, s.spiral_length)
    finite = (
        all(bool(np.isfinite(column).all()) for column in columns)
        and bool(np.isfinite(c.center[arcs]).all() and np.isfinite(c.radius[arcs]).all())
        and bool(np.isfinite(c.start_angle_rad).all() and np.isfinite(c.sweep_rad).all())
        and all(math.isfinite(value) for value in (*stats, s.spline_length))
    )
    if finite:
        return spline
    return GeometryError(
        "spiral",
        "cannot be approximated in double precision (its size is negligible next to its "
        "coordinates, or the tolerance is out of scale)",
        kind="precision",
    )


def _finish(job: Job, spiral: Spiral, spline: ArcSpline) -> JobResult:
    """Add the G-code program if asked for, and encode."""
    checked = _finite(spline)
    if isinstance(checked, GeometryError):
        return checked
    if job.gcode is None:
        return encode(spline, None)
    try:
        program = write_program(spline, spiral, job.gcode)
    except GcodeError as error:
        return error
    return encode(spline, program)


def approximate_one(job: Job, limits: Limits) -> JobResult:
    """One job: the encoded response, or the error that names the offending field."""
    try:
        spiral = build_spiral(job.spiral)
        spline = approximate(spiral, job.tolerance, job.strategy, limits)
    except GeometryError as error:
        return error
    return _finish(job, spiral, spline)


def approximate_chunk(jobs: Sequence[Job], limits: Limits) -> list[JobResult]:
    """Many jobs in one task, in order: one ``approximate_many`` call per strategy."""
    results: list[JobResult | None] = [None] * len(jobs)
    spirals: dict[int, Spiral] = {}
    by_strategy: dict[Strategy, list[int]] = {}
    for i, job in enumerate(jobs):
        try:
            spirals[i] = build_spiral(job.spiral)
        except GeometryError as error:
            results[i] = error
            continue
        by_strategy.setdefault(job.strategy, []).append(i)
    for strategy, indices in by_strategy.items():
        splines = approximate_many(
            [spirals[i] for i in indices], [jobs[i].tolerance for i in indices], strategy, limits
        )
        for i, spline in zip(indices, splines, strict=True):
            if isinstance(spline, GeometryError):
                results[i] = spline
            else:
                results[i] = _finish(jobs[i], spirals[i], spline)
    done = [r for r in results if r is not None]
    assert len(done) == len(jobs), "every job has a result"
    return done


def preview_spline(job: Job, limits: Limits) -> tuple[Spiral, ArcSpline] | GeometryError:
    """The spiral and its arc spline, for drawing (no G-code, no JSON)."""
    try:
        spiral = build_spiral(job.spiral)
        spline = _finite(approximate(spiral, job.tolerance, job.strategy, limits))
    except GeometryError as error:
        return error
    return spline if isinstance(spline, GeometryError) else (spiral, spline)


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
        loop = asyncio.get_running_loop()
        for _attempt in range(2):
            try:
                async with asyncio.timeout_at(deadline):
                    await self._slots.acquire()
            except TimeoutError:
                raise JobTimeoutError(time_limit_s) from None
            try:
                async with self._lock:  # held while rebuilding: wait for the new workers
                    executor, generation = self._executor, self._generation
                if executor is None:
                    raise PoolUnavailableError("the worker pool has stopped")
                try:
                    future = executor.submit(fn, *args)
                except BrokenProcessPool:
                    await self._rebuild(generation)
                    continue
                self.running += 1
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
                    self.running -= 1
                    self._waiting.pop(waiting, None)
                    self._lost.discard(waiting)
            finally:
                self._slots.release()
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
            context.set_forkserver_preload([__name__])
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
