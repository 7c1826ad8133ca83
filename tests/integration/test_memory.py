"""Memory and liveness of a real server under the largest batches (docs/deployment.md,
"Memory"): the hostile batch is refused before memory is at risk, and /healthz answers
during the largest batch allowed."""

from __future__ import annotations

import threading
import time
from pathlib import Path
from typing import Any

import httpx

from tests.support.processes import memory_kib, parents
from tests.support.server import running_server

SPIRAL: dict[str, Any] = {
    "start": [1.5, 3.0],
    "start_tangent": [1.0, 0.0],
    "turn_angle_deg": 51.34,
    "end_curvature": 0.41574,
}
#: Just above the paper spiral's tolerance floor (5.6525e-10 = 1e-10 × its chord): 1,278 arcs,
#: 558 KB of JSON each.
FLOOR = 5.66e-10
#: The server, its forkserver and workers together, in RSS (shared pages counted in each, so
#: more than the pod is charged): 270 MiB at rest; the pod's limit is 512 MiB (docs/deployment.md,
#: "Memory"). Today's code peaked at 2.4 GiB on the hostile batch.
MAX_TREE_RSS_MIB = 512
#: /healthz must answer well inside the liveness probe's 3 s timeout.
MAX_HEALTHZ_S = 1.0


def _rss_mib(pid: int) -> float:
    return (memory_kib(pid, "VmRSS") or 0) / 1024


def _pss_mib(pid: int) -> float:
    """Proportional set size, as the pod's memory cgroup charges the tree."""
    return (memory_kib(pid, "Pss") or 0) / 1024


def _tree(pid: int) -> set[int]:
    """``pid`` and all its descendants (forkserver, workers)."""
    known = parents()
    tree = {pid}
    while grown := {p for p, parent in known.items() if parent in tree} - tree:
        tree |= grown
    return tree


class _Watch:
    """While open: the largest RSS of the server's process tree, and /healthz latencies."""

    def __init__(self, url: str, pid: int) -> None:
        self.url, self.pid = url, pid
        self.peak_mib = 0.0
        self.peak_pss_mib = 0.0
        self.latencies_s: list[float] = []
        self._stop = threading.Event()
        self._threads = [threading.Thread(target=self._rss), threading.Thread(target=self._probe)]

    def __enter__(self) -> _Watch:
        for thread in self._threads:
            thread.start()
        return self

    def __exit__(self, *_: object) -> None:
        time.sleep(0.2)
        self._stop.set()
        for thread in self._threads:
            thread.join()

    def _rss(self) -> None:
        while not self._stop.is_set():
            tree = _tree(self.pid)
            self.peak_mib = max(self.peak_mib, sum(map(_rss_mib, tree)))
            self.peak_pss_mib = max(self.peak_pss_mib, sum(map(_pss_mib, tree)))
            time.sleep(0.01)

    def _probe(self) -> None:
        with httpx.Client(timeout=30) as client:
            while not self._stop.is_set():
                start = time.perf_counter()
                try:
                    ok = client.get(f"{self.url}/healthz").status_code == 200
                except httpx.HTTPError:
                    ok = False
                # A failed probe counts as never answered.
                self.latencies_s.append(time.perf_counter() - start if ok else float("inf"))
                time.sleep(0.02)


def test_the_hostile_batch_is_refused_before_memory_is_at_risk(tmp_path: Path) -> None:
    """1,000 × the paper's spiral at its floor: 558 MB of JSON, and 1.1 GB of server RSS
    before the work budget."""
    jobs = [{"spiral": SPIRAL, "tolerance": FLOOR}] * 1000
    with running_server(tmp_path, pool_size=2) as server:
        with _Watch(server.url, server.process.pid) as watch:
            response = httpx.post(
                f"{server.url}/v1/approximate/batch", json={"jobs": jobs}, timeout=300
            )
        assert response.status_code == 413, response.text[:300]
        assert response.headers["content-type"] == "application/problem+json"
        problem = response.json()
        assert problem["type"] == "urn:arcspline:problem:work-too-large"
        assert "raise the tolerance" in problem["detail"]
    assert watch.peak_mib < MAX_TREE_RSS_MIB
    assert max(watch.latencies_s) < MAX_HEALTHZ_S


def test_liveness_and_memory_during_the_largest_batch_allowed(tmp_path: Path) -> None:
    """As many 1,278-arc spirals as the default budget (50,000 segments) allows: 39, 22 MB
    of JSON."""
    jobs = [{"spiral": SPIRAL, "tolerance": FLOOR}] * 39
    with running_server(tmp_path, pool_size=2) as server:
        with _Watch(server.url, server.process.pid) as watch:
            response = httpx.post(
                f"{server.url}/v1/approximate/batch", json={"jobs": jobs}, timeout=300
            )
        assert response.status_code == 200, response.text[:300]
        assert len(response.json()["results"]) == 39
    assert watch.peak_mib < MAX_TREE_RSS_MIB
    assert max(watch.latencies_s) < MAX_HEALTHZ_S


def _ellipses(count: int) -> bytes:
    """An SVG of ``count`` small ellipses: about 24 output segments each at tolerance 0.01,
    some 11 KB of JSON."""
    shapes = "".join(
        f'<ellipse cx="{(i % 250) * 10}" cy="{(i // 250) * 10}" rx="4" ry="2"/>'
        for i in range(count)
    )
    return (
        '<svg xmlns="http://www.w3.org/2000/svg" width="3000mm" height="3000mm" '
        f'viewBox="0 0 3000 3000">{shapes}</svg>'
    ).encode()


def _drawings_at_once(url: str, svg: bytes, count: int) -> list[httpx.Response]:
    responses: list[httpx.Response] = []

    def post() -> None:
        headers = {"Content-Type": "image/svg+xml"}
        answer = httpx.post(
            f"{url}/v1/drawings/approximate", content=svg, params={"tolerance": 0.01},
            headers=headers, timeout=300,
        )  # fmt: skip
        responses.append(answer)

    threads = [threading.Thread(target=post) for _ in range(count)]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    return responses


def test_two_of_the_largest_drawings_allowed_fit_in_the_pod(tmp_path: Path) -> None:
    """Two drawings of ~49,000 output segments (21.7 MB of JSON each) at once, one per
    worker. With the old limit (200,000 segments) two drawings of 195,000 were answered and
    took the tree to 1,047 MiB of PSS; they are refused now."""
    with running_server(tmp_path, pool_size=2) as server:
        with _Watch(server.url, server.process.pid) as watch:
            answers = _drawings_at_once(server.url, _ellipses(2_000), 2)
            too_large = _drawings_at_once(server.url, _ellipses(8_000), 2)
        assert [r.status_code for r in answers] == [200, 200], answers[0].text[:300]
        assert all(r.json()["stats"]["segment_count"] > 45_000 for r in answers)
        assert [r.status_code for r in too_large] == [422, 422], too_large[0].text[:300]
    assert watch.peak_pss_mib < MAX_TREE_RSS_MIB
    assert max(watch.latencies_s) < MAX_HEALTHZ_S
