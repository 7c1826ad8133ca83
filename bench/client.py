"""The Python client's throughput against a running service (issues 18 and 19): figures
printed, never asserted.

Starts ``python -m arcspline`` (a pool of 2 workers) and, in one run, sends the paper's
spiral at 1e-5 (54 arcs each) with different seeds of variation (turn angle), measuring
segments/s end to end — requests made, sent, answered and parsed into objects on the client:

1. a plain httpx loop, one ``POST /v1/approximate`` per spiral, JSON parsed with ``json``
   (what every user wrote before the client existed; the baseline);
2. ``Client.approximate`` one spiral at a time (the same loop, typed results: the client's
   own cost per request);
3. ``Client.approximate_batch`` over 10 000 spirals (chunks of 1000, 4 in flight);
4. ``AsyncClient.approximate_batch`` over the same;

and, in the same run, the plain one-spiral-at-a-time implementation ``bench/plain.py``
(``bench/service.py``'s ``plain_arcs_per_s``, the same spiral and tolerance): issue 19's
target is a 10,000-spiral batch through the client, parsed, at ≥ 20× plain Python.

Run with ``make bench`` or ``.venv/bin/python bench/client.py``.
"""

from __future__ import annotations

import asyncio
import json
import sys
import time
from pathlib import Path
from typing import Any

import httpx

sys.path.insert(0, str(Path(__file__).resolve().parent))
sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "service"))

from serve import service

from arcspline.client import ApproximateResponse, AsyncClient, Client
from service import SPEEDUP_TARGET, plain_arcs_per_s

TOLERANCE = 1e-5
LOOP_SPIRALS = 1000
BATCH_SPIRALS = 10_000


def spirals(count: int) -> list[dict[str, Any]]:
    """The paper's spiral with turn angles spread over 51.0°–51.68° (each one different)."""
    return [
        {
            "spiral": {
                "start": [1.5, 3.0],
                "start_tangent": [1.0, 0.0],
                "turn_angle_deg": 51.0 + 0.68 * i / count,
                "end_curvature": 0.41574,
            },
            "tolerance": TOLERANCE,
        }
        for i in range(count)
    ]


def plain_loop(url: str, requests: list[dict[str, Any]]) -> int:
    segments = 0
    with httpx.Client(base_url=url, timeout=60) as http:
        for request in requests:
            reply = http.post("/v1/approximate", json=request)
            reply.raise_for_status()
            segments += json.loads(reply.content)["stats"]["segment_count"]
    return segments


def client_loop(url: str, requests: list[dict[str, Any]]) -> int:
    with Client(url) as client:
        return sum(client.approximate(r).stats.segment_count for r in requests)


def client_batch(url: str, requests: list[dict[str, Any]]) -> int:
    with Client(url) as client:
        return sum(_count(answer) for answer in client.approximate_batch(requests))


def async_batch(url: str, requests: list[dict[str, Any]]) -> int:
    async def run() -> int:
        async with AsyncClient(url) as client:
            return sum(_count(answer) for answer in await client.approximate_batch(requests))

    return asyncio.run(run())


def _count(answer: object) -> int:
    assert isinstance(answer, ApproximateResponse), answer
    return answer.stats.segment_count


def rate(
    label: str, run: Any, url: str, requests: list[dict[str, Any]], base: float, plain: float
) -> float:
    best = float("inf")
    segments = 0
    for _ in range(3):
        began = time.perf_counter()
        segments = run(url, requests)
        best = min(best, time.perf_counter() - began)
    per_s = segments / best
    ratio = f"{per_s / base:6.1f}× the loop" if base else " " * 15
    print(
        f"  {label:<44} {len(requests):>6} spirals {per_s:12,.0f} segments/s {ratio} "
        f"{per_s / plain:6.1f}× plain Python"
    )
    return per_s


def main() -> None:
    with service(2) as running:
        url = running.url
        plain = plain_arcs_per_s()
        print(f"segments/s end to end (paper spiral at {TOLERANCE:g}, pool of 2, parsed):")
        print(f"  {'plain Python (bench/plain.py), no service':<51} {plain:19,.0f} segments/s")
        base = rate("plain httpx loop, one request each", plain_loop, url,
                    spirals(LOOP_SPIRALS), 0.0, plain)  # fmt: skip
        rate("Client.approximate, one request each", client_loop, url,
             spirals(LOOP_SPIRALS), base, plain)  # fmt: skip
        batch = rate("Client.approximate_batch", client_batch, url, spirals(BATCH_SPIRALS),
                     base, plain)  # fmt: skip
        rate("AsyncClient.approximate_batch", async_batch, url, spirals(BATCH_SPIRALS), base,
             plain)  # fmt: skip
        verdict = "meets" if batch / plain >= SPEEDUP_TARGET else "misses"
        print(
            f"  Client.approximate_batch {batch / plain:.1f}× plain Python "
            f"({verdict} ≥ {SPEEDUP_TARGET:g}×)"
        )


if __name__ == "__main__":
    main()
