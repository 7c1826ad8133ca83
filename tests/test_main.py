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
