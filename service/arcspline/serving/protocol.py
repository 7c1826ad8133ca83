"""uvicorn's httptools protocol with bounds on what a connection may hold (docs/deployment.md,
"Connections").

httptools (llhttp) sets no limit of its own: it hands uvicorn the request line and every
header as they arrive, and uvicorn keeps them all, so a client may send headers without end
and hold memory for as long as it likes. This protocol answers, as problem details, and closes:

- request line and headers over ``max_header_bytes`` → 431 ``headers-too-large``;
- headers not complete ``header_timeout_s`` after the connection opened (or after the first
  byte of a later request on it) → 408 ``request-timeout`` (closed without an answer if the
  client sent nothing at all, like an idle keep-alive connection);
- a body not complete ``body_timeout_s`` after its headers, while the app waits for it → 408;
- an answer the client leaves unread, the socket's buffer full, for ``send_timeout_s`` → the
  connection is dropped, so that the answer (and, for a batch, its turn among the answers
  sent at once) is not held for as long as the client likes;
- HTTP that does not parse → 400 ``malformed-http`` (uvicorn answers text/plain);
- a connection beyond ``max_connections`` first closes the connection that has waited longest
  without a request in the app (idle, or its headers still arriving); if every connection has
  one, the new one gets 503 ``too-many-connections`` with ``Retry-After``.

A request pays a counter per read and a few flags (about 2 µs of CPU, measured in process
against uvicorn's protocol); its timers are armed only when its headers or body span reads
(one header timer per connection covers its first request).
"""

from __future__ import annotations

import asyncio
import logging
from asyncio import TimerHandle
from dataclasses import dataclass
from typing import Any, ClassVar

import orjson
from uvicorn.protocols.http.httptools_impl import STATUS_LINE, HttpToolsProtocol

from arcspline.api.errors import PROBLEM_MEDIA_TYPE, problem

from .refusals import refuse

log = logging.getLogger(__name__)


@dataclass(frozen=True)
class ConnectionLimits:
    """What one serving process allows its connections (settings: docs/http-api.md)."""

    max_connections: int
    max_header_bytes: int
    header_timeout_s: float
    body_timeout_s: float
    retry_after_s: int
    send_timeout_s: float = 30.0


def problem_bytes(
    kind: str,
    detail: str,
    default_headers: list[tuple[bytes, bytes]],
    *,
    limit: float | None = None,
    retry_after_s: int | None = None,
) -> bytes:
    """A whole HTTP/1.1 problem response that closes the connection."""
    content = problem(kind, detail, limit=limit)
    body = orjson.dumps(content)
    head = [STATUS_LINE[int(content["status"])]]
    headers = [
        *default_headers,
        (b"content-type", PROBLEM_MEDIA_TYPE.encode()),
        (b"content-length", str(len(body)).encode()),
        (b"connection", b"close"),
    ]
    if retry_after_s is not None:
        headers.append((b"retry-after", str(retry_after_s).encode()))
    head.extend(name + b": " + value + b"\r\n" for name, value in headers)
    return b"".join([*head, b"\r\n", body])


class HeadersTooLargeError(Exception):
    """Raised inside the parser's callback to stop it at headers over the limit."""


class BoundedHttpToolsProtocol(HttpToolsProtocol):
    """One connection; build the class for a server with :func:`bounded_protocol`."""

    limits: ClassVar[ConnectionLimits]
    #: Connections with no request in the app (idle, or headers still arriving), oldest
    #: first: the ones closed to make room. One per server (per class built).
    waiting: ClassVar[dict[BoundedHttpToolsProtocol, None]]

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self._header_bytes = 0
        self._reading_headers = True
        self._request_begun = False
        self._in_body = False
        self._headers_too_large = False
        self._header_timer: TimerHandle | None = None
        self._body_timer: TimerHandle | None = None
        self._send_timer: TimerHandle | None = None

    # -- connection ----------------------------------------------------------------------

    def connection_made(self, transport: asyncio.Transport) -> None:  # type: ignore[override]
        super().connection_made(transport)
        if len(self.connections) > self.limits.max_connections and not self._make_room():
            log.warning("connection refused: %d connections, all busy", len(self.connections))
            self._answer_and_close(
                "too_many_connections",
                f"the server holds its most connections ({self.limits.max_connections}), "
                "all with a request in progress",
                limit=self.limits.max_connections,
                retry_after_s=self.limits.retry_after_s,
            )
            return
        self.waiting[self] = None
        self._header_timer = self.loop.call_later(
            self.limits.header_timeout_s, self._on_header_timeout
        )

    def connection_lost(self, exc: Exception | None) -> None:
        self.waiting.pop(self, None)
        self._cancel_header_timer()
        self._cancel_body_timer()
        self._cancel_send_timer()
        super().connection_lost(exc)

    def _make_room(self) -> bool:
        """Close the connection that has waited longest without a request in the app."""
        if not self.waiting:
            return False
        oldest = next(iter(self.waiting))
        del self.waiting[oldest]
        log.debug("closing the oldest connection without a request to make room")
        oldest.transport.close()
        return True

    def _answer_and_close(self, kind: str, detail: str, **extra: Any) -> None:
        """Answer with a problem and close; a request still in the app (pipelined before
        this one) is treated as disconnected, and if its response has begun nothing more is
        written."""
        self.waiting.pop(self, None)
        if self.transport.is_closing():
            return
        refuse(kind)
        cycle = self.cycle
        answer = True
        if cycle is not None and not cycle.response_complete:
            answer = not cycle.response_started
            cycle.disconnected = True
            cycle.message_event.set()
        if answer:
            self.transport.write(
                problem_bytes(kind, detail, self.server_state.default_headers, **extra)
            )
        self.transport.close()

    def _refuse_headers(self) -> None:
        limit = self.limits.max_header_bytes
        self._answer_and_close(
            "headers_too_large", f"request line and headers over {limit} bytes", limit=limit
        )

    def _exact_header_bytes(self) -> int:
        """The request target and headers, as received (without separators)."""
        return len(self.url) + sum(len(name) + len(value) for name, value in self.headers)

    # -- reading -------------------------------------------------------------------------

    def data_received(self, data: bytes) -> None:
        if self._reading_headers:
            self._header_bytes += len(data)
        super().data_received(data)
        if self.transport.is_closing():
            return
        if self._reading_headers:
            if self._header_bytes > self.limits.max_header_bytes:
                self._refuse_headers()
            elif self._request_begun and self._header_timer is None:
                self._header_timer = self.loop.call_later(
                    self.limits.header_timeout_s, self._on_header_timeout
                )
        elif self._in_body and self._body_timer is None:
            self._body_timer = self.loop.call_later(
                self.limits.body_timeout_s, self._on_body_timeout
            )

    def send_400_response(self, msg: str) -> None:
        if self._headers_too_large:
            self._refuse_headers()
        else:
            self._answer_and_close("malformed_http", "the request is not valid HTTP/1.1")

    def on_message_begin(self) -> None:
        super().on_message_begin()
        self._request_begun = True

    def on_headers_complete(self) -> None:
        # Headers that arrived whole in one read (up to 256 KiB) are measured here; the
        # exception stops the parser, and uvicorn's handler of parser errors calls
        # send_400_response, which answers 431.
        limit = self.limits.max_header_bytes
        if self._header_bytes > limit and self._exact_header_bytes() > limit:
            self._headers_too_large = True
            raise HeadersTooLargeError(limit)
        self._reading_headers = False
        self._in_body = True
        self._header_bytes = 0
        self._cancel_header_timer()
        self.waiting.pop(self, None)
        super().on_headers_complete()

    def on_message_complete(self) -> None:
        super().on_message_complete()
        self._in_body = False
        self._cancel_body_timer()
        self._reading_headers = True
        self._request_begun = False

    def on_response_complete(self) -> None:
        super().on_response_complete()
        if not self.transport.is_closing() and self.cycle.response_complete:
            self.waiting[self] = None

    # -- writing -------------------------------------------------------------------------

    def pause_writing(self) -> None:
        # The transport's buffer passed its high-water mark: the client reads slower than
        # the answer is written. It has send_timeout_s to drain it below the low-water mark.
        super().pause_writing()
        if self._send_timer is None:
            self._send_timer = self.loop.call_later(
                self.limits.send_timeout_s, self._on_send_timeout
            )

    def resume_writing(self) -> None:
        super().resume_writing()
        self._cancel_send_timer()

    def _on_send_timeout(self) -> None:
        self._send_timer = None
        if self.flow.write_paused and not self.transport.is_closing():
            log.info(
                "a client left its answer unread for %g s; dropping the connection",
                self.limits.send_timeout_s,
            )
            refuse("send_timeout")
            # Not close(): that would wait for the unread buffer to be flushed.
            self.transport.abort()

    def _cancel_send_timer(self) -> None:
        if self._send_timer is not None:
            self._send_timer.cancel()
            self._send_timer = None

    # -- timeouts ------------------------------------------------------------------------

    def _on_header_timeout(self) -> None:
        self._header_timer = None
        if not self._reading_headers or self.transport.is_closing():
            return
        if self._busy():
            # A pipelined request's headers wait while the one before it is answered.
            self._header_timer = self.loop.call_later(
                self.limits.header_timeout_s, self._on_header_timeout
            )
            return
        if self._request_begun:
            self._answer_and_close(
                "request_timeout",
                f"request line and headers not complete within {self.limits.header_timeout_s:g} s",
                limit=self.limits.header_timeout_s,
            )
        else:
            self.waiting.pop(self, None)
            self.transport.close()

    def _on_body_timeout(self) -> None:
        self._body_timer = None
        cycle = self.cycle
        if not self._in_body or cycle is None or cycle.response_started:
            return
        if self.flow.read_paused:
            # Reading is paused (a request before it, or a body the app has not taken yet):
            # the client is not the one keeping it waiting.
            self._body_timer = self.loop.call_later(
                self.limits.body_timeout_s, self._on_body_timeout
            )
            return
        # The app sees the client gone (as when it disconnects) and answers no one.
        self._answer_and_close(
            "request_timeout",
            f"request body not complete within {self.limits.body_timeout_s:g} s",
            limit=self.limits.body_timeout_s,
        )

    def _busy(self) -> bool:
        """A request is in the app, its response not complete."""
        return self.cycle is not None and not self.cycle.response_complete

    def _cancel_header_timer(self) -> None:
        if self._header_timer is not None:
            self._header_timer.cancel()
            self._header_timer = None

    def _cancel_body_timer(self) -> None:
        if self._body_timer is not None:
            self._body_timer.cancel()
            self._body_timer = None


def bounded_protocol(limits: ConnectionLimits) -> type[BoundedHttpToolsProtocol]:
    """The protocol class for one server (uvicorn's ``http=``), holding its limits and its
    register of waiting connections."""
    namespace = {"limits": limits, "waiting": {}}
    return type("BoundedHttpToolsProtocol", (BoundedHttpToolsProtocol,), namespace)
