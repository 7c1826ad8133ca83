"""Start-up of the service (issue 15): figures printed, never asserted.

Starts ``python -m arcspline`` (a pool of 2 workers, ``bench/serve.py``) and measures:

1. how long the process takes to answer /readyz with 200 (the worker pool's forkserver
   imports the core and runs a warm-up job of each kind before it forks any worker);
2. the first request of each kind after that cold start against the median of the next
   ``WARM_REQUESTS`` of the same kind (target: the first ≤ 3× a warm one), and against
   requests sent after an idle pause — the paper's spiral at 1e-3 by ``subdivide``, by
   ``fewest-arcs``, with a G-code program, and its preview;
3. how long after a worker is killed (SIGKILL) a new one has replaced it and /readyz answers
   200 again, over ``KILLS`` kills (target: within 1 s).

Run with ``make bench`` or ``.venv/bin/python bench/startup.py``. Setting
``ARCSPLINE_BENCH_MODULE`` and ``ARCSPLINE_BENCH_PYTHONPATH`` measures another checkout.
"""

from __future__ import annotations

import os
import signal
import statistics
import sys
import time
from pathlib import Path

import httpx

sys.path.insert(0, str(Path(__file__).resolve().parent))

from serve import Service, service

SPIRAL = {"start": [1.5, 3.0], "start_tangent": [1.0, 0.0], "turn_angle_deg": 51.34,
          "end_curvature": 0.41574}  # fmt: skip
REQUESTS = {
    "subdivide": ("/v1/approximate", {"spiral": SPIRAL, "tolerance": 1e-3}),
    "fewest-arcs": (
        "/v1/approximate",
        {"spiral": SPIRAL, "tolerance": 1e-3, "strategy": "fewest-arcs"},
    ),
    "G-code": (
        "/v1/approximate",
        {"spiral": SPIRAL, "tolerance": 1e-3, "gcode": {"feed_rate": 1000}},
    ),
    "preview": ("/v1/preview", {"spiral": SPIRAL, "tolerance": 1e-3}),
}
WARM_REQUESTS = 50
IDLE_REQUESTS = 3
IDLE_S = 1.0
KILLS = 5
FIRST_TARGET = 3.0
REPLACE_TARGET_S = 1.0


def timed(client: httpx.Client, path: str, body: object) -> float:
    began = time.perf_counter()
    response = client.post(path, json=body)
    elapsed = time.perf_counter() - began
    response.raise_for_status()
    return elapsed


def first_requests(running: Service) -> None:
    print(f"cold start: /readyz answered 200 after {running.ready_after_s:.2f} s")
    print(
        f"first request after the cold start vs the median of the next {WARM_REQUESTS} "
        f"(back to back), and of {IDLE_REQUESTS} more each after {IDLE_S:g} s idle (this VM "
        "wakes idle processes slowly: the cost of an idle pause, not of cold code):"
    )
    worst = 0.0
    with httpx.Client(base_url=running.url, timeout=30) as client:
        # The client's own first request (connection, lazy imports) is not the server's.
        client.get("/healthz").raise_for_status()
        for name, (path, body) in REQUESTS.items():
            first = timed(client, path, body)
            warm = statistics.median(timed(client, path, body) for _ in range(WARM_REQUESTS))
            idle = []
            for _ in range(IDLE_REQUESTS):
                time.sleep(IDLE_S)
                idle.append(timed(client, path, body))
            worst = max(worst, first / warm)
            print(f"  {name:<12} first {first * 1e3:7.2f} ms  warm {warm * 1e3:7.2f} ms "
                  f"({first / warm:4.2f}×)  after idle {statistics.median(idle) * 1e3:7.2f} ms "
                  f"({first / statistics.median(idle):4.2f}×)")  # fmt: skip
    verdict = "met" if worst <= FIRST_TARGET else "NOT met"
    print(f"  target: first ≤ {FIRST_TARGET:g}× warm — worst {worst:.2f}× — {verdict}")


def replacements(running: Service) -> None:
    waits = []
    with httpx.Client(base_url=running.url, timeout=2) as client:
        for _ in range(KILLS):
            before = set(running.worker_pids())
            victim = min(before)
            began = time.monotonic()
            os.kill(victim, signal.SIGKILL)
            # Ready again: a new worker has taken the dead one's place and /readyz, which is
            # 503 while a worker is being replaced, answers 200.
            while True:
                pids = set(running.worker_pids())
                replaced = victim not in pids and pids - before and len(pids) == len(before)
                if replaced and client.get("/readyz").status_code == 200:
                    break
                if time.monotonic() - began > 10:
                    raise SystemExit("no worker replaced the killed one within 10 s")
                time.sleep(0.001)
            waits.append(time.monotonic() - began)
            time.sleep(0.2)
    worst = max(waits)
    verdict = "met" if worst <= REPLACE_TARGET_S else "NOT met"
    print(f"a worker killed (SIGKILL) {KILLS} times: ready again after "
          + ", ".join(f"{w * 1e3:.0f}" for w in waits)
          + f" ms — target ≤ {REPLACE_TARGET_S:g} s — {verdict}")  # fmt: skip


def main() -> None:
    with service() as running:
        first_requests(running)
        replacements(running)


if __name__ == "__main__":
    main()
