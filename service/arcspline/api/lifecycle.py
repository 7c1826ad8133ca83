"""A request's life bound to its client's and to the server's (pure ASGI middleware;
docs/http-api.md, "Cancellation, drain and fairness").

- **A client that disconnects cancels its request.** Once the body has been read,
  ``receive`` has only ``http.disconnect`` left to give, which uvicorn sends when the
  connection drops (or once the response is complete). A watcher waits for it and, while
  the response is incomplete, cancels the request's task; the worker pool then kills the
  work no other request waits for. Nothing is sent (no one would read it); the request is
  counted with status 499, nginx's "client closed request".
- **A request still running when the drain ends is answered 503.** On SIGTERM or SIGINT
  uvicorn stops accepting and waits for the requests in flight; past its graceful timeout it
  cancels them (an ERROR line), and answers each with a text/plain 500 and a traceback in
  the log. Here the drain ends first: ``ARCSPLINE_DRAIN_TIMEOUT_S`` after the signal, the
  requests still running are cancelled and answered ``503 shutting_down`` with
  ``Retry-After`` (another replica can take it), and one line counts them; uvicorn's timeout
  is a few seconds longer (``__main__.DRAIN_BACKSTOP_S``), a backstop that is not reached.
  The app hears of the drain from the signal: uvicorn tells an app nothing before
  ``lifespan.shutdown``, which comes after it has cancelled the requests. Without the
  signal (the app in this process, say, behind the command line's in-process transport) a
  cancellation is the caller's, and goes on.
"""

from __future__ import annotations

import asyncio
import contextlib
import logging
import signal
import threading
from types import FrameType
from typing import Any

from starlette.types import ASGIApp, Message, Receive, Scope, Send

from .errors import problem, problem_response
from .metrics import Metrics

log = logging.getLogger(__name__)

#: How long a request runs before a watcher listens for its client's disconnect: a request
#: shorter than this pays no task for it (most single jobs take a millisecond or two).
WATCH_AFTER_S = 0.05
#: The status a request whose client has gone is counted with (nginx's; never sent).
CLIENT_CLOSED_REQUEST = 499
_DRAIN_SIGNALS = (signal.SIGINT, signal.SIGTERM)


class LifecycleMiddleware:
    """Cancels a request whose client has gone; answers 503 to one the drain cuts."""

    def __init__(
        self, app: ASGIApp, retry_after_s: int, metrics: Metrics, drain_timeout_s: float
    ) -> None:
        self.app = app
        self.retry_after_s = retry_after_s
        self.metrics = metrics
        self.drain_timeout_s = drain_timeout_s
        #: The requests in the app now: those the drain cuts when it ends.
        self.running: set[_Request] = set()
        self._loop: asyncio.AbstractEventLoop | None = None
        #: Set by SIGTERM or SIGINT: a request cancelled from now on is cut by the drain.
        self.draining = False
        #: Requests cut by the drain, not yet logged.
        self.cut = 0
        self._summarised = False
        self._previous_handlers: dict[int, Any] = {}

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        if scope["type"] == "http":
            await _Request(self, scope, receive, send).run()
        elif scope["type"] == "lifespan":
            await self._lifespan(scope, receive, send)
        else:
            await self.app(scope, receive, send)

    # -- the drain ---------------------------------------------------------------------

    async def _lifespan(self, scope: Scope, receive: Receive, send: Send) -> None:
        async def send_and_summarise(message: Message) -> None:
            if message["type"].startswith("lifespan.shutdown."):
                self._restore_handlers()
                self._summarise()
            await send(message)

        self._loop = asyncio.get_running_loop()
        self._hear_drain_signals()
        try:
            await self.app(scope, receive, send_and_summarise)
        finally:
            self._restore_handlers()

    def _hear_drain_signals(self) -> None:
        """Chain a handler before the server's own for the signals that start a drain
        (uvicorn installs its handlers before the lifespan starts, and restores the ones it
        found when it exits)."""
        if threading.current_thread() is not threading.main_thread():
            return  # signals reach the main thread only: no server of ours runs elsewhere
        for signum in _DRAIN_SIGNALS:
            previous = signal.getsignal(signum)
            if callable(previous):
                self._previous_handlers[signum] = previous
                signal.signal(signum, self._on_drain_signal)

    def _on_drain_signal(self, signum: int, frame: FrameType | None) -> None:
        if not self.draining and self._loop is not None:
            # The handler runs between two bytecodes of the loop's thread: the loop is told
            # through its self-pipe, as from another thread.
            self._loop.call_soon_threadsafe(self._end_drain_later)
        self.draining = True
        self._previous_handlers[signum](signum, frame)

    def _end_drain_later(self) -> None:
        assert self._loop is not None
        self._loop.call_later(self.drain_timeout_s, self._end_drain)

    def _end_drain(self) -> None:
        """The drain's time is up: cancel what still runs (each answers 503 itself)."""
        for request in list(self.running):
            request.task.cancel()

    def _restore_handlers(self) -> None:
        for signum, previous in self._previous_handlers.items():
            if signal.getsignal(signum) == self._on_drain_signal:
                signal.signal(signum, previous)
        self._previous_handlers.clear()

    def note_cut(self) -> None:
        self.cut += 1
        self.metrics.error("shutting_down")
        if self._summarised:  # after the summary: a line of its own
            self._summarise()

    def _summarise(self) -> None:
        self._summarised = True
        if self.cut:
            log.warning(
                "the drain ended with %d request(s) still running: answered 503 shutting_down",
                self.cut,
            )
            self.cut = 0


class _Request:
    """One HTTP request's run: its body read, its response sent, and whether it is cut."""

    __slots__ = (
        "complete",
        "gone",
        "lifecycle",
        "receive",
        "scope",
        "send",
        "started",
        "task",
        "timer",
        "watcher",
    )

    def __init__(
        self, lifecycle: LifecycleMiddleware, scope: Scope, receive: Receive, send: Send
    ) -> None:
        self.lifecycle = lifecycle
        self.scope, self.receive, self.send = scope, receive, send
        task = asyncio.current_task()
        assert task is not None
        self.task = task
        self.started = self.complete = self.gone = False
        self.timer: asyncio.TimerHandle | None = None
        self.watcher: asyncio.Task[None] | None = None

    async def run(self) -> None:
        self.lifecycle.running.add(self)
        try:
            await self.lifecycle.app(self.scope, self._receive, self._send)
        except asyncio.CancelledError:
            if self.gone and self.task.uncancel() == 0:
                await self._count_as_gone()
                return
            if not self.lifecycle.draining:
                raise
            self.task.uncancel()
            self.lifecycle.note_cut()
            if not self.started:
                await self._answer_shutting_down()
            # Else the answer is cut short: uvicorn closes the connection (the client sees
            # a body shorter than announced, or a stream without its end).
        finally:
            self.lifecycle.running.discard(self)
            if self.timer is not None:
                self.timer.cancel()
            if self.watcher is not None:
                self.watcher.cancel()

    async def _receive(self) -> Message:
        if self.timer is not None or self.watcher is not None:
            # Asked again once the body has been read (Starlette's is_disconnected, a
            # stream's listener): only the end is left to come, and the watcher awaits it.
            await self._watch_now()
            return {"type": "http.disconnect"}
        message = await self.receive()
        if message["type"] == "http.request" and not message.get("more_body", False):
            self.timer = asyncio.get_running_loop().call_later(WATCH_AFTER_S, self._start_watch)
        return message

    async def _send(self, message: Message) -> None:
        if message["type"] == "http.response.start":
            self.started = True
        elif message["type"] == "http.response.body" and not message.get("more_body", False):
            self.complete = True
        await self.send(message)

    def _start_watch(self) -> None:
        if self.watcher is None and not self.complete:
            self.watcher = asyncio.create_task(self._watch(), name="arcspline-disconnect")

    async def _watch_now(self) -> None:
        if self.timer is not None:
            self.timer.cancel()
        self._start_watch()
        if self.watcher is not None:
            await asyncio.shield(self.watcher)

    async def _watch(self) -> None:
        message = await self.receive()
        if message["type"] == "http.disconnect" and not self.complete:
            self.gone = True
            self.task.cancel()

    async def _count_as_gone(self) -> None:
        """The request counted with status 499 by the metrics: a start message the server
        drops (its connection is closed)."""
        if not self.started:
            with contextlib.suppress(OSError):
                start = {"type": "http.response.start", "status": CLIENT_CLOSED_REQUEST}
                await self._send({**start, "headers": []})

    async def _answer_shutting_down(self) -> None:
        lifecycle = self.lifecycle
        detail = (
            "the server is shutting down and its drain ended before this request did; "
            f"retry in {lifecycle.retry_after_s} s (another replica can take it)"
        )
        headers = {"Retry-After": str(lifecycle.retry_after_s), "Connection": "close"}
        response = problem_response(problem("shutting_down", detail), headers=headers)
        await response(self.scope, self.receive, self._send)
