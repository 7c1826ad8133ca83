"""Small single jobs computed in the serving process (api/fast_path.py): the same answers,
byte for byte, as through the worker pool; larger or costlier jobs, and small ones once
inline jobs have had their share of the process's time, still go to the pool;
``inline_max_segments=0`` sends every job there."""

from __future__ import annotations

import math
from collections.abc import AsyncIterator
from typing import Any

import httpx
import pytest
from fastapi import FastAPI

from arcspline.api.fast_path import Allowance, inline_limits, run_inline
from arcspline.api.schemas import ApproximateRequest
from arcspline.api.translate import to_job
from arcspline.geometry import GeometryError
from arcspline.settings import Settings
from arcspline.worker.jobs import Job, approximate_one
from arcspline.worker.pool import WorkerPool

from .conftest import TEST_SETTINGS, running_app

pytestmark = pytest.mark.anyio

#: Small for the tests: the paper's spiral needs 12 segments at 1e-3, 54 at 1e-5 (inline)
#: and 114 at 1e-6 (over it: the pool).
INLINE_MAX_SEGMENTS = 64
#: The configured limit: the paper's spiral at 1e-8 (some 500 segments) is refused.
MAX_SEGMENTS = 200
PAPER = {
    "start": [1.5, 3.0],
    "start_tangent": [1.0, 0.0],
    "turn_angle_deg": 51.34,
    "end_curvature": 0.41574,
}
CONTROL_POINTS = {"control_points": [[0.0, 0.0], [1.0, 0.0], [2.0, 0.0], [3.0, 1.0]]}
#: A fixed request id: problem details carry it.
HEADERS = {"X-Request-ID": "fast-path-test"}


def spiral(tolerance: float, **fields: Any) -> dict[str, Any]:
    return {"spiral": PAPER, "tolerance": tolerance, **fields}


#: Requests the fast path computes itself (answers and errors).
INLINE_REQUESTS = {
    "paper-1e-3": spiral(1e-3),
    "paper-1e-4": spiral(1e-4),
    "paper-1e-5": spiral(1e-5),
    "paper-0.5": spiral(0.5),
    "paper-1e-3-explicit-subdivide": spiral(1e-3, strategy="subdivide"),
    "clockwise": {"spiral": {**PAPER, "end_curvature": -0.41574}, "tolerance": 1e-4},
    "large-coordinates": {
        "spiral": {**PAPER, "start": [1e5, -3e5], "start_tangent": [-0.3, 2.0]},
        "tolerance": 1e-3,
    },
    "control-points": {"spiral": CONTROL_POINTS, "tolerance": 1e-3},
    "below-tolerance-floor": spiral(1e-15),
    "bad-control-points": {
        "spiral": {"control_points": [[0, 0], [1, 0], [1, 0], [0, 0]]},
        "tolerance": 1e-3,
    },
}
#: Requests whose cost the segment count does not bound, or over the inline count: the pool.
POOL_REQUESTS = {
    "paper-1e-6-over-inline-count": spiral(1e-6),
    "over-max-segments": spiral(1e-8),
    "gcode": spiral(1e-3, gcode={"feed_rate": 600}),
    "gcode-passes": spiral(
        1e-4, gcode={"feed_rate": 600, "safe_z": 5.0, "cut_z": -1.0, "step_down": 0.25}
    ),
    "fewest-arcs": spiral(1e-3, strategy="fewest-arcs"),
}


def unlimited(app: FastAPI) -> None:
    """No share of time for inline jobs to exhaust: which path a job takes here depends on
    the job alone, not on how fast this machine runs the tests."""
    app.state.runtime.inline_allowance = Allowance(share=1.0, burst_s=math.inf)


@pytest.fixture(scope="module")
async def apps() -> AsyncIterator[dict[str, tuple[FastAPI, httpx.AsyncClient]]]:
    """The same settings with the fast path on and off."""
    limits = {"max_segments": MAX_SEGMENTS}
    async with (
        running_app(inline_max_segments=INLINE_MAX_SEGMENTS, **limits) as inline,
        running_app(inline_max_segments=0, **limits) as pooled,
    ):
        unlimited(inline[0])
        yield {"inline": inline, "pooled": pooled}


def pool_tasks(app: FastAPI) -> int:
    """Tasks the single-job coalescer has sent to the workers so far."""
    tasks: int = app.state.runtime.coalescer.tasks
    return tasks


async def answer(pair: tuple[FastAPI, httpx.AsyncClient], body: dict[str, Any]) -> Any:
    """The response's status, media type and bytes, and how many pool tasks it took."""
    app, client = pair
    before = pool_tasks(app)
    response = await client.post("/v1/approximate", json=body, headers=HEADERS)
    media_type = response.headers["content-type"]
    return (response.status_code, media_type, response.content), pool_tasks(app) - before


@pytest.mark.parametrize("name", sorted(INLINE_REQUESTS))
async def test_inline_answer_is_the_pools_byte_for_byte(
    apps: dict[str, tuple[FastAPI, httpx.AsyncClient]], name: str
) -> None:
    inline, inline_tasks = await answer(apps["inline"], INLINE_REQUESTS[name])
    pooled, pooled_tasks = await answer(apps["pooled"], INLINE_REQUESTS[name])
    assert inline == pooled
    assert (inline_tasks, pooled_tasks) == (0, 1)


@pytest.mark.parametrize("name", sorted(POOL_REQUESTS))
async def test_costlier_jobs_go_to_the_pool(
    apps: dict[str, tuple[FastAPI, httpx.AsyncClient]], name: str
) -> None:
    inline, inline_tasks = await answer(apps["inline"], POOL_REQUESTS[name])
    pooled, pooled_tasks = await answer(apps["pooled"], POOL_REQUESTS[name])
    assert inline == pooled
    assert (inline_tasks, pooled_tasks) == (1, 1)


async def test_the_cases_cover_answers_and_errors(
    apps: dict[str, tuple[FastAPI, httpx.AsyncClient]],
) -> None:
    """The comparisons above are not all of one kind: answers, refusals of the core at the
    floor and at the segment limit (inline), and the pool's own answers and refusals."""
    statuses = {}
    for name, body in {**INLINE_REQUESTS, **POOL_REQUESTS}.items():
        (status, media_type, _content), _ = await answer(apps["inline"], body)
        statuses[name] = status
        if status == 422:
            assert media_type == "application/problem+json"
    assert statuses["paper-1e-3"] == statuses["paper-1e-6-over-inline-count"] == 200
    assert statuses["below-tolerance-floor"] == statuses["bad-control-points"] == 422
    assert statuses["over-max-segments"] == 422


async def counters(pair: tuple[FastAPI, httpx.AsyncClient]) -> dict[str, float]:
    """The job and segment counters of ``/metrics``, by series."""
    text = (await pair[1].get("/metrics")).text
    series = (line.rsplit(" ", 1) for line in text.splitlines())
    return {
        name: float(value)
        for name, value in series
        if name.startswith(("arcspline_jobs_total", "arcspline_segments_produced_total"))
    }


async def test_inline_jobs_count_in_the_metrics_as_pool_jobs_do(
    apps: dict[str, tuple[FastAPI, httpx.AsyncClient]],
) -> None:
    moved = {}
    for name, pair in apps.items():
        before = await counters(pair)
        for body in (spiral(1e-3), spiral(1e-5), spiral(1e-15), spiral(1e-6)):
            await answer(pair, body)
        after = await counters(pair)
        moved[name] = {k: v - before.get(k, 0.0) for k, v in after.items() if v != before.get(k)}
    assert moved["inline"] == moved["pooled"]
    assert moved["inline"] == {
        'arcspline_jobs_total{endpoint="approximate",outcome="ok"}': 3.0,
        'arcspline_jobs_total{endpoint="approximate",outcome="error"}': 1.0,
        'arcspline_segments_produced_total{type="arc"}': 12.0 + 54.0 + 114.0,
    }


def job_of(body: dict[str, Any]) -> Job:
    return to_job(ApproximateRequest.model_validate(body), ["body"])


def ready_pool() -> WorkerPool:
    """A pool that admits (no workers: the fast path never sends it anything)."""
    pool = WorkerPool(1, 4, start_method="spawn")
    pool.state = "ready"
    return pool


#: No share of time to exhaust.
UNLIMITED = Allowance(share=1.0, burst_s=math.inf)


def test_a_job_over_the_inline_count_is_handed_back_uncomputed() -> None:
    """The core stops at the inline count; a job that needs more is the pool's, with the
    configured limit (under which it fits)."""
    settings = Settings(**TEST_SETTINGS, inline_max_segments=INLINE_MAX_SEGMENTS)
    pool = ready_pool()
    assert run_inline(job_of(spiral(1e-6)), settings, pool, UNLIMITED) is None
    small = run_inline(job_of(spiral(1e-3)), settings, pool, UNLIMITED)
    assert small == approximate_one(job_of(spiral(1e-3)), settings.limits)
    assert pool.in_flight == 0


def test_a_job_over_the_configured_limit_is_refused_inline_as_in_the_pool() -> None:
    """With the configured limit under the inline count, the core's refusal at it is the
    final answer, worded with the configured limit as the pool's."""
    settings = Settings(**TEST_SETTINGS, inline_max_segments=INLINE_MAX_SEGMENTS, max_segments=40)
    job = job_of(spiral(1e-5))
    refused = run_inline(job, settings, ready_pool(), UNLIMITED)
    expected = approximate_one(job, settings.limits)
    assert isinstance(refused, GeometryError)
    assert isinstance(expected, GeometryError)
    assert refused.kind == "segment_limit"
    assert (refused.message, refused.limit) == (expected.message, expected.limit)


def test_inline_jobs_take_at_most_their_share_of_time() -> None:
    """Under load a job that shares a worker task with others costs the serving process less
    than computing it there: inline jobs get a share of its time, then go to the pool."""
    allowance = Allowance(share=0.1, burst_s=0.005, now=100.0)
    assert allowance.open(100.0)
    allowance.take(0.004)
    assert allowance.open(100.0)  # 1 ms left
    allowance.take(0.002)
    assert not allowance.open(100.0)  # overdrawn by 1 ms: the pool's turn
    assert not allowance.open(100.005)  # 0.5 ms of the 1 ms refilled
    assert allowance.open(100.0101)  # refilled past the overdraft
    assert allowance.open(200.0)
    assert allowance.left_s == 0.005  # never more than the burst


def test_an_exhausted_share_sends_small_jobs_to_the_pool() -> None:
    settings = Settings(**TEST_SETTINGS, inline_max_segments=INLINE_MAX_SEGMENTS)
    exhausted = Allowance(share=0.0, burst_s=0.0)
    assert run_inline(job_of(spiral(1e-3)), settings, ready_pool(), exhausted) is None


def test_inline_limits() -> None:
    on = Settings(**TEST_SETTINGS, inline_max_segments=INLINE_MAX_SEGMENTS)
    limits = inline_limits(on)
    assert limits is not None
    assert limits.max_segments == INLINE_MAX_SEGMENTS
    assert limits.min_relative_tolerance == on.min_relative_tolerance
    # Never above the configured limit.
    low = Settings(**TEST_SETTINGS, inline_max_segments=500, max_segments=40)
    assert inline_limits(low) is not None
    assert inline_limits(low).max_segments == 40  # type: ignore[union-attr]
    assert inline_limits(Settings(**TEST_SETTINGS, inline_max_segments=0)) is None
    # An inline job cannot be stopped: none under a time limit this short.
    assert inline_limits(Settings(**TEST_SETTINGS, job_time_limit_s=0.01)) is None


async def test_a_full_queue_refuses_inline_jobs_as_pool_jobs(
    apps: dict[str, tuple[FastAPI, httpx.AsyncClient]],
) -> None:
    """Admission is the pool's: with the queue full, the same 503 whichever path."""
    answers = {}
    for name, pair in apps.items():
        pool = pair[0].state.runtime.pool
        pool.in_flight += pool.capacity
        try:
            answers[name], _ = await answer(pair, spiral(1e-3))
        finally:
            pool.in_flight -= pool.capacity
    assert answers["inline"][0] == 503
    assert answers["inline"] == answers["pooled"]
