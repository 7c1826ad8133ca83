"""The service over real HTTP: endpoints, a batch of good and bad jobs, a worker killed
during a burst, SIGTERM during load, a full queue, a time limit."""

from __future__ import annotations

import asyncio
import os
import signal
from pathlib import Path
from typing import Any

import httpx
import pytest

from tests.integration.workloads import CLIENT_TIMEOUT_S, HEAVY, SPIRAL, until
from tests.support.server import Server, parse_metrics, running_server

pytestmark = [
    pytest.mark.integration,
    pytest.mark.xdist_group("integration"),
    pytest.mark.anyio,
]


def _client(server: Server) -> httpx.AsyncClient:
    limits = httpx.Limits(max_connections=200, max_keepalive_connections=200)
    return httpx.AsyncClient(base_url=server.url, timeout=CLIENT_TIMEOUT_S, limits=limits)


def _same_stats(a: dict[str, Any], b: dict[str, Any]) -> bool:
    """Equal statistics, to the bit: a job's result does not depend on the jobs that share
    its worker task."""
    return a == b


async def _metrics(client: httpx.AsyncClient) -> dict[str, float]:
    return parse_metrics((await client.get("/metrics")).text)


async def _ready(client: httpx.AsyncClient) -> bool:
    return (await client.get("/readyz")).status_code == 200


async def test_endpoints_answer_over_http(server: Server) -> None:
    async with _client(server) as client:
        assert (await client.get("/healthz")).json() == {"status": "ok"}
        assert (await client.get("/readyz")).json()["workers"] == 2
        body = await client.post("/v1/approximate", json={"spiral": SPIRAL, "tolerance": 1e-4})
        assert body.status_code == 200
        assert body.json()["stats"]["arc_count"] == 26  # Table 1
        preview = await client.post("/v1/preview", json={"spiral": SPIRAL, "tolerance": 1e-2})
        assert preview.headers["content-type"].startswith("image/svg+xml")
        missing = await client.get("/nowhere")
        assert missing.status_code == 404
        assert missing.headers["content-type"] == "application/problem+json"
        assert "x-request-id" in missing.headers
        assert "arcspline_pool_workers 2.0" in (await client.get("/metrics")).text


async def test_a_batch_of_good_and_bad_jobs(server: Server) -> None:
    tolerances = [0.1, 0.01, 0.001, 1e-4, 1e-5]
    jobs: list[Any] = [{"spiral": SPIRAL, "tolerance": t} for t in tolerances * 20]
    bad = {
        3: {"spiral": SPIRAL, "tolerance": -1},
        10: {"spiral": {**SPIRAL, "end_curvature": 0}, "tolerance": 0.1},
        42: {"spiral": SPIRAL, "tolerance": 1e-15},
        77: [],
    }
    for i, job in bad.items():
        jobs[i] = job
    async with _client(server) as client:
        response = await client.post("/v1/approximate/batch", json={"jobs": jobs})
    assert response.status_code == 200
    results = response.json()["results"]
    assert len(results) == 100
    table = {0.1: 4, 0.01: 8, 0.001: 12, 1e-4: 26, 1e-5: 54}
    for i, result in enumerate(results):
        if i in bad:
            assert result["status"] == "error"
            assert result["error"]["status"] == 422
            assert all(e["loc"][:3] == ["body", "jobs", i] for e in result["error"]["errors"])
        else:
            assert result["status"] == "ok"
            assert result["result"]["stats"]["arc_count"] == table[jobs[i]["tolerance"]]


async def test_killing_a_worker_during_a_burst(server: Server) -> None:
    async with _client(server) as client:
        expected = (await client.post("/v1/approximate", json=HEAVY)).json()["stats"]
        workers = server.worker_pids()
        assert len(workers) == 2
        rebuilds_before = server.metrics()["arcspline_pool_worker_restarts_total"]
        burst = [
            asyncio.create_task(client.post("/v1/approximate", json=HEAVY)) for _ in range(120)
        ]

        async def under_way() -> bool:
            return (await _metrics(client))["arcspline_pool_in_flight"] >= 8

        await until(under_way)
        os.kill(workers[0], signal.SIGKILL)
        responses = await asyncio.wait_for(asyncio.gather(*burst), CLIENT_TIMEOUT_S)
        statuses = [r.status_code for r in responses]
        assert set(statuses) <= {200, 503}, statuses
        assert statuses.count(200) > 0
        for response in responses:
            if response.status_code == 200:
                assert _same_stats(response.json()["stats"], expected)
            else:
                assert response.headers["content-type"] == "application/problem+json"
        await until(lambda: _ready(client))
        assert (await _metrics(client))["arcspline_pool_worker_restarts_total"] > rebuilds_before
        assert workers[0] not in server.worker_pids()
        after = await client.post("/v1/approximate", json=HEAVY)
        assert _same_stats(after.json()["stats"], expected)


async def test_sigterm_drains_in_flight_requests_and_exits_0(tmp_path: Path) -> None:
    with running_server(tmp_path, pool_size=1) as server:
        async with _client(server) as client:
            requests = 40
            load = [
                asyncio.create_task(client.post("/v1/approximate", json=HEAVY))
                for _ in range(requests)
            ]

            async def all_admitted() -> bool:
                m = await _metrics(client)
                done = m.get("arcspline_jobs_total{endpoint=approximate,outcome=ok}", 0.0)
                return m["arcspline_pool_in_flight"] + done == requests

            await until(all_admitted)
            in_flight = (await _metrics(client))["arcspline_pool_in_flight"]
            assert in_flight > 0, "the load ended before the signal"
            server.process.send_signal(signal.SIGTERM)
            responses = await asyncio.wait_for(asyncio.gather(*load), CLIENT_TIMEOUT_S)
        assert [r.status_code for r in responses] == [200] * requests
        assert {r.json()["stats"]["arc_count"] for r in responses} == {1044}
        assert server.process.wait(timeout=60) == 0
        assert server.worker_pids() == []


async def test_a_full_queue_answers_503_with_retry_after(tmp_path: Path) -> None:
    with running_server(tmp_path, pool_size=1, queue_capacity=1, retry_after_s=2) as server:
        async with _client(server) as client:
            responses = await asyncio.gather(
                *(client.post("/v1/approximate", json=HEAVY) for _ in range(30))
            )
    refused = [r for r in responses if r.status_code == 503]
    assert refused, "30 simultaneous requests fitted a queue of one"
    assert {r.status_code for r in responses} <= {200, 503}
    for response in refused:
        assert response.headers["retry-after"] == "2"
        assert response.json()["type"].endswith(":queue-full")


async def test_a_job_past_its_time_limit_is_a_504_and_the_pool_recovers(tmp_path: Path) -> None:
    with running_server(tmp_path, pool_size=1, job_time_limit_s=0.002) as server:
        async with _client(server) as client:
            response = await client.post("/v1/approximate", json=HEAVY)
            assert response.status_code == 504
            assert response.json()["type"].endswith(":time-limit")
            await until(lambda: _ready(client))
            metrics = await _metrics(client)
            assert metrics["arcspline_pool_worker_restarts_total"] >= 1
            assert metrics["arcspline_errors_total{kind=time_limit}"] >= 1
