"""The app factory: routes, error handlers, middleware and the worker pool's lifespan."""

from __future__ import annotations

import random
import uuid
from collections.abc import AsyncIterator
from contextlib import asynccontextmanager

from asgi_correlation_id import CorrelationIdMiddleware
from fastapi import FastAPI
from fastapi.routing import APIRoute

from arcspline.settings import Settings, get_settings
from arcspline.worker.inline import InlinePool
from arcspline.worker.jobs import approximate_chunk
from arcspline.worker.pool import Coalescer, WorkerPool

from . import approximate, drawings, health, metrics, paths, preview
from .errors import RawJSONResponse, install_error_handlers
from .limits import BodyLimitMiddleware
from .metrics import MetricsMiddleware
from .runtime import Runtime

#: Version of the HTTP contract (``info.version`` of the OpenAPI document).
API_VERSION = "1.0.0"

DESCRIPTION = """\
Approximates planar cubic Bézier spirals by G1 arc splines within a tolerance
(D.J. Walton, D.S. Meek, *Approximation of a planar cubic Bézier spiral by circular arcs*,
J. Comput. Appl. Math. 75 (1996) 47–56), for CNC tool paths.

Every error is RFC 9457 problem details (`application/problem+json`)."""


def request_id() -> str:
    """A random UUID4 as 32 hex digits, for requests that bring no ``X-Request-ID``.

    From the ``random`` module, not ``os.urandom`` (a system call per request): the id
    identifies a request in logs, it guards nothing.
    """
    return uuid.UUID(int=random.getrandbits(128), version=4).hex


def operation_id(route: APIRoute) -> str:
    """Stable operation ids: the route's name, which each route sets explicitly."""
    return route.name


def _new_pool(config: Settings) -> WorkerPool:
    if config.start_method == "inline":
        return InlinePool(
            config.pool_size, config.queue_capacity, retry_after_s=config.retry_after_s
        )
    return WorkerPool(
        config.pool_size,
        config.queue_capacity,
        start_method=config.start_method,
        retry_after_s=config.retry_after_s,
    )


def create_app(settings: Settings | None = None) -> FastAPI:
    """A new app; ``settings`` default to the process-wide ones from the environment."""
    runtime = Runtime(settings or get_settings())

    @asynccontextmanager
    async def lifespan(_app: FastAPI) -> AsyncIterator[None]:
        config = runtime.settings
        pool = _new_pool(config)
        await pool.start()
        runtime.pool = pool
        runtime.coalescer = Coalescer(
            pool,
            approximate_chunk,
            config.limits,
            time_limit_s=config.job_time_limit_s,
            max_items=config.coalesce_max_jobs,
        )
        try:
            yield
        finally:
            # Uvicorn has already waited for in-flight requests (graceful shutdown); this
            # waits for any task still running, then stops the workers.
            await pool.drain(config.drain_timeout_s)
            runtime.pool = runtime.coalescer = None

    app = FastAPI(
        title="arcspline",
        version=API_VERSION,
        description=DESCRIPTION,
        lifespan=lifespan,
        default_response_class=RawJSONResponse,
        generate_unique_id_function=operation_id,
        redoc_url=None,
    )
    app.state.runtime = runtime
    install_error_handlers(app)
    for module in (approximate, paths, drawings, preview, health, metrics):
        app.include_router(module.router)
    # The last added is the outermost: request id, then metrics, then the body limit.
    app.add_middleware(
        BodyLimitMiddleware, max_body_bytes=runtime.settings.max_body_bytes, metrics=runtime.metrics
    )
    app.add_middleware(MetricsMiddleware, metrics=runtime.metrics)
    app.add_middleware(CorrelationIdMiddleware, header_name="X-Request-ID", generator=request_id)
    return app
