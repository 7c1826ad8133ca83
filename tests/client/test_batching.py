"""Batches through a real server: chunked under the limits, answered in order, a bad job an
error entry, and a client set for the defaults still working against a server configured
smaller (its 413s split the chunks)."""

from __future__ import annotations

import asyncio
from collections.abc import Iterator
from typing import Any

import httpx
import pytest

from arcspline.api.schemas import ProblemResponse
from arcspline.client import (
    ApproximateResponse,
    AsyncClient,
    Client,
    PathResponse,
    Retry,
    ServiceError,
)
from arcspline.client.batching import Chunk, pack, split
from arcspline.client.errors import ServiceError as Error
from tests.support.server import Server, running_server


def spiral(tolerance: float, turn_angle_deg: float = 51.34) -> dict[str, Any]:
    return {
        "spiral": {
            "start": [1.5, 3.0],
            "start_tangent": [1.0, 0.0],
            "turn_angle_deg": turn_angle_deg,
            "end_curvature": 0.41574,
        },
        "tolerance": tolerance,
    }


BAD = {"spiral": {"control_points": [[0, 0], [1, 0], [2, 0]]}, "tolerance": 0.1}


def test_answers_come_in_order_with_the_bad_job_an_error(server: Server) -> None:
    # Different angles, so that a mix-up of the order would show in the answers.
    requests: list[dict[str, Any]] = [spiral(0.001, 10 + i) for i in range(70)]
    requests.insert(33, BAD)
    with Client(server.url, batch_max_jobs=16, max_concurrency=3) as client:
        answers = client.approximate_batch(requests)
        singles = [client.approximate(r) for r in requests[30:36] if r is not BAD]
    assert len(answers) == 71
    error = answers[33]
    assert isinstance(error, ServiceError)
    assert error.kind == "validation"
    good = [a for a in answers if isinstance(a, ApproximateResponse)]
    assert len(good) == 70
    assert [a for a in answers[30:36] if a is not error] == singles


def test_the_async_client_answers_alike(server: Server) -> None:
    requests = [spiral(0.01, 20 + i) for i in range(40)]

    async def run() -> list[Any]:
        async with AsyncClient(server.url, batch_max_jobs=7, max_concurrency=2) as client:
            return await client.approximate_batch(requests)

    answers = asyncio.run(run())
    with Client(server.url) as client:
        assert answers == client.approximate_batch(requests)


def test_paths_go_through_their_own_batch(server: Server) -> None:
    requests = [{"path": f"M 0 0 Q {i} 10 20 0", "tolerance": 0.01} for i in range(1, 6)]
    with Client(server.url, batch_max_jobs=2) as client:
        answers = client.approximate_paths_batch(requests)
        assert answers[2] == client.approximate_path(requests[2])
    assert all(isinstance(a, PathResponse) for a in answers)


def test_a_batch_holds_one_kind() -> None:
    with Client("http://127.0.0.1:9") as client, pytest.raises(ValueError, match="request 1"):
        client.approximate_batch([spiral(0.1), {"path": "M 0 0 L 1 1", "tolerance": 0.1}])


@pytest.fixture(scope="module")
def small_server(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Server]:
    """A server that takes at most 5 jobs and 3000 bytes per request."""
    with running_server(
        tmp_path_factory.mktemp("small"), pool_size=1, batch_max_jobs=5, max_body_bytes=3000
    ) as server:
        yield server


def test_the_servers_smaller_limits_split_the_chunks(small_server: Server) -> None:
    before = small_server.metrics()
    requests = [spiral(0.01, 20 + i) for i in range(23)]
    with Client(small_server.url) as client:  # set for the defaults: 1000 jobs, 4 MiB
        answers = client.approximate_batch(requests)
    assert all(isinstance(a, ApproximateResponse) for a in answers)
    with Client(small_server.url) as client:
        assert answers[17] == client.approximate(requests[17])
    after = small_server.metrics()

    def refused(kind: str) -> float:
        key = f"arcspline_errors_total{{kind={kind}}}"
        return after.get(key, 0.0) - before.get(key, 0.0)

    # The first chunk was refused for its size, and the service told the client so.
    assert refused("too_many_jobs") + refused("body_too_large") >= 1


def test_a_single_job_larger_than_the_body_limit_is_its_own_error(small_server: Server) -> None:
    huge = {"path": "M 0 0 " + "L 1 1 L 2 0 " * 300, "tolerance": 0.01}
    with Client(small_server.url) as client:
        answers = client.approximate_paths_batch([huge, {"path": "M 0 0 L 1 1", "tolerance": 1}])
    assert isinstance(answers[0], ServiceError)
    assert answers[0].status == 413
    assert isinstance(answers[1], PathResponse)


# -- packing, without a server ---------------------------------------------------------


def jobs(*sizes: int) -> list[bytes]:
    return [b"x" * size for size in sizes]


def test_pack_keeps_order_and_both_bounds() -> None:
    encoded = jobs(10, 10, 10, 10, 10, 10, 10)
    chunks = pack(encoded, 0, max_jobs=3, max_bytes=10_000)
    assert [len(c.jobs) for c in chunks] == [3, 3, 1]
    assert [c.start for c in chunks] == [0, 3, 6]
    # {"jobs":[ + ]} is 11 bytes; three jobs of 10 with two commas make 43.
    chunks = pack(encoded, 0, max_jobs=100, max_bytes=43)
    assert [len(c.jobs) for c in chunks] == [3, 3, 1]
    assert all(len(c.body) <= 43 for c in chunks)
    assert b"".join(b"".join(c.jobs) for c in chunks) == b"".join(encoded)


def test_a_job_larger_than_the_bound_goes_alone() -> None:
    chunks = pack(jobs(5, 100, 5), 0, max_jobs=10, max_bytes=40)
    assert [len(c.jobs) for c in chunks] == [1, 1, 1]


def refusal(kind: str, limit: float | None = None) -> Error:
    return Error(
        ProblemResponse(
            type=f"urn:arcspline:problem:{kind}", title="x", status=413, detail="x", limit=limit
        )
    )


def test_split_follows_the_servers_limit_or_halves() -> None:
    chunk = Chunk(10, jobs(*[1] * 9))
    parts = split(chunk, refusal("too-many-jobs", 4))
    assert parts is not None
    assert [(p.start, len(p.jobs)) for p in parts] == [(10, 4), (14, 4), (18, 1)]
    parts = split(chunk, refusal("body-too-large", 100))
    assert parts is not None
    assert [(p.start, len(p.jobs)) for p in parts] == [(10, 4), (14, 5)]
    assert split(Chunk(0, jobs(1)), refusal("body-too-large")) is None


def test_a_limit_no_smaller_than_the_chunk_halves_it() -> None:
    chunk = Chunk(0, jobs(*[1] * 4))
    for limit in (4, 1000):
        parts = split(chunk, refusal("too-many-jobs", limit))
        assert parts is not None
        assert [len(p.jobs) for p in parts] == [2, 2]


def test_a_server_that_always_refuses_for_size_ends_in_errors_not_a_loop() -> None:
    def refuse(request: httpx.Request) -> httpx.Response:
        body = {"type": "urn:arcspline:problem:too-many-jobs", "title": "x", "status": 413,
                "detail": "x", "limit": 1000}  # fmt: skip
        return httpx.Response(413, json=body, headers={"Content-Type": "application/problem+json"})

    with Client("http://x", transport=httpx.MockTransport(refuse)) as client:
        answers = client.approximate_batch([spiral(0.1)] * 4)
    assert [a.status for a in answers if isinstance(a, ServiceError)] == [413] * 4


def test_a_chunk_whose_connection_fails_is_its_jobs_entries_and_the_rest_finish(
    server: Server,
) -> None:
    """Jobs 0–2 go in one chunk, 3–5 in another; the first chunk's connection fails."""
    requests = [spiral(0.01, 10.0 + i) for i in range(6)]
    quick = Retry(attempts=2, backoff_s=0.001)
    with httpx.HTTPTransport() as real:

        def handle(request: httpx.Request) -> httpx.Response:
            if b"10.0" in request.content:  # the first chunk's first job
                raise httpx.ConnectError("scripted", request=request)
            return real.handle_request(request)

        transport = httpx.MockTransport(handle)
        with Client(server.url, batch_max_jobs=3, transport=transport, retry=quick) as client:
            answers = client.approximate_batch(requests)
    for batch in (answers, asyncio.run(_async_batch(server.url, requests, quick))):
        assert all(isinstance(a, httpx.ConnectError) for a in batch[:3])
        assert all(isinstance(a, ApproximateResponse) for a in batch[3:])


async def _async_batch(url: str, requests: list[dict[str, Any]], retry: Retry) -> list[Any]:
    async with httpx.AsyncHTTPTransport() as real:

        async def handle(request: httpx.Request) -> httpx.Response:
            await request.aread()
            if b"10.0" in request.content:
                raise httpx.ConnectError("scripted", request=request)
            return await real.handle_async_request(request)

        transport = httpx.MockTransport(handle)
        async with AsyncClient(url, batch_max_jobs=3, transport=transport, retry=retry) as client:
            return await client.approximate_batch(requests)
