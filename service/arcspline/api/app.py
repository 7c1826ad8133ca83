"""The app factory: routes, error handlers, middleware and the worker pool's lifespan."""

from __future__ import annotations

import logging
import random
import re
import uuid
from collections.abc import AsyncIterator
from contextlib import asynccontextmanager
from typing import Any

from asgi_correlation_id import CorrelationIdMiddleware
from fastapi import FastAPI
from fastapi.routing import APIRoute

from arcspline.settings import Settings, get_settings
from arcspline.worker.inline import InlinePool
from arcspline.worker.jobs import approximate_chunk
from arcspline.worker.pool import Coalescer, WorkerPool

from . import approximate, contract, docs, drawings, health, metrics, paths, preview
from .compression import Compression
from .errors import REQUEST_ID_HEADER, RawJSONResponse, install_error_handlers
from .lifecycle import LifecycleMiddleware
from .limits import BodyLimitMiddleware
from .metrics import MetricsMiddleware
from .runtime import Runtime


def request_id() -> str:
    """A random UUID4 as 32 hex digits, for requests that bring no ``X-Request-ID``.

    From the ``random`` module, not ``os.urandom`` (a system call per request): the id
    identifies a request in logs, it guards nothing.
    """
    return uuid.UUID(int=random.getrandbits(128), version=4).hex


#: A client's own request id (docs/http-api.md#request-ids): 1–128 printable ASCII
#: characters, no space — UUIDs, nginx's $request_id, W3C trace ids, `job-42/retry:1` — and
#: nothing that could forge or split a log line.
_CLIENT_ID = re.compile(r"[!-~]{1,128}")
log = logging.getLogger(__name__)


def client_request_id(given: str) -> str:
    """``given`` if it is an id safe to log and echo, else a new one: quietly (DEBUG), since
    a client that sends such ids sends them with every request."""
    if _CLIENT_ID.fullmatch(given):
        return given
    fresh = request_id()
    log.debug("X-Request-ID replaced by %s: not 1-128 printable ASCII characters", fresh)
    return fresh


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


class ArcsplineAPI(FastAPI):
    """FastAPI, with the OpenAPI document finished by :func:`.contract.finish` (the headers
    every response carries, and the document's security) once, when it is first built."""

    def openapi(self) -> dict[str, Any]:
        if self.openapi_schema is None:
            self.openapi_schema = contract.finish(super().openapi())
        return self.openapi_schema


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

    app = ArcsplineAPI(
        title="arcspline",
        version=contract.VERSION,
        description=contract.DESCRIPTION,
        license_info=contract.LICENSE,
        contact=contract.CONTACT,
        servers=contract.SERVERS,
        openapi_tags=contract.TAGS,
        lifespan=lifespan,
        default_response_class=RawJSONResponse,
        generate_unique_id_function=operation_id,
        # Not `POST /v1/approximate/` → 307 to http://<Host>/v1/approximate: a redirect to
        # wherever the Host header says. Such a path is a 404.
        redirect_slashes=False,
        # Served by .docs from the package's own copies of Swagger UI and ReDoc (no CDN).
        docs_url=None,
        redoc_url=None,
    )
    app.state.runtime = runtime
    install_error_handlers(app)
    for module in (approximate, paths, drawings, preview, health, metrics):
        app.include_router(module.router)
    docs.install(app)
    # The last added is the outermost: request id, metrics, body limit, lifecycle, gzip.
    # gzip level 1: 3.3x on answers at 120 MB/s, against 3.6x at 34 for 6 (docs/performance.md).
    app.add_middleware(Compression, minimum_size=1024, compresslevel=1)
    # Outside gzip (which holds a start message back), inside the metrics (which count its 499s).
    app.add_middleware(
        LifecycleMiddleware, retry_after_s=runtime.settings.retry_after_s,
        metrics=runtime.metrics, drain_timeout_s=runtime.settings.drain_timeout_s,
    )  # fmt: skip
    app.add_middleware(
        BodyLimitMiddleware, max_body_bytes=runtime.settings.max_body_bytes, metrics=runtime.metrics
    )
    app.add_middleware(MetricsMiddleware, metrics=runtime.metrics)
    app.add_middleware(
        CorrelationIdMiddleware, header_name=REQUEST_ID_HEADER, generator=request_id,
        validator=None, transformer=client_request_id,  # (its validator warns per request)
    )  # fmt: skip
    return app
