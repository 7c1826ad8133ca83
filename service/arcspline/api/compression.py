"""gzip for clients that ask for it (``Accept-Encoding: gzip``; docs/http-api.md, "Big
answers"): Starlette's ``GZipMiddleware``, which compresses large pieces in a thread and
keeps streams streaming, but out of the way of every other request.

Starlette wraps every response, gzip or not, to inspect its headers on the way out; for the
many small requests of a CAM pipeline that wrapping is a measurable share of the serving
process's time (docs/performance.md, issue 19). A request that does not accept gzip goes
straight to the app here: its answer is the same, only without ``Vary: Accept-Encoding``,
which a cache needs on compressed answers (they have it) and not on plain ones.
"""

from __future__ import annotations

from starlette.middleware.gzip import GZipMiddleware
from starlette.types import Receive, Scope, Send


def accepts_gzip(scope: Scope) -> bool:
    """Whether the request's ``Accept-Encoding`` names gzip (as Starlette decides it)."""
    for name, value in scope["headers"]:
        if name == b"accept-encoding":
            return b"gzip" in value
    return False


class Compression(GZipMiddleware):
    """``GZipMiddleware`` for the requests that accept gzip; the others pass untouched."""

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        if scope["type"] == "http" and accepts_gzip(scope):
            await super().__call__(scope, receive, send)
        else:
            await self.app(scope, receive, send)
