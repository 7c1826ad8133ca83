"""What the routes share: the settings, the metrics and the worker pool of one app."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Annotated

from fastapi import Depends, Request

from service.settings import Settings
from service.worker import PoolUnavailableError, WorkerPool

from .metrics import Metrics


@dataclass(eq=False)
class Runtime:
    """One per app; ``pool`` exists between lifespan startup and shutdown."""

    settings: Settings
    metrics: Metrics = field(init=False)
    pool: WorkerPool | None = None

    def __post_init__(self) -> None:
        self.metrics = Metrics(lambda: self.pool)

    def running_pool(self) -> WorkerPool:
        if self.pool is None:
            raise PoolUnavailableError("the worker pool is not running")
        return self.pool


def get_runtime(request: Request) -> Runtime:
    runtime: Runtime = request.app.state.runtime
    return runtime


RuntimeDep = Annotated[Runtime, Depends(get_runtime)]
