"""Over real HTTP: SIGTERM while a request outlives the drain (docs/http-api.md,
"Cancellation, drain and fairness"; docs/deployment.md)."""

from __future__ import annotations

import asyncio
import signal
import time
from collections.abc import Awaitable, Callable
from pathlib import Path

import httpx
import pytest

from arcspline.settings import Settings
from tests.support.server import parse_metrics, running_server

pytestmark = [
    pytest.mark.integration,
    pytest.mark.xdist_group("integration"),
    pytest.mark.anyio,
]

SPIRAL = {
    "start": [1.5, 3.0],
    "start_tangent": [1.0, 0.0],
    "turn_angle_deg": 51.34,
    "end_curvature": 0.41574,
}
#: About 30 ms of a worker's time (a thousand arcs and their G-code).
HEAVY = {"spiral": SPIRAL, "tolerance": 1e-9, "gcode": {"feed_rate": 1000, "decimals": 6}}
#: Room for batches of seconds of work: the batch work budget (ARCSPLINE_BATCH_MAX_SEGMENTS)
#: would stop them at a fraction of that.
ROOM = {"batch_max_segments": 10**7} if "batch_max_segments" in Settings.model_fields else {}
#: Hang guard for every request and wait: far beyond any answer's time.
CLIENT_TIMEOUT_S = 120.0


async def _until(condition: Callable[[], Awaitable[bool]], timeout_s: float = 60.0) -> None:
    deadline = time.monotonic() + timeout_s
    while not await condition():
        assert time.monotonic() < deadline, "condition not reached in time"
        await asyncio.sleep(0.01)


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

            await _until(running)
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
