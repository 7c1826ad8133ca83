"""In-process API fixtures: the app with its lifespan (a real process pool), over httpx's
ASGI transport."""

from __future__ import annotations

import time
from collections.abc import AsyncIterator, Callable
from contextlib import AbstractAsyncContextManager, asynccontextmanager
from typing import Any

import anyio
import httpx
import pytest
from asgi_lifespan import LifespanManager
from fastapi import FastAPI

from arcspline.api.app import create_app
from arcspline.settings import Settings

#: Small pools: the suite runs two test processes on two cores.
TEST_SETTINGS: dict[str, Any] = {"pool_size": 2, "queue_capacity": 16}

Client = Callable[..., AbstractAsyncContextManager[tuple[FastAPI, httpx.AsyncClient]]]


@asynccontextmanager
async def running_app(**overrides: Any) -> AsyncIterator[tuple[FastAPI, httpx.AsyncClient]]:
    """An app started (lifespan included) with ``overrides`` of the settings, and a client."""
    app = create_app(Settings(**{**TEST_SETTINGS, **overrides}))
    async with (
        LifespanManager(app, startup_timeout=60, shutdown_timeout=60) as manager,
        httpx.AsyncClient(
            transport=httpx.ASGITransport(app=manager.app), base_url="http://testserver"
        ) as client,
    ):
        yield app, client


@pytest.fixture(scope="module")
async def app_client() -> AsyncIterator[tuple[FastAPI, httpx.AsyncClient]]:
    """One started app per test module, with the test settings."""
    async with running_app() as pair:
        yield pair


@pytest.fixture
def client(app_client: tuple[FastAPI, httpx.AsyncClient]) -> httpx.AsyncClient:
    return app_client[1]


@pytest.fixture
def app(app_client: tuple[FastAPI, httpx.AsyncClient]) -> FastAPI:
    return app_client[0]


def problem_of(response: httpx.Response, status: int) -> dict[str, Any]:
    """The problem details of ``response``, after checking its status and media type."""
    assert response.status_code == status, response.text
    assert response.headers["content-type"] == "application/problem+json"
    body: dict[str, Any] = response.json()
    assert body["status"] == status
    assert body["title"]
    assert body["detail"]
    assert body["type"]
    return body


async def until_ready(client: httpx.AsyncClient, timeout_s: float = 30.0) -> None:
    """Poll /readyz until the pool is ready again (a replaced worker starts in the background)."""
    deadline = time.monotonic() + timeout_s
    while (await client.get("/readyz")).status_code != 200:
        assert time.monotonic() < deadline, "the pool did not become ready"
        await anyio.sleep(0.02)


def locs(problem: dict[str, Any]) -> list[list[str | int]]:
    return [error["loc"] for error in problem.get("errors", [])]
