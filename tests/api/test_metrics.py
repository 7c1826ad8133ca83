"""GET /metrics: requests and latency by route, jobs, arcs, the pool, errors by kind."""

from __future__ import annotations

from typing import Any

import httpx
import pytest
from prometheus_client.parser import text_string_to_metric_families

pytestmark = pytest.mark.anyio


def _samples(text: str) -> dict[tuple[str, frozenset[tuple[str, str]]], float]:
    return {
        (s.name, frozenset(s.labels.items())): s.value
        for family in text_string_to_metric_families(text)
        for s in family.samples
    }


async def _scrape(client: httpx.AsyncClient) -> dict[tuple[str, frozenset[tuple[str, str]]], float]:
    response = await client.get("/metrics")
    assert response.status_code == 200
    assert response.headers["content-type"].startswith("text/plain")
    return _samples(response.text)


def _get(samples: dict[Any, float], name: str, **labels: str) -> float:
    return samples.get((name, frozenset(labels.items())), 0.0)


async def test_metrics_count_requests_jobs_arcs_and_errors(
    client: httpx.AsyncClient, paper_request: dict[str, Any]
) -> None:
    before = await _scrape(client)
    assert (await client.post("/v1/approximate", json=paper_request)).status_code == 200
    assert (await client.post("/v1/approximate", json={"tolerance": 1})).status_code == 422
    assert (await client.get("/nowhere")).status_code == 404
    after = await _scrape(client)

    def delta(name: str, **labels: str) -> float:
        return _get(after, name, **labels) - _get(before, name, **labels)

    route = {"route": "/v1/approximate", "method": "POST"}
    assert delta("arcspline_http_requests_total", **route, status="200") == 1
    assert delta("arcspline_http_requests_total", **route, status="422") == 1
    assert (
        delta("arcspline_http_requests_total", route="unmatched", method="GET", status="404") == 1
    )
    assert delta("arcspline_http_request_duration_seconds_count", **route) == 2
    assert delta("arcspline_jobs_total", endpoint="approximate", outcome="ok") == 1
    assert delta("arcspline_segments_produced_total", type="arc") == 12  # Table 1
    assert delta("arcspline_errors_total", kind="validation") == 1
    assert delta("arcspline_errors_total", kind="not_found") == 1


async def test_metrics_show_the_pool(client: httpx.AsyncClient) -> None:
    samples = await _scrape(client)
    assert _get(samples, "arcspline_pool_workers") == 2
    assert _get(samples, "arcspline_pool_ready") == 1
    assert _get(samples, "arcspline_pool_queue_depth") == 0
    assert _get(samples, "arcspline_pool_queue_capacity") == 16
    assert ("arcspline_pool_worker_restarts_total", frozenset()) in samples


async def test_metrics_show_the_process_and_the_runtime(client: httpx.AsyncClient) -> None:
    samples = await _scrape(client)
    names = {name for name, _ in samples}
    # prometheus_client's process (Linux /proc), platform and garbage-collector collectors.
    assert {"process_resident_memory_bytes", "process_open_fds", "process_cpu_seconds_total"} <= (
        names
    )
    assert any(name == "python_info" for name in names)
    assert _get(samples, "python_gc_collections_total", generation="0") >= 0
    assert ("python_gc_collections_total", frozenset({("generation", "0")})) in samples


async def test_metrics_count_preview_jobs(
    client: httpx.AsyncClient, paper_request: dict[str, Any]
) -> None:
    bad = {**paper_request, "tolerance": 1e-13}  # below what can be reached: refused by the job
    path = {"path": "M 0 0 L 10 0", "tolerance": 0.01}
    before = await _scrape(client)
    assert (await client.post("/v1/preview", json=paper_request)).status_code == 200
    assert (await client.post("/v1/preview", json=bad)).status_code == 422
    assert (await client.post("/v1/paths/preview", json=path)).status_code == 200
    after = await _scrape(client)

    def delta(name: str, **labels: str) -> float:
        return _get(after, name, **labels) - _get(before, name, **labels)

    assert delta("arcspline_jobs_total", endpoint="preview", outcome="ok") == 1
    assert delta("arcspline_jobs_total", endpoint="preview", outcome="error") == 1
    assert delta("arcspline_jobs_total", endpoint="paths_preview", outcome="ok") == 1
