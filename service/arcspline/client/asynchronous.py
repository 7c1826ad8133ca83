"""The asyncio client (docs/client.md): :class:`~arcspline.client.Client`'s operations,
awaited, with a batch's chunks in flight together."""

from __future__ import annotations

import asyncio
from collections.abc import Iterable, Mapping
from pathlib import Path
from types import TracebackType
from typing import Any, BinaryIO, TypeVar

import httpx

from arcspline.api.drawing_schemas import DrawingResponse
from arcspline.api.path_schemas import PathResponse
from arcspline.api.schemas import ApproximateResponse, HealthResponse, ReadyResponse

from . import operations as ops
from .batching import DEFAULT_MAX_BYTES, DEFAULT_MAX_JOBS, BatchPlan, Chunk, Entry, Results, plan
from .batching import split as split_chunk
from .config import DEFAULT_URL, ClientConfig
from .errors import ServiceError
from .files import atomic_writer
from .operations import AnyRequest, Call, Document, Kind, Output
from .retry import Retry, is_retryable

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

    async def download(self, request: AnyRequest, output: Output, to: Path | BinaryIO) -> Document:
        """:meth:`document`, streamed into a file (``content`` is then empty)."""
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
    ) -> list[ApproximateResponse | ServiceError]:
        """Many spirals through ``POST /v1/approximate/batch``, in chunks: one entry per
        request, in order, its response or the :class:`ServiceError` that refused it."""
        return await self._batch("spiral", requests)  # type: ignore[return-value]

    async def approximate_paths_batch(
        self, requests: Iterable[AnyRequest]
    ) -> list[PathResponse | ServiceError]:
        """Many paths through ``POST /v1/paths/batch``, in chunks (as
        :meth:`approximate_batch`)."""
        return await self._batch("path", requests)  # type: ignore[return-value]

    # -- sending -------------------------------------------------------------------------

    async def _batch(self, kind: Kind, requests: Iterable[AnyRequest]) -> list[Entry]:
        batch = plan(kind, requests, self.config.batch_max_jobs, self.config.batch_max_bytes)
        results = Results(batch.size)
        in_flight = asyncio.Semaphore(self.config.max_concurrency)
        await asyncio.gather(*(self._chunk(batch, c, results, in_flight) for c in batch.chunks))
        return results.done()

    async def _chunk(
        self,
        batch: BatchPlan,
        chunk: Chunk,
        results: Results,
        in_flight: asyncio.Semaphore,
    ) -> None:
        try:
            async with in_flight:
                entries = await self._run(batch.call(chunk))
            results.fill(chunk, entries)
        except ServiceError as error:
            smaller = split_chunk(chunk, error)
            if smaller is None:
                results.fill(chunk, error)
                return
            for part in smaller:
                await self._chunk(batch, part, results, in_flight)

    async def _run(self, call: Call[T], to: Path | BinaryIO | None = None) -> T:
        retry = self.config.retry
        attempt = 0
        while True:
            try:
                if to is None:
                    response = await self._http.request(
                        call.method, call.path, content=call.body, headers=call.headers
                    )
                    if response.is_success:
                        return call.read(response)
                else:
                    response = await self._stream(call, to)
                    if response.is_success:
                        return ops.read_streamed(response)  # type: ignore[return-value]
            except httpx.TransportError as error:
                wait = retry.wait_s(attempt) if is_retryable(error) else None
                if wait is None:
                    raise
            else:
                wait = retry.wait_s(attempt, response)
                if wait is None:
                    raise ServiceError.from_response(response)
            await asyncio.sleep(wait)
            attempt += 1

    async def _stream(self, call: Call[Any], to: Path | BinaryIO) -> httpx.Response:
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
