"""The one settings object: environment variables prefixed ``ARCSPLINE_``, read once.

Every setting has a default that suits a container with a few CPUs; the README lists them.
Command-line flags of ``python -m service`` (``--host``, ``--port``) override the
environment for the address only.
"""

from __future__ import annotations

import difflib
import logging
import os
import re
from functools import lru_cache
from typing import Any, Literal

from pydantic import Field, PositiveFloat, PositiveInt, model_validator
from pydantic.fields import FieldInfo
from pydantic_settings import (
    BaseSettings,
    EnvSettingsSource,
    PydanticBaseSettingsSource,
    SettingsConfigDict,
)

from arcspline.geometry import DEFAULT_LIMITS, Limits
from arcspline.geometry.limits import MAX_SEGMENTS

log = logging.getLogger(__name__)

ENV_PREFIX = "ARCSPLINE_"
LogLevel = Literal["critical", "error", "warning", "info", "debug"]
StartMethod = Literal["forkserver", "spawn", "inline"]


def available_cpus() -> int:
    """CPUs this process may run on (its affinity mask, which containers narrow)."""
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:  # pragma: no cover - platforms without affinity masks
        return os.cpu_count() or 1


#: The variables Kubernetes sets in every pod for a Service named ``arcspline`` (service links,
#: kubernetes.io/docs/concepts/services-networking/service/#environment-variables):
#: ``ARCSPLINE_SERVICE_HOST``, ``ARCSPLINE_SERVICE_PORT[_<NAME>]``,
#: ``ARCSPLINE_PORT=tcp://10.0.0.1:8000`` and ``ARCSPLINE_PORT_8000_TCP[_PROTO|_PORT|_ADDR]``.
_SERVICE_LINK_NAME = re.compile(
    ENV_PREFIX + r"(SERVICE_HOST|SERVICE_PORT(_\w+)?|PORT_\d+_(TCP|UDP|SCTP)(_(PROTO|PORT|ADDR))?)"
)
_SERVICE_LINK_URL = re.compile(r"(tcp|udp|sctp)://\S+:\d+", re.IGNORECASE)


def is_service_link(name: str, value: str | None) -> bool:
    """Whether the variable ``name`` (upper case) is one Kubernetes sets for a Service."""
    if name == ENV_PREFIX + "PORT":
        return value is not None and _SERVICE_LINK_URL.fullmatch(value) is not None
    return _SERVICE_LINK_NAME.fullmatch(name) is not None


def _suggestion(name: str, known: set[str]) -> str:
    close = difflib.get_close_matches(name, known, n=1)
    return f" (did you mean {close[0]}?)" if close else ""


class _EnvWithoutServiceLinks(EnvSettingsSource):
    """The environment, less ``ARCSPLINE_PORT`` when it is a service link's URL: the port
    then keeps its default (the container port the Service targets)."""

    def get_field_value(self, field: FieldInfo, field_name: str) -> tuple[Any, str, bool]:
        value, key, complex_ = super().get_field_value(field, field_name)
        name = ENV_PREFIX + field_name.upper()
        if field_name == "port" and isinstance(value, str) and is_service_link(name, value):
            log.debug("ignoring %s=%s: a Kubernetes service link, not a port", name, value)
            return None, key, complex_
        return value, key, complex_


class Settings(BaseSettings):
    """Service configuration; each field is read from ``ARCSPLINE_<FIELD NAME>``."""

    model_config = SettingsConfigDict(
        env_prefix="ARCSPLINE_", extra="forbid", frozen=True, validate_default=True
    )

    host: str = Field(default="127.0.0.1", description="Address to listen on.")
    port: int = Field(default=8000, ge=0, le=65535, description="TCP port to listen on.")
    pool_size: PositiveInt = Field(
        default_factory=available_cpus,
        description="Worker processes computing approximations (default: CPUs available).",
    )
    queue_capacity: PositiveInt = Field(
        default=64,
        description="Pool tasks admitted at once, running or waiting; beyond it: 503.",
    )
    job_time_limit_s: PositiveFloat = Field(
        default=30.0,
        description="Time limit of one /v1/approximate or /v1/preview job (504 beyond); "
        "k jobs that share a worker task share k times the limit.",
    )
    batch_time_limit_s: PositiveFloat = Field(
        default=120.0, description="Time limit of a whole /v1/approximate/batch request."
    )
    # Small tasks keep jobs queued for the next worker to come free instead of one worker
    # taking them all while the other idles: measured over HTTP (wrk, 32 connections, pool
    # of 2, paper spiral at 1e-3), 8 gave approximate/healthz 0.64-0.70 where 32 gave 0.50-0.52
    # (and 0.65 against 0.69 at 64 connections).
    coalesce_max_jobs: PositiveInt = Field(
        default=8,
        description="Most single jobs sent to a worker as one task while all are busy.",
    )
    # Off by default: it cuts a lone request's latency, but under load the serving process is
    # the bottleneck and a worker task shared by queued jobs costs it less (wrk, 32
    # connections: 0.58x /healthz on, 0.68x off; docs/performance.md, issue 19).
    inline_max_segments: int = Field(
        default=0,
        ge=0,
        le=MAX_SEGMENTS,
        description="Largest single /v1/approximate job computed in the serving process "
        "instead of a worker, in output segments (JSON answers by 'subdivide' only; the core "
        "stops at this count and the job goes to the pool; at most a tenth of the process's "
        "time); 0: every job goes to the pool.",
    )
    batch_max_jobs: PositiveInt = Field(
        default=1000, description="Most jobs in one batch (413 beyond)."
    )
    batch_chunk_min_jobs: PositiveInt = Field(
        default=32, description="Fewest jobs worth a pool task of their own when a batch is split."
    )
    # Sized to the pod's memory limit: docs/deployment.md, "Memory" (the arithmetic).
    batch_max_segments: PositiveInt = Field(
        default=50_000,
        description="Work budget of one batch: most output segments of all its jobs together "
        "in a JSON answer (413 work_too_large beyond), and of one chunk of a streamed one.",
    )
    max_body_bytes: PositiveInt = Field(
        default=4 * 1024 * 1024, description="Largest request body accepted (413 beyond)."
    )
    max_segments: PositiveInt = Field(
        default=DEFAULT_LIMITS.max_segments,
        le=MAX_SEGMENTS,
        description="Most segments in one arc spline (422 beyond).",
    )
    path_max_segments: PositiveInt = Field(
        default=50_000,
        le=MAX_SEGMENTS,
        description="Most output segments for one path, all subpaths together (422 beyond).",
    )
    path_max_input_segments: PositiveInt = Field(
        default=20_000, description="Most input segments in one path (422 beyond)."
    )
    # One answer's segments are held some 2.7 KiB each at the peak (rows, JSON, its pickle,
    # in the worker and the server; docs/deployment.md "Memory"): 200 000 took one drawing
    # to 688 MiB, over the pod's 512; at 50 000, two at once peak at 394 MiB.
    drawing_max_segments: PositiveInt = Field(
        default=50_000,
        le=MAX_SEGMENTS,
        description="Most segments of one drawing, as read and as output (422 beyond).",
    )
    drawing_max_elements: PositiveInt = Field(
        default=100_000, description="Most elements (XML elements, DXF entities) in a drawing."
    )
    drawing_max_depth: PositiveInt = Field(
        default=64, description="Deepest nesting of groups, uses and block references."
    )
    min_relative_tolerance: PositiveFloat = Field(
        default=DEFAULT_LIMITS.min_relative_tolerance,
        lt=1.0,
        description="Smallest tolerance accepted, as a fraction of the spiral's chord.",
    )
    retry_after_s: PositiveInt = Field(
        default=1, description="Retry-After (seconds) sent with 503 when the queue is full."
    )
    drain_timeout_s: PositiveInt = Field(
        default=30, description="On SIGTERM, how long in-flight requests may take to finish (s)."
    )
    start_method: StartMethod = Field(
        default="forkserver",
        description="How worker processes start (never fork: threads exist); 'inline': no "
        "worker processes, jobs run in threads of the serving process without time limits "
        "(the command line's local mode).",
    )
    log_level: LogLevel = Field(default="info", description="Log level of the service and uvicorn.")
    access_log: bool = Field(default=False, description="Log every request (costs throughput).")
    # Connections (serving/protocol.py, docs/deployment.md "Connections").
    max_connections: PositiveInt = Field(
        default=4096,
        description="Most client connections open at once, lowered to fit the open-file "
        "limit; beyond it the longest-idle connection is closed, or 503 if none is idle.",
    )
    max_header_bytes: PositiveInt = Field(
        default=64 * 1024,
        description="Largest request line and headers of a request (431 beyond).",
    )
    header_timeout_s: PositiveFloat = Field(
        default=10.0,
        description="Time for a request's line and headers to arrive (408 beyond).",
    )
    body_timeout_s: PositiveFloat = Field(
        default=60.0, description="Time for a request's body to arrive after its headers (408)."
    )
    send_timeout_s: PositiveFloat = Field(
        default=30.0,
        description="Longest a client may leave the answer unread, its socket's buffer full, "
        "before the connection is dropped (and the answer's memory freed).",
    )
    keep_alive_timeout_s: PositiveInt = Field(
        default=5, description="How long an idle keep-alive connection stays open (s)."
    )

    @classmethod
    def settings_customise_sources(
        cls,
        settings_cls: type[BaseSettings],
        init_settings: PydanticBaseSettingsSource,
        env_settings: PydanticBaseSettingsSource,
        dotenv_settings: PydanticBaseSettingsSource,
        file_secret_settings: PydanticBaseSettingsSource,
    ) -> tuple[PydanticBaseSettingsSource, ...]:
        env = _EnvWithoutServiceLinks(settings_cls)
        return (init_settings, env, dotenv_settings, file_secret_settings)

    @model_validator(mode="after")
    def _no_unknown_variables(self) -> Settings:
        # A misspelt variable (ARCSPLINE_POOL_SIZ) must not be silently ignored, nor stop
        # the service: one WARNING names them all.
        known = {ENV_PREFIX + name.upper() for name in type(self).model_fields}
        unknown = []
        for name, value in sorted(os.environ.items()):
            upper = name.upper()
            if not upper.startswith(ENV_PREFIX) or upper in known:
                continue
            if is_service_link(upper, value):
                log.debug("ignoring %s: a Kubernetes service link, not a setting", name)
            else:
                unknown.append(name + _suggestion(upper, known))
        if unknown:
            log.warning("unknown settings in the environment, ignored: %s", ", ".join(unknown))
        return self

    @property
    def limits(self) -> Limits:
        """The geometry core's limits, as configured."""
        return Limits(
            max_segments=self.max_segments, min_relative_tolerance=self.min_relative_tolerance
        )

    @property
    def path_limits(self) -> Limits:
        """The core's limits for a path: its output segments all together."""
        return Limits(
            max_segments=self.path_max_segments,
            min_relative_tolerance=self.min_relative_tolerance,
        )

    @property
    def drawing_limits(self) -> Limits:
        """The core's limits for a drawing: its output segments all together."""
        return Limits(
            max_segments=self.drawing_max_segments,
            min_relative_tolerance=self.min_relative_tolerance,
        )


@lru_cache(maxsize=1)
def get_settings() -> Settings:
    """The process-wide settings, read from the environment on first use."""
    return Settings()
