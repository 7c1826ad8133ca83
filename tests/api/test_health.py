"""GET /healthz and /readyz: liveness of the process, readiness of the pool."""

from __future__ import annotations

import httpx
import pytest
from fastapi import FastAPI

from arcspline.api.app import create_app
from arcspline.settings import Settings

from .conftest import problem_of

pytestmark = pytest.mark.anyio


async def test_healthz_answers(client: httpx.AsyncClient) -> None:
    response = await client.get("/healthz")
    assert response.status_code == 200
    assert response.json() == {"status": "ok"}


async def test_readyz_reports_the_pool(app: FastAPI, client: httpx.AsyncClient) -> None:
    response = await client.get("/readyz")
    assert response.status_code == 200, response.text
    assert response.json() == {
        "status": "ready",
        "workers": 2,
        "in_flight": 0,
        "queue_capacity": app.state.runtime.settings.queue_capacity,
    }


async def test_readyz_is_a_503_while_the_pool_is_draining(
    app: FastAPI, client: httpx.AsyncClient
) -> None:
    pool = app.state.runtime.pool
    pool.state = "draining"
    try:
        problem = problem_of(await client.get("/readyz"), 503)
    finally:
        pool.state = "ready"
    assert problem["type"].endswith(":not-ready")
    assert "draining" in problem["detail"]


async def test_without_its_lifespan_the_app_is_live_but_not_ready() -> None:
    app = create_app(Settings(pool_size=1))
    transport = httpx.ASGITransport(app=app)
    async with httpx.AsyncClient(transport=transport, base_url="http://testserver") as client:
        assert (await client.get("/healthz")).status_code == 200
        problem_of(await client.get("/readyz"), 503)
        body = {"spiral": {"control_points": [[0, 0], [1, 0], [2, 0], [3, 1]]}, "tolerance": 1}
        problem = problem_of(await client.post("/v1/approximate", json=body), 503)
        assert problem["type"].endswith(":pool-unavailable")
