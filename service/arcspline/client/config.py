"""What both clients are configured with, checked once."""

from __future__ import annotations

import ipaddress
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
        """The headers of every request: ``extra`` over the client's own."""
        extra = extra or {}
        own = {"User-Agent": USER_AGENT}
        given = {name.lower() for name in extra}
        if is_loopback(self.base_url) and "accept-encoding" not in given:
            # gzip saves no time on this machine's own network and costs both ends CPU: a
            # 10,000-spiral batch took 25 % longer with it (docs/performance.md, issue 19).
            own["Accept-Encoding"] = "identity"
        return {**own, **extra}


def is_loopback(base_url: str) -> bool:
    """Whether ``base_url`` names this machine (``localhost``, 127.0.0.0/8, ``::1``)."""
    host = httpx.URL(base_url).host
    if host == "localhost":
        return True
    try:
        return ipaddress.ip_address(host).is_loopback
    except ValueError:  # a name
        return False
