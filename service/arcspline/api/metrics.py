"""Prometheus metrics: requests and latency by route, jobs, arcs produced, the pool, errors,
and the serving process (memory, CPU, open files, garbage collections).

Each app has its own registry (so several apps can live in one test process); the pool's
gauges are read when scraped, not pushed.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Iterator
from typing import Any

from fastapi import APIRouter, Request
from prometheus_client import (
    CollectorRegistry,
    Counter,
    GCCollector,
    Histogram,
    PlatformCollector,
    ProcessCollector,
    disable_created_metrics,
)
from prometheus_client.exposition import choose_encoder
from prometheus_client.metrics_core import CounterMetricFamily, GaugeMetricFamily, Metric
from prometheus_client.registry import Collector
from starlette.responses import Response
from starlette.types import ASGIApp, Message, Receive, Scope, Send

from arcspline.serving.refusals import REFUSED
from arcspline.worker.pool import WorkerPool

from .errors import ALL_KINDS, problem_responses
from .routing import LeanRoute

# The *_created series (a timestamp per label set) double the text for no use here.
disable_created_metrics()  # type: ignore[no-untyped-call]

#: Latency buckets (seconds): from a cached-size request to a batch near its time limit.
LATENCY_BUCKETS_S = (0.001, 0.0025, 0.005, 0.01, 0.025, 0.05, 0.1, 0.25, 0.5, 1, 2.5, 5, 10, 30)


class PoolCollector(Collector):
    """The pool's state at scrape time."""

    def __init__(self, pool: Callable[[], WorkerPool | None]) -> None:
        self._pool = pool

    def collect(self) -> Iterator[Metric]:
        pool = self._pool()
        if pool is None:
            return
        gauges = {
            "workers": ("Worker processes in the pool.", pool.size),
            "in_flight": ("Pool tasks admitted (running or waiting).", pool.in_flight),
            "running": ("Pool tasks running in a worker.", pool.running),
            "queue_depth": ("Pool tasks waiting for a worker.", pool.queue_depth),
            "queue_capacity": ("Most pool tasks admitted at once.", pool.capacity),
            "ready": ("1 when the pool accepts work.", int(pool.ready)),
        }
        for name, (doc, value) in gauges.items():
            yield GaugeMetricFamily(f"arcspline_pool_{name}", doc, value=value)
        yield CounterMetricFamily(
            "arcspline_pool_worker_restarts",
            "Worker processes replaced (after a death or a time limit).",
            value=pool.restarts,
        )


class RefusalCollector(Collector):
    """The connections the serving process's bounds refused (``serving/refusals.py``)."""

    def collect(self) -> Iterator[Metric]:
        family = CounterMetricFamily(
            "arcspline_connections_refused",
            "Connections refused or dropped by their bounds (header size and time, body "
            "time, malformed HTTP, the connection cap, answers left unread), by kind.",
            labels=["kind"],
        )
        for kind, count in sorted(REFUSED.items()):
            family.add_metric([kind], count)
        yield family


class Metrics:
    """The app's metrics and the registry that exposes them."""

    def __init__(self, pool: Callable[[], WorkerPool | None]) -> None:
        self.registry = CollectorRegistry()
        self.requests = Counter(
            "arcspline_http_requests",
            "HTTP requests by route, method and status.",
            ["route", "method", "status"],
            registry=self.registry,
        )
        self.latency = Histogram(
            "arcspline_http_request_duration_seconds",
            "HTTP request latency by route and method.",
            ["route", "method"],
            buckets=LATENCY_BUCKETS_S,
            registry=self.registry,
        )
        self.jobs = Counter(
            "arcspline_jobs",
            "Approximation jobs by endpoint and outcome (ok or error).",
            ["endpoint", "outcome"],
            registry=self.registry,
        )
        self.segments = Counter(
            "arcspline_segments_produced",
            "Segments of the arc splines returned, by type (arc or line).",
            ["type"],
            registry=self.registry,
        )
        self.errors = Counter(
            "arcspline_errors",
            "Problems answered (requests and batch jobs), by kind.",
            ["kind"],
            registry=self.registry,
        )
        for kind in ALL_KINDS:
            self.errors.labels(kind)
        self._arcs = self.segments.labels("arc")
        self._lines = self.segments.labels("line")
        self.registry.register(PoolCollector(pool))
        self.registry.register(RefusalCollector())
        # What prometheus_client puts on its default registry (memory, CPU, open files,
        # the Python version, garbage collections): this registry is the app's own.
        ProcessCollector(registry=self.registry)
        PlatformCollector(registry=self.registry)
        GCCollector(registry=self.registry)
        # The labelled children, found once: labels() validates, builds a key and takes a
        # lock on every call, a few microseconds per request on the hot path.
        self._children: dict[tuple[Any, ...], Any] = {}

    def _child(self, metric: Counter | Histogram, *labels: str) -> Any:
        key = (id(metric), *labels)
        child = self._children.get(key)
        if child is None:
            child = self._children[key] = metric.labels(*labels)
        return child

    def request(self, route: str, method: str, status: int, seconds: float) -> None:
        self._child(self.requests, route, method, str(status)).inc()
        self._child(self.latency, route, method).observe(seconds)

    def error(self, kind: str) -> None:
        self._child(self.errors, kind).inc()

    def job_ok(self, endpoint: str, arcs: int, lines: int, count: int = 1) -> None:
        self._child(self.jobs, endpoint, "ok").inc(count)
        self._arcs.inc(arcs)
        self._lines.inc(lines)

    def job_error(self, endpoint: str, count: int = 1) -> None:
        self._child(self.jobs, endpoint, "error").inc(count)


class MetricsMiddleware:
    """Counts and times every HTTP request by its route template (pure ASGI)."""

    def __init__(self, app: ASGIApp, metrics: Metrics) -> None:
        self.app = app
        self.metrics = metrics

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        if scope["type"] != "http":
            await self.app(scope, receive, send)
            return
        started = time.perf_counter()
        status = 500

        async def send_and_note(message: Message) -> None:
            nonlocal status
            if message["type"] == "http.response.start":
                status = message["status"]
            await send(message)

        try:
            await self.app(scope, receive, send_and_note)
        finally:
            route = scope.get("route")
            path = getattr(route, "path", None) or "unmatched"
            self.metrics.request(path, scope["method"], status, time.perf_counter() - started)


router = APIRouter(tags=["operations"], route_class=LeanRoute)


@router.get(
    "/metrics",
    name="metrics",
    summary="Prometheus metrics",
    response_class=Response,
    responses={
        200: {
            "description": "The metrics, as Prometheus text or OpenMetrics",
            "content": {
                "text/plain": {"schema": {"type": "string"}},
                "application/openmetrics-text": {"schema": {"type": "string"}},
            },
        },
        # The body limit applies to every request, before routing (even a GET's body).
        **problem_responses(413),
    },
)
async def metrics(request: Request) -> Response:
    """Prometheus text format (OpenMetrics when the scraper asks for it)."""
    encoder, content_type = choose_encoder(request.headers.get("accept", ""))
    registry = request.app.state.runtime.metrics.registry
    return Response(encoder(registry), media_type=content_type)
