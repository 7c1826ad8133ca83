"""The worker pool: admission, queueing, time limits, rebuilds, retries, draining, coalescing."""

from __future__ import annotations

import asyncio
import contextlib
import os
import signal
import time
from collections.abc import AsyncIterator
from typing import Any

import pytest

from arcspline.geometry import DEFAULT_LIMITS, SpiralFromParameters
from arcspline.worker.jobs import Encoded, Job, approximate_chunk, approximate_one
from arcspline.worker.pool import (
    Coalescer,
    JobTimeoutError,
    PoolUnavailableError,
    QueueFullError,
    WorkerPool,
    chunk_sizes,
)

PAPER = SpiralFromParameters(
    start=(1.5, 3.0), start_tangent=(1.0, 0.0), turn_angle_deg=51.34, end_curvature=0.41574
)


@pytest.mark.parametrize(
    ("jobs", "workers", "min_jobs", "sizes"),
    [
        (0, 4, 10, []),
        (5, 4, 10, [5]),
        (1000, 2, 32, [500, 500]),
        (101, 4, 10, [26, 25, 25, 25]),
        (40, 8, 10, [10, 10, 10, 10]),
    ],
)
def test_chunks_are_few_even_and_not_too_small(
    jobs: int, workers: int, min_jobs: int, sizes: list[int]
) -> None:
    assert chunk_sizes(jobs, workers, min_jobs) == sizes


pool_test = pytest.mark.anyio


@pytest.fixture
async def pool() -> AsyncIterator[WorkerPool]:
    pool = WorkerPool(2, 4, retry_after_s=3)
    await pool.start()
    try:
        yield pool
    finally:
        await pool.drain(10)


async def _eventually(condition: Any, timeout_s: float = 20.0) -> None:
    deadline = time.monotonic() + timeout_s
    while not condition():
        assert time.monotonic() < deadline, "condition not reached in time"
        await asyncio.sleep(0.05)


@pool_test
async def test_jobs_run_in_the_worker_processes(pool: WorkerPool) -> None:
    assert pool.ready
    assert len(pool.pids) == 2
    pids = await asyncio.gather(*(pool.run(os.getpid, time_limit_s=10) for _ in range(4)))
    assert set(pids) <= set(pool.pids)
    assert os.getpid() not in pids
    result = await pool.run(approximate_one, Job(PAPER, 1e-3), DEFAULT_LIMITS, time_limit_s=10)
    assert isinstance(result, Encoded)
    assert result.arc_count == 12


@pool_test
async def test_admission_beyond_capacity_is_refused_at_once(pool: WorkerPool) -> None:
    with pool.admit(4):
        assert pool.in_flight == 4
        with pytest.raises(QueueFullError) as info:
            await pool.run(os.getpid, time_limit_s=10)
        assert info.value.retry_after_s == 3
    assert pool.in_flight == 0
    await pool.run(os.getpid, time_limit_s=10)


@pool_test
async def test_waiting_tasks_are_queued_not_refused(pool: WorkerPool) -> None:
    # Four tasks on two workers: two wait their turn.
    tasks = [asyncio.create_task(pool.run(time.sleep, 0.3, time_limit_s=10)) for _ in range(4)]
    await _eventually(lambda: pool.queue_depth == 2)
    assert pool.running == 2
    await asyncio.gather(*tasks)
    assert (pool.in_flight, pool.queue_depth) == (0, 0)


@pool_test
async def test_a_task_past_its_time_limit_is_killed_and_the_pool_rebuilt(
    pool: WorkerPool,
) -> None:
    old = pool.pids
    with pytest.raises(JobTimeoutError):
        await pool.run(time.sleep, 30, time_limit_s=0.3)
    await _eventually(lambda: pool.ready)
    assert pool.restarts == 1
    # Only the stuck worker was replaced; the other one never stopped.
    assert len(set(old) - set(pool.pids)) == 1
    assert len(pool.pids) == 2
    assert await pool.run(os.getpid, time_limit_s=10) in pool.pids


@pool_test
async def test_a_killed_worker_is_replaced_and_its_task_retried() -> None:
    pool = WorkerPool(1, 4)
    await pool.start()
    try:
        task = asyncio.create_task(pool.run(time.sleep, 0.5, time_limit_s=10))
        await _eventually(lambda: pool.running == 1)
        await asyncio.sleep(0.1)
        (pid,) = pool.pids
        os.kill(pid, signal.SIGKILL)
        assert await task is None  # retried on the new worker, and finished
        assert pool.restarts == 1
        await _eventually(lambda: pool.ready)
        assert pool.pids != [pid]
    finally:
        await pool.drain(10)


@pool_test
async def test_when_every_worker_is_killed_a_task_ends_and_the_pool_recovers(
    pool: WorkerPool,
) -> None:
    task = asyncio.create_task(pool.run(time.sleep, 0.5, time_limit_s=10))
    await _eventually(lambda: pool.running == 1)
    old = pool.pids
    for pid in old:
        os.kill(pid, signal.SIGKILL)
    # Retried once: on a new worker (None), or on the other one if it was not yet seen dead.
    with contextlib.suppress(PoolUnavailableError):
        assert await task is None
    await _eventually(lambda: pool.ready and len(pool.pids) == 2)
    assert not set(pool.pids) & set(old)
    assert await pool.run(os.getpid, time_limit_s=10) in pool.pids


@pool_test
async def test_a_task_that_kills_its_worker_twice_is_refused(pool: WorkerPool) -> None:
    with pytest.raises(PoolUnavailableError):
        await pool.run(os._exit, 1, time_limit_s=10)
    assert pool.restarts == 2
    await _eventually(lambda: pool.ready)


@pool_test
async def test_an_idle_worker_that_dies_is_replaced(pool: WorkerPool) -> None:
    os.kill(pool.pids[0], signal.SIGKILL)
    await _eventually(lambda: pool.restarts == 1 and pool.ready)
    assert await pool.run(os.getpid, time_limit_s=10) in pool.pids


@pool_test
async def test_run_many_keeps_finished_results_when_another_times_out(pool: WorkerPool) -> None:
    results = await pool.run_many([(time.sleep, (30,)), (os.getpid, ())], time_limit_s=0.5)
    assert isinstance(results[0], JobTimeoutError)
    assert isinstance(results[1], int)


@pool_test
async def test_draining_finishes_in_flight_work_then_stops() -> None:
    pool = WorkerPool(1, 4)
    await pool.start()
    task = asyncio.create_task(pool.run(time.sleep, 0.5, time_limit_s=10))
    await _eventually(lambda: pool.running == 1)
    await pool.drain(10)
    assert task.done()
    assert task.result() is None
    assert pool.state == "stopped"
    assert not pool.ready
    with pytest.raises(PoolUnavailableError):
        await pool.run(os.getpid, time_limit_s=10)


@pool_test
async def test_an_idle_pool_runs_a_single_job_alone_and_at_once(pool: WorkerPool) -> None:
    coalescer = Coalescer(pool, approximate_chunk, DEFAULT_LIMITS, time_limit_s=10, max_items=8)
    result = await coalescer.run(Job(PAPER, 1e-3))
    assert isinstance(result, Encoded)
    assert result.arc_count == 12
    assert coalescer.tasks == 1


@pool_test
async def test_jobs_that_queue_up_share_worker_tasks() -> None:
    pool = WorkerPool(1, 64)
    await pool.start()
    try:
        coalescer = Coalescer(pool, approximate_chunk, DEFAULT_LIMITS, time_limit_s=10, max_items=8)
        tolerances = [10.0 ** -(1 + i % 5) for i in range(20)]
        results = await asyncio.gather(*(coalescer.run(Job(PAPER, t)) for t in tolerances))
        table = {0.1: 4, 0.01: 8, 0.001: 12, 0.0001: 26, 1e-05: 54}
        counts = [r.arc_count for r in results if isinstance(r, Encoded)]
        assert counts == [table[t] for t in tolerances]
        # All 20 queue before the one dispatcher runs: tasks of 8, 8 and 4.
        assert coalescer.tasks == 3
        assert pool.in_flight == 0
    finally:
        await pool.drain(10)


@pool_test
async def test_queued_jobs_are_shared_among_the_free_workers() -> None:
    pool = WorkerPool(2, 64)
    await pool.start()
    try:
        coalescer = Coalescer(
            pool, approximate_chunk, DEFAULT_LIMITS, time_limit_s=10, max_items=32
        )
        results = await asyncio.gather(*(coalescer.run(Job(PAPER, 1e-3)) for _ in range(20)))
        assert [r.arc_count for r in results if isinstance(r, Encoded)] == [12] * 20
        # Both workers are free when the 20 have queued: a task of 10 each, not one of 20.
        assert coalescer.tasks == 2
        assert pool.free_slots == pool.size
    finally:
        await pool.drain(10)


@pool_test
async def test_a_coalesced_task_that_fails_fails_each_of_its_jobs() -> None:
    pool = WorkerPool(1, 64)
    await pool.start()
    try:
        coalescer = Coalescer(
            pool, approximate_chunk, DEFAULT_LIMITS, time_limit_s=1e-4, max_items=8
        )
        outcomes = await asyncio.gather(
            *(coalescer.run(Job(PAPER, 1e-9)) for _ in range(5)), return_exceptions=True
        )
        assert all(isinstance(o, JobTimeoutError) for o in outcomes), outcomes
        assert pool.restarts >= 1
        single = await pool.run(approximate_one, Job(PAPER, 0.1), DEFAULT_LIMITS, time_limit_s=10)
        assert isinstance(single, Encoded)
    finally:
        await pool.drain(10)


def _sleep_each(seconds: list[float], _arg: None) -> list[float]:
    """A coalescable task (``fn(items, arg)``) that takes the time its items say."""
    for s in seconds:
        time.sleep(s)
    return seconds


@pool_test
async def test_a_waiting_single_task_takes_the_next_worker_before_waiting_batch_chunks() -> None:
    pool = WorkerPool(1, 8)
    await pool.start()
    try:
        done: list[str] = []

        def note(name: str) -> Any:
            return lambda _task: done.append(name)

        blocker = asyncio.create_task(pool.run(time.sleep, 0.3, time_limit_s=10))
        blocker.add_done_callback(note("blocker"))
        await _eventually(lambda: pool.running == 1)
        chunks = [(time.sleep, (0.2,)), (time.sleep, (0.2,))]
        batch = asyncio.create_task(pool.run_many(chunks, time_limit_s=10))
        batch.add_done_callback(note("batch"))
        await _eventually(lambda: pool.queue_depth == 2)
        single = asyncio.create_task(pool.run(os.getpid, time_limit_s=10))
        single.add_done_callback(note("single"))
        await asyncio.gather(blocker, batch, single)
        # The single arrived last, after both chunks had queued, and ran first.
        assert done == ["blocker", "single", "batch"]
        assert pool.free_slots == 1
    finally:
        await pool.drain(10)


@pool_test
async def test_a_coalesced_task_runs_on_while_one_of_its_jobs_is_still_awaited() -> None:
    pool = WorkerPool(1, 8)
    await pool.start()
    try:
        coalescer = Coalescer(pool, _sleep_each, None, time_limit_s=10, max_items=8)
        blocker = asyncio.create_task(pool.run(time.sleep, 0.2, time_limit_s=10))
        await _eventually(lambda: pool.running == 1)
        gone, kept = (asyncio.create_task(coalescer.run(0.4)) for _ in range(2))
        await _eventually(lambda: coalescer.tasks == 1)  # both in one task, now running
        gone.cancel()
        assert await kept == 0.4
        await blocker
        assert gone.cancelled()
        assert pool.restarts == 0
    finally:
        await pool.drain(10)


@pool_test
async def test_a_coalesced_task_no_job_awaits_any_more_is_stopped() -> None:
    pool = WorkerPool(1, 8)
    await pool.start()
    try:
        coalescer = Coalescer(pool, _sleep_each, None, time_limit_s=30, max_items=8)
        jobs = [asyncio.create_task(coalescer.run(5.0)) for _ in range(2)]
        await _eventually(lambda: pool.running == 2)  # one task of both jobs
        (pid,) = pool.pids
        for job in jobs:
            job.cancel()
        # Its worker killed and replaced: the work no one awaits does not run on (and the
        # task ending by itself after 10 s would leave the count at 0).
        await _eventually(lambda: pool.restarts == 1 and pool.running == 0)
        await _eventually(lambda: pool.ready)
        assert pool.pids != [pid]
        assert await coalescer.run(0.0) == 0.0  # and the coalescer goes on
        assert coalescer.tasks == 2
    finally:
        await pool.drain(10)
