"""``X-Request-ID``: a client's own id is kept when it is safe to log, replaced quietly when
it is not (docs/http-api.md#request-ids)."""

from __future__ import annotations

import logging
import re

import httpx
import pytest

from arcspline.api.app import client_request_id

from .conftest import problem_of

pytestmark = pytest.mark.anyio

FRESH = re.compile(r"[0-9a-f]{32}")


@pytest.mark.parametrize(
    "given",
    [
        "req-42",
        "7f9c2ba4e88f827d616045507605853e",  # an nginx $request_id, a W3C trace id
        "00-0af7651916cd43dd8448eb211c80319c-b7ad6b7169203331-01",  # a traceparent
        "checkout/retry:2;user=17",
        "x" * 128,
    ],
)
async def test_a_clients_id_is_kept_without_a_warning(
    client: httpx.AsyncClient, caplog: pytest.LogCaptureFixture, given: str
) -> None:
    with caplog.at_level(logging.INFO):
        response = await client.post("/v1/approximate", json={}, headers={"X-Request-ID": given})
    assert response.headers["x-request-id"] == given
    assert problem_of(response, 422)["request_id"] == given
    assert not [r for r in caplog.records if r.levelno >= logging.WARNING]


@pytest.mark.parametrize("given", ["has space", "x" * 129, "caf\u00e9", "tab\there"])
async def test_an_unsafe_id_is_replaced_without_a_warning(
    client: httpx.AsyncClient, caplog: pytest.LogCaptureFixture, given: str
) -> None:
    with caplog.at_level(logging.INFO):
        response = await client.post(
            "/v1/approximate", json={}, headers={"X-Request-ID": given.encode("latin-1")}
        )
    fresh = response.headers["x-request-id"]
    assert FRESH.fullmatch(fresh), fresh
    assert problem_of(response, 422)["request_id"] == fresh
    assert not [r for r in caplog.records if r.levelno >= logging.WARNING]


@pytest.mark.parametrize("given", ["a\nb", "a\r\nINFO forged line", "nul\x00", "del\x7f", ""])
def test_control_characters_never_reach_a_log_line(given: str) -> None:
    # (An HTTP client refuses to send these; a raw socket can.)
    assert FRESH.fullmatch(client_request_id(given))


def test_the_servers_own_ids_pass_unchanged() -> None:
    own = "0123456789abcdef0123456789abcdef"
    assert client_request_id(own) == own
