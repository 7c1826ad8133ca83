"""Speed of the HTTP service (issues 3 and 19): figures printed, never asserted.

Starts ``python -m arcspline`` as a subprocess (a pool of 2 workers) twice, as configured
(every job through the pool) and with small single jobs computed in the serving process
(``inline_max_segments=256``), and measures, in one run:

1. with ``wrk`` (the same settings for both endpoints), at 2 client threads (issue 19's
   target) and at 1, 32 connections: requests/s of ``GET /healthz`` and of
   ``POST /v1/approximate`` (the paper's spiral at 1e-3, 12 arcs) in turn, on each service
   in turn, three rounds (this machine's speed drifts over seconds), and the median of the
   rounds' ratios (target ≥ 0.8); then one round each at 8 and 64 connections;
2. arcs/s through ``POST /v1/approximate/batch`` (1000 paper spirals at 1e-5, 54 000 arcs,
   the JSON made, sent and received in full), with wrk one and two batches at a time, and
   with an httpx client that also parses the reply (and checks its 54 000 arcs), against
   the plain one-spiral-at-a-time implementation ``bench/plain.py`` measured in the same run
   (target ≥ 20×; the project's own client: ``bench/client.py``).

``wrk`` is the Debian package of that name; when it is missing the script installs it with
apt-get if it can, or says how. Run with ``make bench`` or ``.venv/bin/python bench/service.py``.
"""

from __future__ import annotations

import os
import re
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import httpx
import orjson

sys.path.insert(0, str(Path(__file__).resolve().parent))

from plain import plain_approximate
from serve import service

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
WRK_SECONDS = 5
RATIO_ROUNDS = 3
WRK_CONNECTIONS = 32
#: Client threads of wrk: the issue's target is at 2 (issue 19); 1 is the earlier figure.
WRK_THREADS = (2, 1)
RATIO_TARGET = 0.8
#: The service as configured (every single job to the pool, as before issue 19), and with
#: small jobs computed in the serving process (``inline_max_segments``), measured in turn.
DEFAULT_LABEL = "default (pool)"
INLINE_LABEL = "inline_max_segments=256"
#: Other loads, one round each: the ratio depends on how many requests coalesce into one
#: worker task. 64 is the default queue capacity, the most in flight without a 503.
SWEEP_CONNECTIONS = (8, 64)
SPEEDUP_TARGET = 20.0


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


def wrk(
    binary: str,
    url: str,
    *,
    script: Path | None = None,
    connections: int = WRK_CONNECTIONS,
    seconds: int = WRK_SECONDS,
    threads: int = 1,
) -> float:
    """Requests/s of ``url`` under wrk; every answer must be a 2xx."""
    command = [binary, f"-t{threads}", f"-c{connections}", f"-d{seconds}s", "--timeout", "60s"]
    if script is not None:
        command += ["-s", str(script)]
    report = subprocess.run([*command, url], capture_output=True, text=True, check=True).stdout
    match = re.search(r"Requests/sec:\s+([\d.]+)", report)
    if match is None:
        raise SystemExit(f"cannot read wrk's report:\n{report}")
    if "Non-2xx" in report or "Socket errors" in report:
        raise SystemExit(f"wrk saw errors:\n{report}")
    return float(match.group(1))


def post_script(directory: Path, name: str, body: bytes) -> Path:
    """A wrk script that POSTs ``body`` as JSON."""
    script = directory / f"{name}.lua"
    script.write_text(
        'wrk.method = "POST"\n'
        f"wrk.body = '{body.decode()}'\n"
        'wrk.headers["Content-Type"] = "application/json"\n'
    )
    return script


def measure_ratio(binary: str, urls: dict[str, str], scratch: Path) -> None:
    """``GET /healthz`` and ``POST /v1/approximate`` in turn on each service of ``urls``,
    ``RATIO_ROUNDS`` times, at each of ``WRK_THREADS``: this machine's speed drifts over
    seconds, so each round's ratio compares like with like (and the services take turns)."""
    script = post_script(scratch, "approximate", APPROXIMATE_BODY)
    for url in urls.values():
        httpx.post(f"{url}/v1/approximate", content=APPROXIMATE_BODY, timeout=30)  # warm
    for threads in WRK_THREADS:
        rounds: dict[str, list[tuple[float, float]]] = {label: [] for label in urls}
        for _ in range(RATIO_ROUNDS):
            for label, url in urls.items():
                healthz = wrk(binary, f"{url}/healthz", threads=threads)
                approximate = wrk(binary, f"{url}/v1/approximate", script=script, threads=threads)
                rounds[label].append((healthz, approximate))
        print(
            f"wrk -t{threads} -c{WRK_CONNECTIONS}, {WRK_SECONDS} s per run, pool of {POOL_SIZE}, "
            f"{RATIO_ROUNDS} rounds of healthz then approximate (paper spiral, 1e-3):"
        )
        for label, measured in rounds.items():
            for i, (healthz, approximate) in enumerate(measured, 1):
                print(
                    f"  {label:<22} round {i}: GET /healthz {healthz:8,.0f}/s  "
                    f"POST /v1/approximate {approximate:7,.0f}/s  ratio {approximate / healthz:.2f}"
                )
            ratio = statistics.median(a / h for h, a in measured)
            verdict = "meets" if ratio >= RATIO_TARGET else "misses"
            print(
                f"  {label:<22} median ratio approximate / healthz {ratio:.2f}   "
                f"({verdict} ≥ {RATIO_TARGET})"
            )
    url = urls[DEFAULT_LABEL]
    for connections in SWEEP_CONNECTIONS:
        healthz = wrk(binary, f"{url}/healthz", connections=connections)
        approximate = wrk(binary, f"{url}/v1/approximate", script=script, connections=connections)
        print(
            f"  {DEFAULT_LABEL}, -t1 at {connections:>2} connections, one round: GET /healthz "
            f"{healthz:8,.0f}/s  POST /v1/approximate {approximate:7,.0f}/s  "
            f"ratio {approximate / healthz:.2f}"
        )


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


def check_batch(url: str, body: bytes) -> float:
    """One batch through an httpx client, read and parsed in full: its 54 000 arcs are
    checked; the seconds it took (a Python client's view) are returned."""
    began = time.perf_counter()
    reply = httpx.post(
        f"{url}/v1/approximate/batch",
        content=body,
        headers={"content-type": "application/json"},
        timeout=120,
    )
    reply.raise_for_status()
    results = orjson.loads(reply.content)["results"]
    seconds = time.perf_counter() - began
    arcs = sum(r["result"]["stats"]["arc_count"] for r in results if r["status"] == "ok")
    assert arcs == BATCH_ARCS, arcs
    return seconds


def measure_batch(binary: str, url: str, scratch: Path) -> None:
    jobs = [{"spiral": SPIRAL, "tolerance": BATCH_TOLERANCE}] * BATCH_JOBS
    body = orjson.dumps({"jobs": jobs})
    python_client = min(check_batch(url, body) for _ in range(3))
    script = post_script(scratch, "batch", body)
    plain = plain_arcs_per_s()
    print(
        f"arcs/s, {BATCH_JOBS} paper spirals at {BATCH_TOLERANCE:g} per batch ({BATCH_ARCS} arcs):"
    )
    print(f"  {'plain Python, one spiral at a time':<40} {plain:12,.0f} arcs/s")
    for connections in (1, 2):
        batches = wrk(binary, f"{url}/v1/approximate/batch", script=script,
                      connections=connections)  # fmt: skip
        rate = batches * BATCH_ARCS
        label = f"wrk, {connections} batch(es) at a time"
        print(f"  {label:<40} {rate:12,.0f} arcs/s ({rate / plain:5.1f}× plain)")
    rate = BATCH_ARCS / python_client
    label = "httpx, one batch, JSON parsed too"
    print(f"  {label:<40} {rate:12,.0f} arcs/s ({rate / plain:5.1f}× plain)")
    print(f"  target: ≥ {SPEEDUP_TARGET:g}× plain (JSON made, sent and received in full)")


def main() -> None:
    binary = find_wrk()
    if binary is None:
        raise SystemExit(
            "wrk is not installed: `apt-get install wrk` (Debian/Ubuntu), then run again."
        )
    with (
        service(POOL_SIZE) as running,
        service(POOL_SIZE, {"inline_max_segments": "256"}) as inline,
        tempfile.TemporaryDirectory() as scratch,
    ):
        urls = {DEFAULT_LABEL: running.url, INLINE_LABEL: inline.url}
        measure_ratio(binary, urls, Path(scratch))
        measure_batch(binary, running.url, Path(scratch))


if __name__ == "__main__":
    main()
