"""The work budget of a batch (docs/http-api.md, "Batches"): a JSON batch whose jobs together
need more output segments than ``batch_max_segments`` is refused with ``work_too_large``;
one that needs exactly the budget is answered; a chunk never computes past its budget."""

from __future__ import annotations

from typing import Any

import httpx
import pytest

from arcspline.api.schemas import ApproximateRequest
from arcspline.api.translate import to_job
from arcspline.geometry import DEFAULT_LIMITS, GeometryError, Limits
from arcspline.worker.jobs import Job, JobResult, approximate_chunk, segments_of, within_budget

from .conftest import problem_of, running_app

pytestmark = pytest.mark.anyio

SPIRAL: dict[str, Any] = {
    "start": [1.5, 3.0],
    "start_tangent": [1.0, 0.0],
    "turn_angle_deg": 51.34,
    "end_curvature": 0.41574,
}
#: The paper's spiral at tolerances from coarse to fine: 4 to about a thousand arcs.
TOLERANCES = (0.1, 1e-3, 1e-6, 1e-9, 1e-4, 1e-8, 0.01, 1e-7)
PATH = "M 0 0 C 1 2 3 2 4 0 L 6 0 Q 7 1 8 0"


def _jobs() -> list[Any]:
    return [{"spiral": SPIRAL, "tolerance": t} for t in TOLERANCES]


async def _segments_needed(client: httpx.AsyncClient, url: str, jobs: list[Any]) -> int:
    """The output segments of ``jobs`` asked for one at a time (no batch, no budget)."""
    total = 0
    for job in jobs:
        response = await client.post(url, json=job)
        assert response.status_code == 200, response.text[:300]
        total += response.json()["stats"]["segment_count"]
    return total


async def test_a_batch_within_its_budget_is_answered_and_one_segment_over_is_refused() -> None:
    jobs = _jobs()
    async with running_app() as (_, client):
        needed = await _segments_needed(client, "/v1/approximate", jobs)
    async with running_app(batch_max_segments=needed) as (_, client):
        response = await client.post("/v1/approximate/batch", json={"jobs": jobs})
        assert response.status_code == 200, response.text[:300]
        counts = [r["result"]["stats"]["segment_count"] for r in response.json()["results"]]
        assert sum(counts) == needed
    async with running_app(batch_max_segments=needed - 1) as (_, client):
        response = await client.post("/v1/approximate/batch", json={"jobs": jobs})
    body = problem_of(response, 413)
    assert body["type"] == "urn:arcspline:problem:work-too-large"
    assert body["limit"] == needed - 1
    assert f"budget of {needed - 1} output segments" in body["detail"]
    assert "raise the tolerance" in body["detail"]
    assert "jobs per batch" in body["detail"]


async def test_the_hostile_batch_is_refused_and_says_how_to_split_it() -> None:
    """1,000 × the paper's spiral at its tolerance floor: 1,278 arcs each, 558 MB of JSON."""
    floor = 5.6525013e-10 * 1.001  # the floor the service states for this spiral, and a bit
    jobs = [{"spiral": SPIRAL, "tolerance": floor}] * 1000
    async with running_app(batch_max_segments=20_000) as (_, client):
        response = await client.post("/v1/approximate/batch", json={"jobs": jobs})
    body = problem_of(response, 413)
    assert body["type"] == "urn:arcspline:problem:work-too-large"
    assert "about 1278 each" in body["detail"]
    assert "send at most 15 such jobs per batch" in body["detail"]


async def test_errors_take_no_budget_and_stay_in_place() -> None:
    jobs = [*_jobs()[:2], "not a job", {"spiral": SPIRAL, "tolerance": 1e-14}]
    async with running_app() as (_, client):
        needed = await _segments_needed(client, "/v1/approximate", jobs[:2])
    async with running_app(batch_max_segments=needed) as (_, client):
        response = await client.post("/v1/approximate/batch", json={"jobs": jobs})
    assert response.status_code == 200, response.text[:300]
    statuses = [r["status"] for r in response.json()["results"]]
    assert statuses == ["ok", "ok", "error", "error"]


async def test_a_path_batch_shares_the_budget_too() -> None:
    jobs = [{"path": PATH, "tolerance": t} for t in (1e-3, 1e-6, 1e-8)]
    async with running_app() as (_, client):
        needed = await _segments_needed(client, "/v1/paths/approximate", jobs)
    async with running_app(batch_max_segments=needed) as (_, client):
        assert (await client.post("/v1/paths/batch", json={"jobs": jobs})).status_code == 200
    async with running_app(batch_max_segments=needed - 1) as (_, client):
        response = await client.post("/v1/paths/batch", json={"jobs": jobs})
    assert problem_of(response, 413)["type"] == "urn:arcspline:problem:work-too-large"


def _counting_run(calls: list[tuple[int, int]]) -> Any:
    """``approximate_chunk`` that notes each call's (jobs, segment cap): the most it may
    compute at once is their product."""

    def run(jobs: list[Job], limits: Limits) -> list[JobResult]:
        calls.append((len(jobs), limits.max_segments))
        return approximate_chunk(jobs, limits)

    return run


@pytest.mark.parametrize("budget", [500, 1300, 2000, 5000])
def test_a_chunk_never_computes_more_than_its_budget_at_once(budget: int) -> None:
    # Small jobs, then a big one that the small ones' answers would crowd out, and more.
    tolerances = [1e-3] * 20 + [5.66e-10] + [1e-3] * 5 + [1e-9]
    jobs = [
        to_job(ApproximateRequest.model_validate({"spiral": SPIRAL, "tolerance": t}), ["body"])
        for t in tolerances
    ]
    alone = [segments_of(r) for r in approximate_chunk(jobs, DEFAULT_LIMITS)]
    calls: list[tuple[int, int]] = []
    outcome = within_budget(_counting_run(calls), jobs, DEFAULT_LIMITS, budget)
    assert all(count * cap <= budget for count, cap in calls), calls
    # The answers are a prefix, each as the job gets alone, and it stops only where the
    # next job would pass the budget.
    kept = [segments_of(r) for r in outcome.results]
    assert kept == alone[: len(kept)]
    assert outcome.segments == sum(kept) <= budget
    assert outcome.complete == (sum(alone) <= budget)
    if not outcome.complete:
        assert sum(alone[: len(kept) + 1]) > budget
    assert not any(isinstance(r, GeometryError) for r in outcome.results)
