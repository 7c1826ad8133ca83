"""Over real HTTP: a client that disconnects cancels its work, and a single request does not
queue behind batches (docs/http-api.md, "Cancellation, drain and fairness")."""

from __future__ import annotations

import asyncio
from pathlib import Path

import httpx
import pytest

from tests.integration.workloads import CLIENT_TIMEOUT_S, HEAVY, ROOM, SPIRAL, until
from tests.support.server import Server, parse_metrics, running_server

pytestmark = [
    pytest.mark.integration,
    pytest.mark.xdist_group("integration"),
    pytest.mark.anyio,
]

#: A single job that goes to a worker (its G-code is written there).
SINGLE = {"spiral": SPIRAL, "tolerance": 1e-3, "gcode": {"feed_rate": 1000}}


def _client(server: Server) -> httpx.AsyncClient:
    return httpx.AsyncClient(base_url=server.url, timeout=CLIENT_TIMEOUT_S)


async def _metrics(client: httpx.AsyncClient) -> dict[str, float]:
    return parse_metrics((await client.get("/metrics")).text)


async def test_a_client_that_disconnects_cancels_its_batch(tmp_path: Path) -> None:
    # One worker, and a batch that would keep it busy for seconds (one chunk of 200 jobs).
    with running_server(tmp_path, pool_size=1, **ROOM) as server:
        async with _client(server) as observer:
            before = await _metrics(observer)

            async def running() -> bool:
                return (await _metrics(observer))["arcspline_pool_running"] >= 1

            async with _client(server) as leaving:
                batch = asyncio.create_task(
                    leaving.post("/v1/approximate/batch", json={"jobs": [HEAVY] * 200})
                )
                await until(running)
                batch.cancel()  # and the client closes its connection
            with pytest.raises(asyncio.CancelledError):
                await batch

            async def freed() -> bool:
                m = await _metrics(observer)
                restarts = m["arcspline_pool_worker_restarts_total"]
                return (
                    m["arcspline_pool_running"] == 0
                    and restarts > before["arcspline_pool_worker_restarts_total"]
                )

            # The worker computing the chunk no one awaits is killed (and replaced); left
            # alone it would finish the chunk and never be replaced.
            await until(freed)
            after = await observer.post("/v1/approximate", json=SINGLE)
            assert after.status_code == 200
            metrics = await _metrics(observer)
            route = "method=POST,route=/v1/approximate/batch,status=499"
            assert metrics[f"arcspline_http_requests_total{{{route}}}"] == 1
            assert metrics["arcspline_pool_in_flight"] == 0
    assert "Traceback" not in server.log_text()


async def test_a_single_request_goes_before_a_batch_queued_ahead_of_it(tmp_path: Path) -> None:
    # One worker; two batches of one chunk each (60 jobs, about 2 s of work): one running,
    # the other queued when the single request comes.
    jobs = 60
    with running_server(tmp_path, pool_size=1, **ROOM) as server:
        async with _client(server) as client:
            batches = [
                asyncio.create_task(
                    client.post("/v1/approximate/batch", json={"jobs": [HEAVY] * jobs})
                )
                for _ in range(2)
            ]

            async def one_queued() -> bool:
                m = await _metrics(client)
                return m["arcspline_pool_running"] == 1 and m["arcspline_pool_queue_depth"] >= 1

            await until(one_queued)
            single = await client.post("/v1/approximate", json=SINGLE)
            after_single = await _metrics(client)
            responses = await asyncio.gather(*batches)
        assert single.status_code == 200
        assert [r.status_code for r in responses] == [200, 200]
        # The single took the worker when the running chunk ended, before the queued one:
        # that chunk was still in the pool (running now) when the single was answered.
        # Queued behind it, the single would have run only once both chunks were done.
        assert after_single["arcspline_pool_in_flight"] == 1
