"""A request to its output, through a client: the one code path of every command, whether
the client is the service's app in this process (:func:`arcspline.client.local_client`)
or a running service (``--server URL``).

JSON is the service's answer as it wrote it; G-code comes from the JSON answer (it holds
the statistics and, when G-code options are given, the program, byte for byte as the program
alone); a DXF or an SVG is the document alone, with the JSON answer fetched beside it for
the statistics.
"""

from __future__ import annotations

import asyncio
import time
from collections.abc import AsyncIterator
from contextlib import asynccontextmanager
from dataclasses import dataclass
from typing import Any

from arcspline.client import (
    ApproximateResponse,
    AsyncClient,
    DrawingResponse,
    PathResponse,
    local_client,
)

from .errors import CommandError, UsageError
from .options import Format, Kind
from .summary import Summary, summarize

Answer = ApproximateResponse | PathResponse | DrawingResponse
MODELS: dict[Kind, type[Answer]] = {
    "spiral": ApproximateResponse,
    "path": PathResponse,
    "drawing": DrawingResponse,
}


@asynccontextmanager
async def connect(server: str | None, workers: int, concurrency: int) -> AsyncIterator[AsyncClient]:
    """A client of ``server``, else of the app in this process: ``workers=0`` runs its jobs
    in a thread (one file), ``workers=n`` in a pool of n processes (many files).

    ``concurrency`` files may be in flight, each with up to two requests (a document and
    its statistics); the local app admits them all rather than answer 503.
    """
    if server is not None and not server.startswith(("http://", "https://")):
        raise UsageError(f"--server takes a URL such as http://{server}", "--server")
    if server is None:
        from arcspline.settings import get_settings

        capacity = max(get_settings().queue_capacity, 2 * concurrency)
        async with local_client(workers, queue_capacity=capacity) as client:
            yield client
    else:
        async with AsyncClient(server, max_concurrency=concurrency) as client:
            yield client


@dataclass(frozen=True)
class Product:
    """An output's bytes, the statistics of its answer (``None`` when not asked for), and
    the time the work took."""

    content: bytes
    summary: Summary | None
    seconds: float


async def _answer(client: AsyncClient, kind: Kind, request: dict[str, Any]) -> tuple[bytes, Answer]:
    """The JSON answer to ``request``: the service's bytes, and its model."""
    document = await client.document(request, "json")
    return document.content, MODELS[kind].model_validate_json(document.content)


async def produce(
    client: AsyncClient, kind: Kind, request: dict[str, Any], fmt: Format, stats: bool = True
) -> Product:
    """``request``'s output in ``fmt``, and its statistics (``stats``: for a DXF or an SVG,
    at the price of the JSON answer computed beside it)."""
    if fmt == "gcode" and not request.get("gcode"):
        raise UsageError("a program needs the G-code options: give --feed-rate", "--feed-rate")
    started = time.perf_counter()
    if not stats and fmt != "gcode":  # a program comes from the JSON answer anyway
        document = await client.document(request, fmt)
        return Product(document.content, None, time.perf_counter() - started)
    if fmt in ("json", "gcode"):
        content, response = await _answer(client, kind, request)
        if fmt == "gcode":
            content = _program(response)
        return Product(content, summarize(response), time.perf_counter() - started)
    try:
        async with asyncio.TaskGroup() as tasks:
            document_task = tasks.create_task(client.document(request, fmt))
            answer_task = tasks.create_task(_answer(client, kind, request))
    except BaseExceptionGroup as group:  # the first failure says it; the other is cancelled
        raise group.exceptions[0] from None
    summary = summarize(answer_task.result()[1])
    return Product(document_task.result().content, summary, time.perf_counter() - started)


async def picture(client: AsyncClient, request: dict[str, Any]) -> bytes:
    """The preview (SVG) of ``request``'s approximation."""
    return (await client.preview(request)).encode()


def _program(response: Answer) -> bytes:
    if response.gcode is None:
        raise CommandError("the answer holds no program: give the G-code options (--feed-rate)")
    return response.gcode.encode()
