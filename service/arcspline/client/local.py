"""The service without a server: the same app, in this process, reached through
:class:`~arcspline.client.AsyncClient` over an in-process transport. What the command line
runs when it is given no ``--server``; the answers are the server's, byte for byte, because
the routes, workers' functions and writers are the same code.
"""

from __future__ import annotations

from collections.abc import AsyncIterator
from contextlib import asynccontextmanager
from typing import Any

import httpx

from .asynchronous import AsyncClient

#: The body limit of the service in this process: a document of up to 256 MiB (a request
#: holds a document as JSON text, which escaping makes a fifth larger).
LOCAL_MAX_BODY_BYTES = 256 * 1024 * 1024
#: The most segments of a drawing in this process: the service's default (50 000) is what a
#: pod of 512 MiB holds two at a time (docs/deployment.md, "Memory"); one drawing of 200 000
#: takes some 700 MiB, which a workstation has.
LOCAL_DRAWING_MAX_SEGMENTS = 200_000


@asynccontextmanager
async def local_client(workers: int = 0, **settings: Any) -> AsyncIterator[AsyncClient]:
    """An :class:`AsyncClient` of an app started in this process.

    ``workers=0``: jobs run in a thread of this process (no process to start, no time
    limits; for one file); ``workers=n``: a pool of ``n`` worker processes, as the server
    has (for many files at once). ``settings`` override the service's settings
    (``arcspline.settings.Settings``; the environment's ``ARCSPLINE_*`` apply too), but for
    the body and drawing limits: what a network service must bound, a file on this machine
    need not, so they are :data:`LOCAL_MAX_BODY_BYTES` and
    :data:`LOCAL_DRAWING_MAX_SEGMENTS` unless given.
    """
    from arcspline.api.app import create_app
    from arcspline.settings import Settings

    settings = {
        "max_body_bytes": LOCAL_MAX_BODY_BYTES,
        "drawing_max_segments": LOCAL_DRAWING_MAX_SEGMENTS,
        **settings,
    }
    if workers == 0:
        settings = {"start_method": "inline", "pool_size": 1, **settings}
    else:
        settings = {"pool_size": workers, **settings}
    app = create_app(Settings(**settings))
    async with app.router.lifespan_context(app):
        # A failure inside the app is its 500 problem, as a server would answer.
        transport = httpx.ASGITransport(app=app, raise_app_exceptions=False)
        async with AsyncClient("http://arcspline.local", transport=transport) as client:
            yield client
