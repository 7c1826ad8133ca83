"""When to try a request again, and after how long: the service's ``Retry-After`` on 503
(queue full, workers restarting) and 429, else exponential backoff with jitter; connection
failures likewise. Every operation of the service is a pure function of its request, so
trying again is always safe."""

from __future__ import annotations

import email.utils
import random
import time
from dataclasses import dataclass

import httpx

from .errors import ServiceError

#: Statuses worth another try: the service (or a proxy before it) is busy, not the request
#: wrong. A 504 is the request's own time limit: it would take as long again.
RETRY_STATUSES = frozenset({429, 502, 503})


@dataclass(frozen=True)
class Retry:
    """``attempts`` in all (1: never retry); waits ``backoff_s · 2^k`` (k = 0, 1, ...) with
    ±50 % jitter, or what ``Retry-After`` says plus up to half again, never more than
    ``max_wait_s``.

    The jitter on ``Retry-After`` matters: clients refused together and told the same
    second would all come back in the same instant and be refused together again.
    """

    attempts: int = 4
    backoff_s: float = 0.25
    max_wait_s: float = 30.0

    def __post_init__(self) -> None:
        if self.attempts < 1 or self.backoff_s < 0 or self.max_wait_s < 0:
            raise ValueError("attempts must be ≥ 1, backoff_s and max_wait_s ≥ 0")

    def wait_s(self, attempt: int, response: httpx.Response | None = None) -> float | None:
        """How long to wait before attempt ``attempt + 1`` (``attempt`` counts from 0), or
        ``None`` to give up; ``response`` is the answer that failed (``None``: the
        connection did)."""
        if attempt + 1 >= self.attempts:
            return None
        if response is not None:
            if response.status_code not in RETRY_STATUSES:
                return None
            told = retry_after_s(response.headers.get("retry-after"))
            if told is not None:
                return min(told * (1.0 + 0.5 * random.random()), self.max_wait_s)
        jitter = 0.5 + random.random()
        return min(self.backoff_s * 2.0**attempt * jitter, self.max_wait_s)


#: For calls that are not tried again.
NO_RETRY = Retry(attempts=1)


def retry_after_s(value: str | None) -> float | None:
    """``Retry-After`` in seconds: delay-seconds or an HTTP date (RFC 9110 §10.2.3)."""
    if not value:
        return None
    value = value.strip()
    if value.isascii() and value.isdigit():
        return float(value)
    try:
        when = email.utils.parsedate_to_datetime(value)
    except (TypeError, ValueError):
        return None
    return max(0.0, when.timestamp() - time.time())


#: Transport failures not worth another try: a read or write that timed out (a slow answer
#: would be as slow again, and the work would run twice), and a URL or request that cannot
#: be sent at all (no scheme, a bad header).
_FINAL_ERRORS = (
    httpx.ReadTimeout,
    httpx.WriteTimeout,
    httpx.PoolTimeout,
    httpx.UnsupportedProtocol,
    httpx.LocalProtocolError,
)


def is_retryable(error: httpx.TransportError) -> bool:
    """A connection that failed or was dropped (see :data:`_FINAL_ERRORS` for the rest)."""
    return not isinstance(error, _FINAL_ERRORS)


class Attempts:
    """The tries of one call, without I/O: after each failure, how long to wait before the
    next, or the failure to end with (the service's problem as :class:`ServiceError`)."""

    def __init__(self, retry: Retry) -> None:
        self._retry = retry
        self._count = 0

    def after_error(self, error: httpx.TransportError) -> float:
        wait = self._retry.wait_s(self._count) if is_retryable(error) else None
        if wait is None:
            raise error
        self._count += 1
        return wait

    def after_response(self, response: httpx.Response) -> float:
        wait = self._retry.wait_s(self._count, response)
        if wait is None:
            raise ServiceError.from_response(response)
        self._count += 1
        return wait
