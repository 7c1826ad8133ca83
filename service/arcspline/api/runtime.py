"""What the routes share: the settings, the metrics and the worker pool of one app."""

from __future__ import annotations

import asyncio
from dataclasses import dataclass, field

from fastapi import Request

from arcspline.geometry import Limits
from arcspline.settings import Settings
from arcspline.worker.jobs import Job, JobResult
from arcspline.worker.pool import Coalescer, PoolUnavailableError, WorkerPool

from .fast_path import Allowance
from .metrics import Metrics


@dataclass(eq=False)
class Runtime:
    """One per app; ``pool`` (and ``coalescer``) exist between lifespan startup and shutdown."""

    settings: Settings
    metrics: Metrics = field(init=False)
    pool: WorkerPool | None = None
    coalescer: Coalescer[Job, Limits, JobResult] | None = None
    #: JSON batch answers computed or sent at once: each holds up to the work budget
    #: (docs/deployment.md, "Memory"); two keep both workers busy while one is sent.
    json_answers: asyncio.Semaphore = field(default_factory=lambda: asyncio.Semaphore(2))
    #: The serving process's time left for small jobs computed in it (.fast_path).
    inline_allowance: Allowance = field(default_factory=Allowance)

    def __post_init__(self) -> None:
        self.metrics = Metrics(lambda: self.pool)

    def running_pool(self) -> WorkerPool:
        if self.pool is None:
            raise PoolUnavailableError("the worker pool is not running")
        return self.pool

    def singles(self) -> Coalescer[Job, Limits, JobResult]:
        """Where single /v1/approximate jobs go."""
        if self.coalescer is None:
            raise PoolUnavailableError("the worker pool is not running")
        return self.coalescer


def runtime_of(request: Request) -> Runtime:
    """The runtime of the app serving ``request``."""
    runtime: Runtime = request.app.state.runtime
    return runtime
