"""Fixtures shared by the whole suite (keep this file small).

- ``anyio_backend``: async tests run with anyio's pytest plugin on asyncio
  (``@pytest.mark.anyio``); session-scoped so that module-scoped async fixtures work.
- ``paper_request``: the body of ``POST /v1/approximate`` for the paper's example
  (Walton & Meek 1996, Table 1: 12 arcs at this tolerance of 0.001).
"""

from __future__ import annotations

import copy
from typing import Any

import pytest

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
