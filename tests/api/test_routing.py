"""LeanRoute: bodies taken as FastAPI takes them, without FastAPI's per-request machinery."""

from __future__ import annotations

import json
from typing import Any

import httpx
import pytest
from fastapi import APIRouter, FastAPI, Request
from starlette.responses import Response

from arcspline.api.routing import LeanRoute

from .conftest import problem_of

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


@pytest.mark.parametrize(
    "content_type", ["text/plain", "application/x-www-form-urlencoded", "application/xml"]
)
async def test_a_body_not_declared_json_is_an_unsupported_media_type(
    client: httpx.AsyncClient, paper_request: dict[str, Any], content_type: str
) -> None:
    response = await client.post(
        URL, content=_raw(paper_request), headers={"content-type": content_type}
    )
    problem = problem_of(response, 415)
    assert problem["type"].endswith(":unsupported-media-type")
    assert content_type in problem["detail"]
    assert "application/json" in problem["detail"]


async def test_a_body_without_a_content_type_is_refused_plainly(
    client: httpx.AsyncClient, paper_request: dict[str, Any]
) -> None:
    # curl -d sends a form's type; a client that sends none is told what to send, and no
    # name from the code (it said "... instance of ApproximateRequest").
    response = await client.post(URL, content=_raw(paper_request))
    assert "content-type" not in response.request.headers
    problem = problem_of(response, 415)
    assert "no Content-Type" in problem["detail"]
    assert "application/json" in problem["detail"]
    assert "ApproximateRequest" not in response.text


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
        assert problem_of(response, 415)["type"].endswith(":unsupported-media-type")


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


async def test_a_trailing_slash_is_not_redirected_to_the_host_the_client_named(
    client: httpx.AsyncClient, paper_request: dict[str, Any]
) -> None:
    # Starlette answered 307 to http://<Host>/v1/approximate: a Location from a header.
    response = await client.post(
        URL + "/", json=paper_request, headers={"Host": "attacker.example"}
    )
    assert "location" not in response.headers
    assert problem_of(response, 404)["type"] == "about:blank"


def _duplicate(problem: dict[str, Any]) -> list[Any]:
    (error,) = problem["errors"]
    assert error["type"] == "duplicate_key"
    assert "2 times" in error["msg"]
    return list(error["loc"])


@pytest.mark.parametrize(
    ("raw", "loc"),
    [
        (b'{"tolerance": 0.001, "tolerance": 1e9}', ["body", "tolerance"]),
        (
            b'{"spiral": {"start": [0, 0], "start": [5, 5], "turn_angle_deg": 45,'
            b' "end_curvature": 1}, "tolerance": 0.01}',
            ["body", "spiral", "start"],
        ),
        (b'{"a": [{}, {"b": {"k": 1, "k": 2}}]}', ["body", "a", 1, "b", "k"]),
    ],
)
async def test_a_key_named_twice_is_refused_with_where(
    client: httpx.AsyncClient, raw: bytes, loc: list[Any]
) -> None:
    # JSON parsers disagree on which value such a body means (first, last, an error): the
    # service takes none of them rather than silently the last.
    response = await client.post(URL, content=raw, headers={"content-type": "application/json"})
    problem = problem_of(response, 422)
    assert _duplicate(problem) == loc
    assert ".".join(map(str, loc)) in problem["detail"]


async def test_a_key_named_twice_in_one_batch_job_refuses_the_batch(
    client: httpx.AsyncClient, paper_request: dict[str, Any]
) -> None:
    jobs = [_raw(paper_request)] * 3 + [b'{"spiral": {}, "tolerance": 1, "tolerance": 2}']
    raw = b'{"jobs": [' + b",".join(jobs) + b"]}"
    for url in ("/v1/approximate/batch", "/v1/paths/batch"):
        response = await client.post(url, content=raw, headers={"content-type": "application/json"})
        assert _duplicate(problem_of(response, 422)) == ["body", "jobs", 3, "tolerance"]


async def test_a_key_named_twice_is_refused_by_every_json_endpoint(
    client: httpx.AsyncClient,
) -> None:
    raw = b'{"tolerance": 0.1, "tolerance": 0.2}'
    for url in ("/v1/preview", "/v1/paths/approximate", "/v1/drawings/approximate"):
        response = await client.post(url, content=raw, headers={"content-type": "application/json"})
        assert _duplicate(problem_of(response, 422)) == ["body", "tolerance"], url


async def test_malformed_json_after_a_duplicate_is_said_to_be_malformed(
    client: httpx.AsyncClient,
) -> None:
    raw = b'{"a": {"k": 1, "k": 2}, "b": ['
    response = await client.post(URL, content=raw, headers={"content-type": "application/json"})
    assert problem_of(response, 400)["type"].endswith(":malformed-json")


async def test_the_same_key_in_different_objects_is_no_duplicate(
    client: httpx.AsyncClient, paper_request: dict[str, Any]
) -> None:
    body = {"jobs": [paper_request, paper_request]}
    response = await client.post("/v1/approximate/batch", json=body)
    assert response.status_code == 200, response.text
    assert [r["status"] for r in response.json()["results"]] == ["ok", "ok"]
