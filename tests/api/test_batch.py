"""POST /v1/approximate/batch in process: order, isolation of bad jobs, limits, chunking."""

from __future__ import annotations

from typing import Any

import httpx
import pytest

from arcspline.api.schemas import BatchResponse

from .conftest import locs, problem_of, running_app, until_ready
from .spline_json import same_json

pytestmark = pytest.mark.anyio

URL = "/v1/approximate/batch"


def _job(tolerance: float = 1e-3, **spiral_changes: Any) -> dict[str, Any]:
    spiral: dict[str, Any] = {
        "start": [1.5, 3.0],
        "start_tangent": [1.0, 0.0],
        "turn_angle_deg": 51.34,
        "end_curvature": 0.41574,
    }
    spiral.update(spiral_changes)
    return {"spiral": spiral, "tolerance": tolerance}


async def test_good_and_bad_jobs_each_get_their_own_answer_in_order(
    client: httpx.AsyncClient,
) -> None:
    jobs: list[Any] = [
        _job(0.1),
        _job(0.1, turn_angle_deg=95),  # schema: θ outside (0, 90)
        _job(1e-13),  # core: below the reachable tolerance
        {**_job(0.01), "strategy": "fewest-arcs"},
        "not an object",
        {**_job(0.001), "tolerence": 1},  # typo
        _job(1e-4, end_curvature=-2.0),
        {"spiral": {"control_points": [[0, 0], [1, 0], [3, 0], [4, 1]]}, "tolerance": 0.1},
    ]
    response = await client.post(URL, json={"jobs": jobs})
    assert response.status_code == 200, response.text
    body = response.json()
    BatchResponse.model_validate(body)
    results = body["results"]
    assert [r["status"] for r in results] == [
        "ok",
        "error",
        "error",
        "ok",
        "error",
        "error",
        "ok",
        "error",
    ]
    single = [(await client.post("/v1/approximate", json=jobs[i])).json() for i in (0, 3, 6)]
    # The core's batched path may differ from the single one in the last bit (summation order).
    assert same_json([results[i]["result"] for i in (0, 3, 6)], single)
    assert results[0]["result"]["stats"]["arc_count"] == 4
    assert results[3]["result"]["stats"]["strategy"] == "fewest-arcs"
    errors = {i: results[i]["error"] for i in (1, 2, 4, 5, 7)}
    assert all(e["status"] == 422 for e in errors.values())
    assert ["body", "jobs", 1, "spiral", "turn_angle_deg"] in locs(errors[1])
    assert errors[2]["type"].endswith(":tolerance-floor")
    assert locs(errors[2]) == [["body", "jobs", 2, "tolerance"]]
    assert locs(errors[4]) == [["body", "jobs", 4]]
    assert ["body", "jobs", 5, "tolerence"] in locs(errors[5])
    assert locs(errors[7]) == [["body", "jobs", 7, "spiral", "control_points"]]


async def test_a_batch_split_over_workers_gives_the_single_answers() -> None:
    async with running_app(batch_chunk_min_jobs=3) as (_, client):
        tolerances = [10.0 ** -(1 + i % 5) for i in range(20)]
        jobs = [_job(t) for t in tolerances]
        response = await client.post(URL, json={"jobs": jobs})
        assert response.status_code == 200, response.text
        counts = [r["result"]["stats"]["arc_count"] for r in response.json()["results"]]
        # Table 1 of the paper, in the order of the jobs.
        table = {0.1: 4, 0.01: 8, 0.001: 12, 0.0001: 26, 1e-05: 54}
        assert counts == [table[t] for t in tolerances]
        metrics = (await client.get("/metrics")).text
        assert 'arcspline_jobs_total{endpoint="batch",outcome="ok"} 20.0' in metrics
        assert f'arcspline_segments_produced_total{{type="arc"}} {float(sum(counts))}' in metrics


async def test_too_many_jobs_is_a_413_naming_the_limit() -> None:
    async with running_app(batch_max_jobs=3) as (_, client):
        problem = problem_of(await client.post(URL, json={"jobs": [_job()] * 4}), 413)
        assert problem["type"].endswith(":too-many-jobs")
        assert problem["limit"] == 3
        assert (await client.post(URL, json={"jobs": [_job()] * 3})).status_code == 200


@pytest.mark.parametrize(
    ("body", "loc"),
    [
        ({"jobs": []}, ["body", "jobs"]),
        ({"jobs": {}}, ["body", "jobs"]),
        ({}, ["body", "jobs"]),
        ({"jobs": [], "job": []}, ["body", "job"]),
    ],
)
async def test_a_batch_that_is_not_a_list_of_jobs_is_refused(
    client: httpx.AsyncClient, body: dict[str, Any], loc: list[str]
) -> None:
    assert loc in locs(problem_of(await client.post(URL, json=body), 422))


async def test_a_batch_past_its_time_limit_reports_each_job() -> None:
    async with running_app(batch_time_limit_s=0.001) as (app, client):
        response = await client.post(URL, json={"jobs": [_job(1e-9)] * 50})
        assert response.status_code == 200
        results = response.json()["results"]
        assert {r["status"] for r in results} == {"error"}
        assert {r["error"]["status"] for r in results} == {504}
        await until_ready(client)
        assert app.state.runtime.pool.restarts >= 1
