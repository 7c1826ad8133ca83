"""``python -m arcspline``: what the server process sets up before uvicorn serves."""

from __future__ import annotations

import gc
import os
import signal
from collections.abc import Iterator
from typing import Any

import pytest
import uvicorn

from arcspline import __main__ as entry


@pytest.fixture
def _restored() -> Iterator[None]:
    thresholds, handler = gc.get_threshold(), signal.getsignal(signal.SIGTERM)
    yield
    gc.set_threshold(*thresholds)
    signal.signal(signal.SIGTERM, handler)


@pytest.mark.usefixtures("_restored")
def test_the_server_collects_less_often_and_serves_the_settings(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    for name in list(os.environ):
        if name.upper().startswith("ARCSPLINE_"):
            monkeypatch.delenv(name)
    seen: dict[str, Any] = {}

    def run(app: str, **options: Any) -> None:
        seen.update(options, app=app, thresholds=gc.get_threshold())

    monkeypatch.setattr(uvicorn, "run", run)
    gc.set_threshold(700, 10, 10)
    entry.main(["--host", "127.0.0.2", "--port", "8765"])
    assert seen["thresholds"] == entry.GC_THRESHOLDS
    assert seen["thresholds"][0] > 700
    assert (seen["app"], seen["factory"]) == ("arcspline.api.app:create_app", True)
    assert (seen["host"], seen["port"]) == ("127.0.0.2", 8765)
    assert signal.getsignal(signal.SIGTERM) is entry._exit_cleanly


@pytest.mark.usefixtures("_restored")
def test_the_server_bounds_its_connections_by_the_settings_and_the_file_limit(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    from uvicorn.protocols.http.httptools_impl import HttpToolsProtocol

    from arcspline.serving import descriptors
    from arcspline.serving.protocol import ConnectionLimits
    from arcspline.settings import get_settings

    for name in list(os.environ):
        if name.upper().startswith("ARCSPLINE_"):
            monkeypatch.delenv(name)
    for name, value in {
        "MAX_CONNECTIONS": "1000",
        "MAX_HEADER_BYTES": "1000",
        "HEADER_TIMEOUT_S": "2.5",
        "BODY_TIMEOUT_S": "7",
        "KEEP_ALIVE_TIMEOUT_S": "9",
        "POOL_SIZE": "1",
        "RETRY_AFTER_S": "4",
    }.items():
        monkeypatch.setenv(f"ARCSPLINE_{name}", value)
    # An open-file limit of 500 leaves 500 - 64 - 8 × 1 for clients.
    monkeypatch.setattr(descriptors, "raise_nofile_limit", lambda: 500)
    seen: dict[str, Any] = {}
    monkeypatch.setattr(uvicorn, "run", lambda app, **options: seen.update(options))
    get_settings.cache_clear()
    try:
        entry.main([])
    finally:
        get_settings.cache_clear()
    protocol = seen["http"]
    assert issubclass(protocol, HttpToolsProtocol)
    assert protocol.limits == ConnectionLimits(
        max_connections=428,
        max_header_bytes=1000,
        header_timeout_s=2.5,
        body_timeout_s=7.0,
        retry_after_s=4,
    )
    assert seen["timeout_keep_alive"] == 9
