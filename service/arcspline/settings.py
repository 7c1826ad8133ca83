"""The one settings object: environment variables prefixed ``ARCSPLINE_``, read once.

Every setting has a default that suits a container with a few CPUs; the README lists them.
Command-line flags of ``python -m service`` (``--host``, ``--port``) override the
environment for the address only.
"""

from __future__ import annotations

import os
from functools import lru_cache
from typing import Literal

from pydantic import Field, PositiveFloat, PositiveInt, model_validator
from pydantic_settings import BaseSettings, SettingsConfigDict

from arcspline.geometry import DEFAULT_LIMITS, Limits
from arcspline.geometry.limits import MAX_SEGMENTS

LogLevel = Literal["critical", "error", "warning", "info", "debug"]
StartMethod = Literal["forkserver", "spawn", "inline"]


def available_cpus() -> int:
    """CPUs this process may run on (its affinity mask, which containers narrow)."""
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:  # pragma: no cover - platforms without affinity masks
        return os.cpu_count() or 1


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
    batch_max_jobs: PositiveInt = Field(
        default=1000, description="Most jobs in one batch (413 beyond)."
    )
    batch_chunk_min_jobs: PositiveInt = Field(
        default=32, description="Fewest jobs worth a pool task of their own when a batch is split."
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
    drawing_max_segments: PositiveInt = Field(
        default=200_000,
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

    @model_validator(mode="after")
    def _no_unknown_variables(self) -> Settings:
        # A misspelt variable (ARCSPLINE_POOL_SIZ) must not be silently ignored.
        prefix = "ARCSPLINE_"
        known = {prefix + name.upper() for name in type(self).model_fields}
        unknown = sorted(
            k for k in os.environ if k.upper().startswith(prefix) and k.upper() not in known
        )
        if unknown:
            raise ValueError(f"unknown settings in the environment: {', '.join(unknown)}")
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
