"""A running service for the benchmarks: ``python -m arcspline`` (or another module given by
``ARCSPLINE_BENCH_MODULE``, with ``ARCSPLINE_BENCH_PYTHONPATH`` prepended to its path, to
measure an older checkout beside this one) in a subprocess on a free port."""

from __future__ import annotations

import os
import signal
import socket
import subprocess
import sys
import time
from collections.abc import Iterator, Mapping
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path

import httpx

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from tests.support.processes import worker_pids

ROOT = Path(__file__).resolve().parents[1]


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        port: int = s.getsockname()[1]
        return port


@dataclass
class Service:
    process: subprocess.Popen[bytes]
    url: str
    #: Seconds from the process's start to its first 200 from /readyz.
    ready_after_s: float

    def worker_pids(self) -> list[int]:
        return worker_pids(self.process.pid)


def wait_ready(url: str, process: subprocess.Popen[bytes], timeout_s: float = 60.0) -> None:
    """Poll /readyz every 5 ms until it answers 200."""
    deadline = time.monotonic() + timeout_s
    with httpx.Client(timeout=2) as client:
        while True:
            try:
                if client.get(f"{url}/readyz").status_code == 200:
                    return
            except httpx.TransportError:
                pass
            if process.poll() is not None or time.monotonic() > deadline:
                raise SystemExit("the server did not become ready")
            time.sleep(0.005)


@contextmanager
def service(pool_size: int = 2, settings: Mapping[str, str] | None = None) -> Iterator[Service]:
    """The service with a pool of ``pool_size`` workers and ``settings`` (by field name),
    until the block ends."""
    port = _free_port()
    env = {k: v for k, v in os.environ.items() if not k.startswith("ARCSPLINE_")}
    env["ARCSPLINE_POOL_SIZE"] = str(pool_size)
    env.update({f"ARCSPLINE_{name.upper()}": value for name, value in (settings or {}).items()})
    env["ARCSPLINE_LOG_LEVEL"] = "warning"
    module = os.environ.get("ARCSPLINE_BENCH_MODULE", "arcspline")
    if path := os.environ.get("ARCSPLINE_BENCH_PYTHONPATH"):
        env["PYTHONPATH"] = os.pathsep.join([path, env.get("PYTHONPATH", "")])
    began = time.monotonic()
    process = subprocess.Popen(
        [sys.executable, "-m", module, "--host", "127.0.0.1", "--port", str(port)],
        cwd=os.environ.get("ARCSPLINE_BENCH_PYTHONPATH", ROOT),
        env=env,
    )
    url = f"http://127.0.0.1:{port}"
    try:
        wait_ready(url, process)
        yield Service(process, url, time.monotonic() - began)
    finally:
        process.send_signal(signal.SIGTERM)
        process.wait(timeout=60)
