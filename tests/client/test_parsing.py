"""Reading batch answers: asked for as a stream (NDJSON, a line per job) and read a line at
a time, or as one JSON from a server without streams, with the garbage collector paused
(client/parsing.py): the same typed results as a plain validation of the JSON answer, a
stream cut short an error, and the collector's state restored."""

from __future__ import annotations

import gc
import threading
from collections.abc import Iterator
from typing import Any

import httpx
import pytest
from pydantic import ValidationError

from arcspline.api.schemas import BatchResponse
from arcspline.client import ApproximateResponse, Client, ServiceError
from arcspline.client.parsing import gc_paused
from tests.support.server import Server


def spiral(tolerance: float, turn_angle_deg: float) -> dict[str, Any]:
    return {
        "spiral": {
            "start": [1.5, 3.0],
            "start_tangent": [1.0, 0.0],
            "turn_angle_deg": turn_angle_deg,
            "end_curvature": 0.41574,
        },
        "tolerance": tolerance,
    }


@pytest.fixture
def collector_on() -> Iterator[None]:
    """The collector on for the test, and as it was after it."""
    was = gc.isenabled()
    gc.enable()
    try:
        yield
    finally:
        (gc.enable if was else gc.disable)()


class Recording(httpx.HTTPTransport):
    """A real transport that keeps each answer's media type."""

    def __init__(self) -> None:
        super().__init__()
        self.media_types: list[str] = []

    def handle_request(self, request: httpx.Request) -> httpx.Response:
        response = super().handle_request(request)
        self.media_types.append(response.headers["content-type"])
        return response


REQUESTS = [spiral(1e-4, 30 + i) for i in range(40)]
REQUESTS[7] = spiral(1e-15, 40.0)  # below the tolerance floor: an error entry


def json_answer(server: Server) -> bytes:
    """The batch's whole JSON answer, as a client without streams gets it."""
    reply = httpx.post(
        f"{server.url}/v1/approximate/batch",
        json={"jobs": REQUESTS},
        headers={"Accept": "application/json"},
        timeout=60,
    )
    assert reply.headers["content-type"] == "application/json"
    return reply.content


def test_batch_results_equal_a_plain_validation_of_the_answer(server: Server) -> None:
    transport = Recording()
    with Client(server.url, batch_max_jobs=16, transport=transport) as client:
        answers = client.approximate_batch(REQUESTS)
    assert transport.media_types == ["application/x-ndjson"] * 3
    expected = BatchResponse.model_validate_json(json_answer(server)).results
    check_entries(answers, expected)


def check_entries(answers: list[Any], expected: list[Any]) -> None:
    """The client's entries are the JSON answer's results, typed."""
    assert len(answers) == len(expected) == 40
    for answer, entry in zip(answers, expected, strict=True):
        if entry.status == "ok":
            assert isinstance(answer, ApproximateResponse)
            assert answer == entry.result
        else:
            assert isinstance(answer, ServiceError)
            # Each request has its own id; the rest of the problem is the same.
            assert answer.problem.model_dump(exclude={"request_id"}) == entry.error.model_dump(
                exclude={"request_id"}
            )
    assert isinstance(answers[7], ServiceError)
    assert sum(isinstance(a, ApproximateResponse) for a in answers) == 39


def test_a_server_without_streams_is_read_from_its_json(server: Server) -> None:
    body = json_answer(server)

    def answer(request: httpx.Request) -> httpx.Response:
        assert request.headers["accept"].startswith("application/x-ndjson")
        return httpx.Response(200, content=body, headers={"content-type": "application/json"})

    with Client(server.url, transport=httpx.MockTransport(answer)) as client:
        answers = client.approximate_batch(REQUESTS)
    check_entries(answers, BatchResponse.model_validate_json(body).results)


def test_a_stream_cut_short_makes_its_jobs_errors(server: Server) -> None:
    with httpx.Client(base_url=server.url, timeout=60) as http:
        reply = http.post(
            "/v1/approximate/batch",
            json={"jobs": REQUESTS},
            headers={"Accept": "application/x-ndjson"},
        )
    lines = reply.content.splitlines(keepends=True)
    assert len(lines) == 40

    def answer(request: httpx.Request) -> httpx.Response:
        cut = b"".join(lines[:25])
        return httpx.Response(200, content=cut, headers={"content-type": "application/x-ndjson"})

    with Client(server.url, transport=httpx.MockTransport(answer)) as client:
        answers = client.approximate_batch(REQUESTS)
    assert all(isinstance(a, httpx.RemoteProtocolError) for a in answers)
    assert "25 of its 40 entries" in str(answers[0])


@pytest.mark.usefixtures("collector_on")
def test_the_collector_is_paused_while_reading_and_on_after() -> None:
    with gc_paused():
        assert not gc.isenabled()
    assert gc.isenabled()


@pytest.mark.usefixtures("collector_on")
def test_overlapping_readers_restore_the_collector_after_the_last() -> None:
    first_in, second_done = threading.Event(), threading.Event()
    seen: list[bool] = []

    def first() -> None:
        with gc_paused():
            first_in.set()
            second_done.wait(10)
            seen.append(gc.isenabled())  # the second reader has left; this one still reads

    thread = threading.Thread(target=first)
    thread.start()
    first_in.wait(10)
    with gc_paused():
        pass
    second_done.set()
    thread.join(10)
    assert seen == [False]
    assert gc.isenabled()


def test_a_collector_that_was_off_stays_off() -> None:
    was = gc.isenabled()
    gc.disable()
    try:
        with gc_paused():
            pass
        assert not gc.isenabled()
    finally:
        (gc.enable if was else gc.disable)()


@pytest.mark.usefixtures("collector_on")
def test_an_error_while_reading_restores_the_collector() -> None:
    with pytest.raises(ValidationError, match="EOF while parsing"), gc_paused():
        BatchResponse.model_validate_json(b'{"results": [')
    assert gc.isenabled()
