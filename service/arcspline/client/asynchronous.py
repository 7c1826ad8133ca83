"""The asyncio client (docs/client.md): :class:`~arcspline.client.Client`'s operations,
awaited, with a batch's chunks in flight together."""

from __future__ import annotations

import asyncio
from collections.abc import Iterable, Mapping
from types import TracebackType
from typing import Any, TypeVar

import httpx

from arcspline.api.drawing_schemas import DrawingResponse
from arcspline.api.path_schemas import PathResponse
from arcspline.api.schemas import ApproximateResponse, HealthResponse, ReadyResponse

from . import operations as ops
from .batching import (
    DEFAULT_MAX_BYTES,
    DEFAULT_MAX_JOBS,
    BatchPlan,
    Chunk,
    Entry,
    Outcome,
    Results,
    plan,
    settle,
)
from .config import DEFAULT_URL, ClientConfig
from .errors import ServiceError
from .files import Destination, atomic_writer
from .operations import AnyRequest, Call, Document, Kind, Output
from .retry import NO_RETRY, Attempts, Retry

T = TypeVar("T")


class AsyncClient:
    """:class:`~arcspline.client.Client` for asyncio: the same operations and options."""

    def __init__(
        self,
        base_url: str = DEFAULT_URL,
        *,
        timeout_s: float = 150.0,
        retry: Retry | None = None,
        max_concurrency: int = 4,
        batch_max_jobs: int = DEFAULT_MAX_JOBS,
        batch_max_bytes: int = DEFAULT_MAX_BYTES,
        headers: Mapping[str, str] | None = None,
        transport: httpx.AsyncBaseTransport | None = None,
    ) -> None:
        self.config = ClientConfig.of(
            base_url, timeout_s, retry, max_concurrency, batch_max_jobs, batch_max_bytes
        )
        self._http = httpx.AsyncClient(
            base_url=self.config.base_url,
            timeout=self.config.timeout,
            headers=self.config.headers(headers),
            transport=transport,
        )

    async def __aenter__(self) -> AsyncClient:
        return self

    async def __aexit__(
        self,
        kind: type[BaseException] | None,
        error: BaseException | None,
        traceback: TracebackType | None,
    ) -> None:
        await self.aclose()

    async def aclose(self) -> None:
        await self._http.aclose()

    # -- operations ----------------------------------------------------------------------

    async def approximate(self, request: AnyRequest) -> ApproximateResponse:
        """``POST /v1/approximate``: the arc spline of one spiral."""
        return await self._run(ops.approximate(request))

    async def approximate_path(self, request: AnyRequest) -> PathResponse:
        """``POST /v1/paths/approximate``: the arc splines of a path."""
        return await self._run(ops.approximate_path(request))

    async def approximate_drawing(self, request: AnyRequest) -> DrawingResponse:
        """``POST /v1/drawings/approximate``: the toolpaths of a whole drawing."""
        return await self._run(ops.approximate_drawing(request))

    async def document(self, request: AnyRequest, output: Output) -> Document:
        """The G-code program, DXF or SVG of a spiral, path or drawing, alone; ``"json"``:
        the JSON answer as the service's bytes."""
        return await self._run(ops.document(request, output))

    async def download(self, request: AnyRequest, output: Output, to: Destination) -> Document:
        """:meth:`document`, streamed into a file (a path) or a binary stream, which gets
        the whole document or nothing (``content`` is then empty)."""
        return await self._run(ops.document(request, output), to)

    async def preview(self, request: AnyRequest) -> str:
        """The picture (SVG) of a spiral's, path's or drawing's approximation."""
        return await self._run(ops.preview(request))

    async def health(self) -> HealthResponse:
        return await self._run(ops.health())

    async def ready(self) -> ReadyResponse:
        """``GET /readyz`` (a :class:`ServiceError` 503 while the workers are not ready)."""
        return await self._run(ops.ready())

    async def approximate_batch(
        self, requests: Iterable[AnyRequest]
    ) -> list[ApproximateResponse | ServiceError | httpx.TransportError]:
        """Many spirals through ``POST /v1/approximate/batch``, in chunks: one entry per
        request, in order: its response, the :class:`ServiceError` that refused it, or the
        connection failure that ended its chunk after every retry."""
        return await self._batch("spiral", requests)  # type: ignore[return-value]

    async def approximate_paths_batch(
        self, requests: Iterable[AnyRequest]
    ) -> list[PathResponse | ServiceError | httpx.TransportError]:
        """Many paths through ``POST /v1/paths/batch``, in chunks (as
        :meth:`approximate_batch`)."""
        return await self._batch("path", requests)  # type: ignore[return-value]

    # -- sending -------------------------------------------------------------------------

    async def _batch(self, kind: Kind, requests: Iterable[AnyRequest]) -> list[Entry]:
        batch = plan(kind, requests, self.config.batch_max_jobs, self.config.batch_max_bytes)
        results = Results(batch.size)
        in_flight = asyncio.Semaphore(self.config.max_concurrency)
        # A task group: if anything unexpected ends one chunk, the others are cancelled.
        async with asyncio.TaskGroup() as chunks:
            for chunk in batch.chunks:
                chunks.create_task(self._chunk(batch, chunk, results, in_flight))
        return results.done()

    async def _chunk(
        self,
        batch: BatchPlan,
        chunk: Chunk,
        results: Results,
        in_flight: asyncio.Semaphore,
    ) -> None:
        outcome: Outcome
        try:
            async with in_flight:
                outcome = await self._run(batch.call(chunk))
        except (ServiceError, httpx.TransportError) as error:
            outcome = error
        for part in settle(results, chunk, outcome):
            await self._chunk(batch, part, results, in_flight)

    async def _run(self, call: Call[T], to: Destination | None = None) -> T:
        attempts = Attempts(self.config.retry if call.retried else NO_RETRY)
        while True:
            try:
                response = await (self._send(call) if to is None else self._stream(call, to))
            except httpx.TransportError as error:
                wait = attempts.after_error(error)
            else:
                if response.is_success:
                    read = call.read if to is None else ops.read_streamed
                    return read(response)  # type: ignore[return-value]
                wait = attempts.after_response(response)
            await asyncio.sleep(wait)

    async def _send(self, call: Call[Any]) -> httpx.Response:
        return await self._http.request(
            call.method, call.path, content=call.body, headers=call.headers
        )

    async def _stream(self, call: Call[Any], to: Destination) -> httpx.Response:
        async with self._http.stream(
            call.method, call.path, content=call.body, headers=call.headers
        ) as response:
            if not response.is_success:
                await response.aread()
                return response
            with atomic_writer(to) as file:
                async for block in response.aiter_bytes():
                    file.write(block)
            return response
