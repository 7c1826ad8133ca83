"""The request body size limit (pure ASGI middleware).

A declared ``Content-Length`` over the limit is refused before the body is read; a body
sent without one (chunked) is counted as it arrives and refused once it crosses the limit.
Both answer 413 as problem details.
"""

from __future__ import annotations

from starlette.datastructures import Headers
from starlette.exceptions import HTTPException
from starlette.types import ASGIApp, Message, Receive, Scope, Send

from .errors import problem, problem_kind, problem_response
from .metrics import Metrics


class BodyLimitMiddleware:
    def __init__(self, app: ASGIApp, max_body_bytes: int, metrics: Metrics) -> None:
        self.app = app
        self.max_body_bytes = max_body_bytes
        self.metrics = metrics

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        if scope["type"] != "http":
            await self.app(scope, receive, send)
            return
        declared = Headers(scope=scope).get("content-length")
        if declared is not None and declared.isdigit() and int(declared) > self.max_body_bytes:
            detail = f"the body is {declared} bytes; the limit is {self.max_body_bytes} bytes"
            body = problem("body_too_large", detail)
            body["limit"] = self.max_body_bytes
            self.metrics.error(problem_kind(body))
            await problem_response(body)(scope, receive, send)
            return
        received = 0

        async def receive_within_limit() -> Message:
            nonlocal received
            message = await receive()
            if message["type"] == "http.request":
                received += len(message.get("body", b""))
                if received > self.max_body_bytes:
                    # FastAPI passes HTTPExceptions from reading the body through to the
                    # app's handler, which answers with problem details.
                    detail = f"the body exceeds the limit of {self.max_body_bytes} bytes"
                    raise HTTPException(413, detail)
            return message

        await self.app(scope, receive_within_limit, send)
