"""What the integration tests send a real server, and how they wait on it."""

from __future__ import annotations

import asyncio
import time
from collections.abc import Awaitable, Callable
from typing import Any

SPIRAL: dict[str, Any] = {
    "start": [1.5, 3.0],
    "start_tangent": [1.0, 0.0],
    "turn_angle_deg": 51.34,
    "end_curvature": 0.41574,
}
#: A request that keeps a worker busy for tens of milliseconds (about a thousand arcs and
#: their G-code), so that a burst of them outruns the client and work piles up.
HEAVY = {"spiral": SPIRAL, "tolerance": 1e-9, "gcode": {"feed_rate": 1000, "decimals": 6}}
#: Room for batches of seconds of work: the batch work budget (ARCSPLINE_BATCH_MAX_SEGMENTS)
#: would stop them at a fraction of that.
ROOM = {"batch_max_segments": 10**7}
#: Hang guard for every request and wait: far beyond any answer's time.
CLIENT_TIMEOUT_S = 120.0


async def until(condition: Callable[[], Awaitable[bool]], timeout_s: float = 60.0) -> None:
    """Wait until ``condition()`` holds, checking every 10 ms."""
    deadline = time.monotonic() + timeout_s
    while not await condition():
        assert time.monotonic() < deadline, "condition not reached in time"
        await asyncio.sleep(0.01)
