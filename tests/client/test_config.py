"""The client's own headers: no compression asked of a service on this machine (its CPU
cost buys no transfer time there), unless the caller asks for it."""

from __future__ import annotations

import pytest

from arcspline.client import Client
from arcspline.client.config import ClientConfig, is_loopback


@pytest.mark.parametrize(
    ("url", "loopback"),
    [
        ("http://127.0.0.1:8000", True),
        ("http://127.8.0.1", True),
        ("http://localhost:8000/", True),
        ("http://[::1]:8000", True),
        ("https://arcspline.example.com", False),
        ("http://192.0.2.7:8000", False),
    ],
)
def test_loopback_urls(url: str, loopback: bool) -> None:
    assert is_loopback(url) is loopback


def config(url: str) -> ClientConfig:
    return ClientConfig.of(url, 10.0, None, 1, 1, 1)


def test_a_local_service_is_asked_for_no_compression() -> None:
    assert config("http://127.0.0.1:8000").headers(None)["Accept-Encoding"] == "identity"
    assert "Accept-Encoding" not in config("https://arcspline.example.com").headers(None)


def test_the_callers_choice_wins() -> None:
    headers = config("http://127.0.0.1:8000").headers({"accept-encoding": "gzip"})
    assert {k.lower(): v for k, v in headers.items()}["accept-encoding"] == "gzip"
    assert len([k for k in headers if k.lower() == "accept-encoding"]) == 1


def test_the_client_sends_them() -> None:
    with Client("http://127.0.0.1:8000") as client:
        assert client._http.headers["accept-encoding"] == "identity"
    with Client("https://arcspline.example.com") as client:
        assert "gzip" in client._http.headers["accept-encoding"]
