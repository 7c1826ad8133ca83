"""The worker pool and its job functions."""

from __future__ import annotations

import asyncio
import json
import os
import signal
import time
from collections.abc import AsyncIterator
from typing import Any

import pytest

from service.gcode import GcodeOptions
from service.geometry import DEFAULT_LIMITS, GeometryError, Limits, Spiral, approximate
from service.worker import (
    ControlPointsSpec,
    Encoded,
    Job,
    JobTimeoutError,
    ParametersSpec,
    PoolUnavailableError,
    QueueFullError,
    WorkerPool,
    approximate_chunk,
    approximate_one,
    chunk_sizes,
    encode,
)

PAPER = ParametersSpec(
    start=(1.5, 3.0), start_tangent=(1.0, 0.0), turn_angle_deg=51.34, end_curvature=0.41574
)


def _paper_spiral() -> Spiral:
    return Spiral.from_parameters((1.5, 3.0), (1.0, 0.0), 51.34, 0.41574)


# -- job functions -----------------------------------------------------------------------


def test_encode_writes_every_field_of_every_segment() -> None:
    spline = approximate(_paper_spiral(), 1e-3)
    encoded = encode(spline, None)
    body = json.loads(encoded.body)
    c = spline.columns
    assert (encoded.arc_count, encoded.line_count) == (12, 0)
    for i, segment in enumerate(body["segments"]):
        assert segment["type"] == "arc"
        assert segment["start"] == c.start[i].tolist()
        assert segment["end"] == c.end[i].tolist()
        assert segment["center"] == c.center[i].tolist()
        assert segment["radius"] == c.radius[i]
        assert segment["sweep_rad"] == c.sweep_rad[i]
        assert segment["direction"] == ("ccw" if c.sweep_rad[i] > 0 else "cw")
        for name in (
            "start_angle_rad",
            "length",
            "u_start",
            "u_end",
            "max_deviation",
            "u_at_max_deviation",
        ):
            assert segment[name] == getattr(c, name)[i]
    stats = body["stats"]
    assert stats["segment_count"] == 12
    assert stats["tolerance"] == 1e-3
    assert stats["strategy"] == "subdivide"
    assert stats["min_radius"] == spline.stats.min_radius
    assert body["gcode"] is None


def test_lines_carry_no_centre_or_radius() -> None:
    # A turn of 1e-9° is numerically straight: the core answers with lines.
    spiral = Spiral.from_parameters((0.0, 0.0), (1.0, 0.0), 1e-9, 1.0)
    spline = approximate(spiral, spiral.chord * 1e-3)
    body = json.loads(encode(spline, None).body)
    assert body["stats"]["line_count"] == len(body["segments"]) > 0
    assert body["stats"]["min_radius"] is None
    assert body["stats"]["max_radius"] is None
    for segment in body["segments"]:
        assert set(segment) == {
            "type",
            "start",
            "end",
            "length",
            "u_start",
            "u_end",
            "max_deviation",
            "u_at_max_deviation",
        }
        assert segment["type"] == "line"


def test_approximate_one_returns_the_body_or_the_error() -> None:
    ok = approximate_one(Job(PAPER, 0.1), DEFAULT_LIMITS)
    assert isinstance(ok, Encoded)
    assert ok.arc_count == 4
    floor = approximate_one(Job(PAPER, 1e-14), DEFAULT_LIMITS)
    assert isinstance(floor, GeometryError)
    assert floor.kind == "tolerance_floor"
    capped = approximate_one(Job(PAPER, 1e-5), Limits(max_segments=10))
    assert isinstance(capped, GeometryError)
    assert capped.kind == "segment_limit"
    assert capped.limit == 10
    bad = approximate_one(
        Job(ControlPointsSpec(((0, 0), (1, 0), (3, 0), (4, 1))), 0.1), DEFAULT_LIMITS
    )
    assert isinstance(bad, GeometryError)
    assert bad.field == "control_points"


def test_approximate_one_adds_the_program_when_asked() -> None:
    result = approximate_one(Job(PAPER, 0.1, gcode=GcodeOptions(feed_rate=200.0)), DEFAULT_LIMITS)
    assert isinstance(result, Encoded)
    program = json.loads(result.body)["gcode"]
    assert isinstance(program, str)
    assert "M2" in program


def test_a_chunk_answers_each_job_in_order_like_single_jobs() -> None:
    jobs = [
        Job(PAPER, 0.1),
        Job(PAPER, 1e-14),
        Job(PAPER, 0.01, "fewest-arcs"),
        Job(ControlPointsSpec(((0, 0), (1, 0), (3, 0), (4, 1))), 0.1),
        Job(PAPER, 1e-4),
        Job(PAPER, 1e-3, "fewest-arcs"),
    ]
    results = approximate_chunk(jobs, DEFAULT_LIMITS)
    assert len(results) == len(jobs)
    for job, result in zip(jobs, results, strict=True):
        single = approximate_one(job, DEFAULT_LIMITS)
        assert type(result) is type(single)
        if isinstance(result, Encoded):
            assert isinstance(single, Encoded)
            assert (result.arc_count, result.line_count) == (single.arc_count, single.line_count)
            assert json.loads(result.body)["stats"]["strategy"] == job.strategy
        else:
            assert isinstance(single, GeometryError)
            assert (result.field, result.kind) == (single.field, single.kind)


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


# -- the pool ----------------------------------------------------------------------------

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
    assert pool.rebuilds == 1
    assert pool.ready
    assert not set(pool.pids) & set(old)
    assert await pool.run(os.getpid, time_limit_s=10) in pool.pids


@pool_test
async def test_a_killed_worker_is_replaced_and_its_task_retried(pool: WorkerPool) -> None:
    task = asyncio.create_task(pool.run(time.sleep, 0.5, time_limit_s=10))
    await _eventually(lambda: pool.running == 1)
    await asyncio.sleep(0.1)
    for pid in pool.pids:
        os.kill(pid, signal.SIGKILL)
    assert await task is None  # retried on the new workers, and finished
    assert pool.rebuilds == 1
    assert pool.ready


@pool_test
async def test_a_task_whose_workers_are_replaced_is_retried(pool: WorkerPool) -> None:
    # A rebuild asked for by another task (here directly) abandons what the old workers owe,
    # even if their executor never reports it: CPython can lose a future submitted in the
    # instant the executor broke, and such a task must not wait forever.
    task = asyncio.create_task(pool.run(time.sleep, 0.3, time_limit_s=30))
    await _eventually(lambda: pool.running == 1)
    await pool._rebuild(pool._generation)
    assert await task is None
    assert pool.rebuilds == 1


@pool_test
async def test_a_task_that_kills_its_worker_twice_is_refused(pool: WorkerPool) -> None:
    with pytest.raises(PoolUnavailableError):
        await pool.run(os._exit, 1, time_limit_s=10)
    assert pool.rebuilds == 2
    await _eventually(lambda: pool.ready)


@pool_test
async def test_an_idle_worker_that_dies_is_replaced(pool: WorkerPool) -> None:
    os.kill(pool.pids[0], signal.SIGKILL)
    await _eventually(lambda: pool.rebuilds == 1 and pool.ready)
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
