"""Over real HTTP: SIGTERM while a request outlives the drain (docs/http-api.md,
"Cancellation, drain and fairness"; docs/deployment.md)."""

from __future__ import annotations

import asyncio
import signal
from pathlib import Path

import httpx
import pytest

from tests.integration.workloads import CLIENT_TIMEOUT_S, HEAVY, ROOM, until
from tests.support.server import parse_metrics, running_server

pytestmark = [
    pytest.mark.integration,
    pytest.mark.xdist_group("integration"),
    pytest.mark.anyio,
]


async def test_a_request_still_running_when_the_drain_ends_is_answered_503(
    tmp_path: Path,
) -> None:
    # A batch of seconds on one worker, and a drain of one second.
    settings = {"pool_size": 1, "drain_timeout_s": 1, "retry_after_s": 3, **ROOM}
    with running_server(tmp_path, **settings) as server:
        async with httpx.AsyncClient(base_url=server.url, timeout=CLIENT_TIMEOUT_S) as client:
            batch = asyncio.create_task(
                client.post("/v1/approximate/batch", json={"jobs": [HEAVY] * 200})
            )

            async def running() -> bool:
                metrics = parse_metrics((await client.get("/metrics")).text)
                return metrics["arcspline_pool_running"] >= 1

            await until(running)
            server.process.send_signal(signal.SIGTERM)
            response = await batch
        assert response.status_code == 503
        assert response.headers["content-type"] == "application/problem+json"
        assert response.headers["retry-after"] == "3"
        problem = response.json()
        assert problem["type"] == "urn:arcspline:problem:shutting-down"
        assert problem["status"] == 503
        assert problem["request_id"] == response.headers["x-request-id"]
        assert server.process.wait(timeout=60) == 0
        assert server.worker_pids() == []
    log = server.log_text()
    assert "Traceback" not in log
    assert "CancelledError" not in log
    assert " ERROR " not in log  # uvicorn's own cut ("Cancel 1 running task(s)") not reached
    assert "the drain ended with 1 request(s) still running: answered 503" in log
