"""LeanRoute: bodies taken as FastAPI takes them, without FastAPI's per-request machinery."""

from __future__ import annotations

import json
from typing import Any

import httpx
import pytest
from fastapi import APIRouter, FastAPI, Request
from starlette.responses import Response

from arcspline.api.routing import LeanRoute

from .conftest import locs, problem_of

pytestmark = pytest.mark.anyio

URL = "/v1/approximate"


def _raw(body: dict[str, Any]) -> bytes:
    return json.dumps(body).encode()


@pytest.mark.parametrize(
    "content_type",
    [
        "application/json",
        "application/json; charset=utf-8",
        "Application/JSON",
        "application/x+json",
    ],
)
async def test_a_json_body_is_taken_with_any_json_media_type(
    client: httpx.AsyncClient, paper_request: dict[str, Any], content_type: str
) -> None:
    response = await client.post(
        URL, content=_raw(paper_request), headers={"content-type": content_type}
    )
    assert response.status_code == 200, response.text
    assert response.json()["stats"]["arc_count"] == 12


@pytest.mark.parametrize("content_type", ["text/plain", "application/x-www-form-urlencoded", ""])
async def test_a_body_not_declared_json_is_not_an_object(
    client: httpx.AsyncClient, paper_request: dict[str, Any], content_type: str
) -> None:
    response = await client.post(
        URL, content=_raw(paper_request), headers={"content-type": content_type}
    )
    problem = problem_of(response, 422)
    assert locs(problem) == [["body"]]
    assert "dictionary" in problem["errors"][0]["msg"]


async def test_an_empty_body_is_a_missing_one(client: httpx.AsyncClient) -> None:
    response = await client.post(URL, content=b"", headers={"content-type": "application/json"})
    problem = problem_of(response, 422)
    assert problem["errors"] == [{"loc": ["body"], "msg": "Field required", "type": "missing"}]


async def test_malformed_json_says_where(client: httpx.AsyncClient) -> None:
    response = await client.post(
        URL, content=b'{"spiral": {"start": [1.5,', headers={"content-type": "application/json"}
    )
    problem = problem_of(response, 400)
    assert problem["type"].endswith(":malformed-json")
    assert "line 1 column" in problem["detail"]


async def test_the_batch_and_preview_take_their_bodies_the_same_way(
    client: httpx.AsyncClient,
) -> None:
    for url in ("/v1/approximate/batch", "/v1/preview"):
        response = await client.post(
            url, content=b"[", headers={"content-type": "application/json"}
        )
        assert problem_of(response, 400)["type"].endswith(":malformed-json")
        response = await client.post(url, content=b"{}", headers={"content-type": "text/plain"})
        assert locs(problem_of(response, 422)) == [["body"]]


def test_an_endpoint_with_other_parameters_is_refused_when_declared() -> None:
    router = APIRouter(route_class=LeanRoute)

    async def endpoint(request: Request, limit: int) -> Response:
        return Response()

    with pytest.raises(TypeError, match="'limit' is neither"):
        router.add_api_route("/x", endpoint, methods=["GET"])


async def test_the_request_alone_is_passed() -> None:
    router = APIRouter(route_class=LeanRoute)

    async def endpoint(request: Request) -> Response:
        return Response(request.url.path)

    router.add_api_route("/echo", endpoint, methods=["GET"])
    app = FastAPI()
    app.include_router(router)
    async with httpx.AsyncClient(
        transport=httpx.ASGITransport(app=app), base_url="http://test"
    ) as client:
        assert (await client.get("/echo")).text == "/echo"
