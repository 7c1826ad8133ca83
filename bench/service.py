"""Speed of the HTTP service (issue 3): figures printed, never asserted.

Starts ``python -m service`` as a subprocess (a pool of 2 workers) and measures, in one run:

1. with ``wrk`` (one load generator, the same settings for both): requests/s of
   ``GET /healthz`` and of ``POST /v1/approximate`` (the paper's spiral at 1e-3, 12 arcs),
   and their ratio (target ≥ 0.5);
2. with an httpx client: arcs/s through ``POST /v1/approximate/batch`` (1000 paper spirals at
   1e-5, 54 000 arcs, the JSON sent and received in full), one batch at a time and several
   at once, against the plain one-spiral-at-a-time implementation ``bench/plain.py`` measured
   in the same run (target ≥ 20×).

``wrk`` is the Debian package of that name; when it is missing the script installs it with
apt-get if it can, or says how. Run with ``make bench`` or ``.venv/bin/python bench/service.py``.
"""

from __future__ import annotations

import asyncio
import os
import re
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import time
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

import httpx
import orjson

sys.path.insert(0, str(Path(__file__).resolve().parent))

from plain import plain_approximate

ROOT = Path(__file__).resolve().parents[1]
POOL_SIZE = 2
SPIRAL = {
    "start": [1.5, 3.0],
    "start_tangent": [1.0, 0.0],
    "turn_angle_deg": 51.34,
    "end_curvature": 0.41574,
}
APPROXIMATE_BODY = orjson.dumps({"spiral": SPIRAL, "tolerance": 1e-3})
BATCH_JOBS = 1000
BATCH_TOLERANCE = 1e-5
BATCH_ARCS = 54 * BATCH_JOBS  # Table 1: 54 arcs at 1e-5
WRK_SECONDS = 10
WRK_CONNECTIONS = 32
RATIO_TARGET = 0.5
SPEEDUP_TARGET = 20.0


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        port: int = s.getsockname()[1]
        return port


@contextmanager
def server() -> Iterator[str]:
    """``python -m service`` with a pool of 2 workers, until the block ends."""
    port = _free_port()
    env = {k: v for k, v in os.environ.items() if not k.startswith("ARCSPLINE_")}
    env["ARCSPLINE_POOL_SIZE"] = str(POOL_SIZE)
    env["ARCSPLINE_LOG_LEVEL"] = "warning"
    process = subprocess.Popen(
        [sys.executable, "-m", "service", "--host", "127.0.0.1", "--port", str(port)],
        cwd=ROOT,
        env=env,
    )
    url = f"http://127.0.0.1:{port}"
    try:
        deadline = time.monotonic() + 60
        while True:
            try:
                if httpx.get(f"{url}/readyz", timeout=2).status_code == 200:
                    break
            except httpx.TransportError:
                pass
            if process.poll() is not None or time.monotonic() > deadline:
                raise SystemExit("the server did not start")
            time.sleep(0.1)
        yield url
    finally:
        process.send_signal(signal.SIGTERM)
        process.wait(timeout=60)


# -- wrk ------------------------------------------------------------------------------------


def find_wrk() -> str | None:
    """``wrk`` on the PATH, installed with apt-get when that is possible."""
    found = shutil.which("wrk")
    if found or not shutil.which("apt-get") or os.geteuid() != 0:
        return found
    print("wrk is missing: installing the Debian package (apt-get install wrk) ...")
    install = ["apt-get", "install", "-y", "-q", "wrk"]
    if subprocess.run(install, capture_output=True).returncode != 0:
        subprocess.run(["apt-get", "update", "-q"], capture_output=True)
        subprocess.run(install, capture_output=True)
    return shutil.which("wrk")


def wrk(binary: str, url: str, script: Path | None = None) -> tuple[float, str]:
    """Requests/s of ``url`` under wrk, and wrk's report."""
    command = [binary, "-t1", f"-c{WRK_CONNECTIONS}", f"-d{WRK_SECONDS}s", "--latency"]
    if script is not None:
        command += ["-s", str(script)]
    report = subprocess.run([*command, url], capture_output=True, text=True, check=True).stdout
    match = re.search(r"Requests/sec:\s+([\d.]+)", report)
    if match is None:
        raise SystemExit(f"cannot read wrk's report:\n{report}")
    if "Non-2xx" in report or "Socket errors" in report:
        print(f"  warning: wrk saw errors:\n{report}")
    return float(match.group(1)), report


def measure_wrk(url: str) -> None:
    binary = find_wrk()
    if binary is None:
        print("wrk is not installed: `apt-get install wrk` (Debian/Ubuntu), then run again.")
        return
    with tempfile.TemporaryDirectory() as scratch:
        script = Path(scratch) / "approximate.lua"
        body = APPROXIMATE_BODY.decode()
        script.write_text(
            'wrk.method = "POST"\n'
            f"wrk.body = '{body}'\n"
            'wrk.headers["Content-Type"] = "application/json"\n'
        )
        # Warm both paths, then measure each for the same time with the same settings.
        httpx.post(f"{url}/v1/approximate", content=APPROXIMATE_BODY, timeout=30)
        healthz, _ = wrk(binary, f"{url}/healthz")
        approximate, _ = wrk(binary, f"{url}/v1/approximate", script)
    ratio = approximate / healthz
    print(f"wrk, {WRK_CONNECTIONS} connections, {WRK_SECONDS} s each, pool of {POOL_SIZE}:")
    print(f"  GET  /healthz                        {healthz:10,.0f} requests/s")
    print(f"  POST /v1/approximate (paper, 1e-3)   {approximate:10,.0f} requests/s")
    verdict = "meets" if ratio >= RATIO_TARGET else "misses"
    print(f"  ratio approximate / healthz          {ratio:10.2f}   ({verdict} ≥ {RATIO_TARGET})")


# -- batch arcs/s -----------------------------------------------------------------------------


def plain_arcs_per_s() -> float:
    """The plain implementation, one spiral after another, for about two seconds."""
    start, tangent = (1.5, 3.0), (1.0, 0.0)
    arcs = plain_approximate(start, tangent, 51.34, 0.41574, BATCH_TOLERANCE)
    assert len(arcs) == 54, len(arcs)
    count, began = 0, time.perf_counter()
    while (elapsed := time.perf_counter() - began) < 2.0:
        count += len(plain_approximate(start, tangent, 51.34, 0.41574, BATCH_TOLERANCE))
    return count / elapsed


async def batch_arcs_per_s(url: str, concurrent: int, rounds: int) -> tuple[float, float]:
    """Arcs/s through the batch endpoint: bodies received in full, and also parsed."""
    jobs = [{"spiral": SPIRAL, "tolerance": BATCH_TOLERANCE}] * BATCH_JOBS
    body = orjson.dumps({"jobs": jobs})
    headers = {"content-type": "application/json"}
    async with httpx.AsyncClient(base_url=url, timeout=120) as client:

        async def one() -> bytes:
            response = await client.post("/v1/approximate/batch", content=body, headers=headers)
            response.raise_for_status()
            return response.content

        await one()  # warm the connection and the workers
        began = time.perf_counter()
        replies = [
            r
            for _ in range(rounds)
            for r in await asyncio.gather(*(one() for _ in range(concurrent)))
        ]
        received = time.perf_counter() - began
        parse_began = time.perf_counter()
        arcs = sum(
            result["result"]["stats"]["arc_count"]
            for reply in replies
            for result in orjson.loads(reply)["results"]
        )
        parsed = received + time.perf_counter() - parse_began
    assert arcs == BATCH_ARCS * concurrent * rounds, arcs
    return arcs / received, arcs / parsed


def measure_batch(url: str) -> None:
    plain = plain_arcs_per_s()
    print(f"arcs/s, {BATCH_JOBS} paper spirals at {BATCH_TOLERANCE:g} per batch:")
    print(f"  plain Python, one spiral at a time   {plain:12,.0f} arcs/s")
    for concurrent, rounds in ((1, 5), (2, 3)):
        received, parsed = asyncio.run(batch_arcs_per_s(url, concurrent, rounds))
        label = f"batch, {concurrent} at a time"
        print(
            f"  {label:<36} {received:12,.0f} arcs/s ({received / plain:5.1f}× plain), "
            f"{parsed:,.0f} with the client's JSON parse ({parsed / plain:.1f}×)"
        )
    print(f"  target: ≥ {SPEEDUP_TARGET:g}× plain (JSON made, sent and received in full)")


def main() -> None:
    with server() as url:
        measure_wrk(url)
        measure_batch(url)


if __name__ == "__main__":
    main()
