"""What both clients are configured with, checked once."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from importlib.metadata import version

import httpx

from .retry import Retry

#: Where ``make run`` serves.
DEFAULT_URL = "http://127.0.0.1:8000"
USER_AGENT = f"arcspline-client/{version('arcspline')}"


@dataclass(frozen=True)
class ClientConfig:
    base_url: str
    timeout: httpx.Timeout
    retry: Retry
    max_concurrency: int
    batch_max_jobs: int
    batch_max_bytes: int

    @classmethod
    def of(
        cls,
        base_url: str,
        timeout_s: float,
        retry: Retry | None,
        max_concurrency: int,
        batch_max_jobs: int,
        batch_max_bytes: int,
    ) -> ClientConfig:
        if timeout_s <= 0 or max_concurrency < 1 or batch_max_jobs < 1 or batch_max_bytes < 1:
            raise ValueError(
                "timeout_s must be > 0; max_concurrency, batch_max_jobs, batch_max_bytes ≥ 1"
            )
        # A connection either opens quickly or not at all; the answer may take the job's time.
        timeout = httpx.Timeout(timeout_s, connect=min(10.0, timeout_s))
        return cls(
            base_url.rstrip("/"),
            timeout,
            retry or Retry(),
            max_concurrency,
            batch_max_jobs,
            batch_max_bytes,
        )

    def headers(self, extra: Mapping[str, str] | None) -> dict[str, str]:
        return {"User-Agent": USER_AGENT, **(extra or {})}
