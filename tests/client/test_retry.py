"""Retries: the service's 503 + Retry-After honoured against a real server whose queue is
full, and the policy itself (which answers, how long, how many times)."""

from __future__ import annotations

import asyncio
import email.utils
import time
from collections.abc import Iterator
from typing import Any

import httpx
import pytest

from arcspline.client import ApproximateResponse, AsyncClient, Client, Retry, ServiceError
from arcspline.client.retry import retry_after_s
from tests.support.server import Server, running_server


@pytest.fixture(scope="module")
def busy_server(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Server]:
    """One worker and room for one request: a second at the same time gets 503. Every job
    goes to the worker (``inline_max_segments=0``): a small one computed in the serving
    process would be done before the next arrives, and never find the queue full."""
    with running_server(
        tmp_path_factory.mktemp("busy"), pool_size=1, queue_capacity=1, inline_max_segments=0
    ) as server:
        yield server


def test_requests_refused_as_busy_are_retried_until_answered(
    busy_server: Server, paper_request: dict[str, Any]
) -> None:
    before = busy_server.metrics().get("arcspline_errors_total{kind=queue_full}", 0.0)
    request = {**paper_request, "tolerance": 1e-6}

    async def run() -> list[ApproximateResponse]:
        retry = Retry(attempts=8, max_wait_s=5)
        async with AsyncClient(busy_server.url, retry=retry) as client:
            return await asyncio.gather(*(client.approximate(request) for _ in range(6)))

    answers = asyncio.run(run())
    refused = busy_server.metrics()["arcspline_errors_total{kind=queue_full}"] - before
    assert refused >= 1, "the server refused none: the test did not load it"
    assert all(a == answers[0] for a in answers)


def test_without_retries_the_busy_answer_is_the_error(
    busy_server: Server, paper_request: dict[str, Any]
) -> None:
    request = {**paper_request, "tolerance": 1e-6}

    async def run() -> list[Any]:
        async with AsyncClient(busy_server.url, retry=Retry(attempts=1)) as client:
            calls = (client.approximate(request) for _ in range(6))
            return await asyncio.gather(*calls, return_exceptions=True)

    errors = [a for a in asyncio.run(run()) if isinstance(a, ServiceError)]
    assert errors, "six at once against room for one: some must be refused"
    assert {(e.status, e.kind) for e in errors} == {(503, "queue-full")}


# -- the policy, with httpx's mock transport -------------------------------------------


def scripted(*answers: int | type[Exception], retry_after: str | None = None) -> Any:
    """A transport answering with these statuses (or raising these errors) in turn."""
    calls: list[float] = []

    def handle(request: httpx.Request) -> httpx.Response:
        calls.append(time.monotonic())
        answer = answers[min(len(calls), len(answers)) - 1]
        if isinstance(answer, type):
            raise answer("scripted", request=request)
        headers = {"Retry-After": retry_after} if retry_after and answer == 503 else {}
        body = {"type": "about:blank", "title": "t", "status": answer, "detail": "d"}
        if answer == 200:
            return httpx.Response(200, text="<svg/>")
        return httpx.Response(
            answer, json=body, headers={**headers, "Content-Type": "application/problem+json"}
        )

    return httpx.MockTransport(handle), calls


QUICK = Retry(attempts=4, backoff_s=0.001)
#: Any call that is retried: a preview (its answer read as text).
PATH = {"path": "M 0 0 L 1 1", "tolerance": 1}


def test_busy_and_dropped_connections_are_retried() -> None:
    transport, calls = scripted(503, httpx.ConnectError, 429, 200)
    with Client("http://x", retry=QUICK, transport=transport) as client:
        assert client.preview(PATH) == "<svg/>"
    assert len(calls) == 4


def test_retry_after_is_waited_for() -> None:
    transport, calls = scripted(503, 200, retry_after="1")
    with Client("http://x", retry=QUICK, transport=transport) as client:
        client.preview(PATH)
    assert 1.0 <= calls[1] - calls[0] <= 1.6


def test_retry_after_is_spread_so_that_clients_refused_together_part() -> None:
    busy = httpx.Response(503, headers={"Retry-After": "2"})
    waits = {Retry().wait_s(0, busy) for _ in range(200)}
    assert min(waits) >= 2.0  # type: ignore[type-var]
    assert max(waits) <= 3.0  # type: ignore[type-var]
    assert len(waits) > 100


def test_the_probes_are_not_retried() -> None:
    transport, calls = scripted(503, 200)
    with (
        Client("http://x", retry=QUICK, transport=transport) as client,
        pytest.raises(ServiceError),
    ):
        client.ready()
    assert len(calls) == 1


@pytest.mark.parametrize("status", [400, 404, 413, 422, 500, 504])
def test_answers_that_would_not_change_are_not_retried(status: int) -> None:
    transport, calls = scripted(status, 200)
    with (
        Client("http://x", retry=QUICK, transport=transport) as client,
        pytest.raises(ServiceError) as caught,
    ):
        client.preview(PATH)
    assert caught.value.status == status
    assert len(calls) == 1


def test_a_read_timeout_is_not_retried() -> None:
    transport, calls = scripted(httpx.ReadTimeout, 200)
    with (
        Client("http://x", retry=QUICK, transport=transport) as client,
        pytest.raises(httpx.ReadTimeout),
    ):
        client.preview(PATH)
    assert len(calls) == 1


def test_attempts_are_counted_in_all() -> None:
    transport, calls = scripted(503)
    with (
        Client("http://x", retry=QUICK, transport=transport) as client,
        pytest.raises(ServiceError),
    ):
        client.preview(PATH)
    assert len(calls) == 4


def test_a_url_that_cannot_be_sent_is_not_retried() -> None:
    with Client("127.0.0.1:9", retry=QUICK) as client, pytest.raises(httpx.UnsupportedProtocol):
        client.preview(PATH)


def test_an_answer_that_is_not_a_problem_keeps_its_status_and_text() -> None:
    transport = httpx.MockTransport(lambda r: httpx.Response(502, text="<html>bad gateway"))
    with (
        Client("http://x", retry=Retry(attempts=1), transport=transport) as client,
        pytest.raises(ServiceError) as caught,
    ):
        client.health()
    assert (caught.value.status, caught.value.kind) == (502, "about:blank")
    assert "bad gateway" in caught.value.detail


def test_retry_after_in_seconds_or_as_a_date() -> None:
    assert retry_after_s("3") == 3.0
    later = email.utils.formatdate(time.time() + 20, usegmt=True)
    told = retry_after_s(later)
    assert told is not None
    assert 18 <= told <= 21
    assert retry_after_s("soon") is None
    assert retry_after_s("²") is None  # a digit to str.isdigit, not to float
    assert retry_after_s(None) is None


def test_waits_grow_and_are_capped() -> None:
    retry = Retry(attempts=10, backoff_s=1.0, max_wait_s=5.0)
    waits = [retry.wait_s(k) for k in range(9)]
    assert all(w is not None for w in waits)
    assert 0.5 <= waits[0] <= 1.5  # type: ignore[operator]
    assert waits[-1] == 5.0
    assert retry.wait_s(9) is None
    with pytest.raises(ValueError, match="attempts"):
        Retry(attempts=0)
