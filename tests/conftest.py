"""Fixtures shared by the whole suite (keep this file small).

- ``anyio_backend``: async tests run with anyio's pytest plugin on asyncio
  (``@pytest.mark.anyio``); session-scoped so that module-scoped async fixtures work.
- ``paper_request``: the body of ``POST /v1/approximate`` for the paper's example
  (Walton & Meek 1996, Table 1: 12 arcs at this tolerance of 0.001).
- ``rs274``: LinuxCNC's interpreter, fetched and cached by ``scripts/fetch-rs274.sh``
  (skipped where it cannot be fetched, except in CI).
"""

from __future__ import annotations

import copy
import os
from pathlib import Path
from typing import Any

import pytest

from tests.support.rs274 import Rs274, provide

FETCH = Path(__file__).resolve().parents[1] / "scripts" / "fetch-rs274.sh"

PAPER_SPIRAL: dict[str, Any] = {
    "start": [1.5, 3.0],
    "start_tangent": [1.0, 0.0],
    "turn_angle_deg": 51.34,
    "end_curvature": 0.41574,
}


@pytest.fixture(scope="session")
def anyio_backend() -> str:
    return "asyncio"


@pytest.fixture
def paper_request() -> dict[str, Any]:
    return {"spiral": copy.deepcopy(PAPER_SPIRAL), "tolerance": 0.001}


@pytest.fixture(scope="session")
def rs274() -> Rs274:
    """The interpreter, fetched once per machine (the script caches it and takes a lock, so
    the xdist workers of one run share a single download). Where the machine cannot fetch it
    (not Debian or Ubuntu, no network) the G-code tests skip, saying why; in CI they fail."""
    return provide(FETCH, ci=os.environ.get("CI", "").lower() == "true")
