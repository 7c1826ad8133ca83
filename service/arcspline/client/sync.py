"""The blocking client (docs/client.md)."""

from __future__ import annotations

import time
from collections.abc import Iterable, Mapping
from concurrent.futures import ThreadPoolExecutor
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


class Client:
    """A client of the arcspline service; every method raises :class:`ServiceError` with
    the service's problem details when it refuses a request.

    ``retry`` governs busy answers (503/429, honouring ``Retry-After``) and dropped
    connections; a batch is cut into chunks under ``batch_max_jobs`` jobs and
    ``batch_max_bytes`` bytes, at most ``max_concurrency`` in flight.
    """

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
        transport: httpx.BaseTransport | None = None,
    ) -> None:
        self.config = ClientConfig.of(
            base_url, timeout_s, retry, max_concurrency, batch_max_jobs, batch_max_bytes
        )
        self._http = httpx.Client(
            base_url=self.config.base_url,
            timeout=self.config.timeout,
            headers=self.config.headers(headers),
            transport=transport,
        )

    def __enter__(self) -> Client:
        return self

    def __exit__(
        self,
        kind: type[BaseException] | None,
        error: BaseException | None,
        traceback: TracebackType | None,
    ) -> None:
        self.close()

    def close(self) -> None:
        self._http.close()

    # -- operations ----------------------------------------------------------------------

    def approximate(self, request: AnyRequest) -> ApproximateResponse:
        """``POST /v1/approximate``: the arc spline of one spiral."""
        return self._run(ops.approximate(request))

    def approximate_path(self, request: AnyRequest) -> PathResponse:
        """``POST /v1/paths/approximate``: the arc splines of a path."""
        return self._run(ops.approximate_path(request))

    def approximate_drawing(self, request: AnyRequest) -> DrawingResponse:
        """``POST /v1/drawings/approximate``: the toolpaths of a whole drawing."""
        return self._run(ops.approximate_drawing(request))

    def document(self, request: AnyRequest, output: Output) -> Document:
        """The G-code program, DXF or SVG of a spiral, path or drawing, alone; ``"json"``:
        the JSON answer as the service's bytes."""
        return self._run(ops.document(request, output))

    def download(self, request: AnyRequest, output: Output, to: Destination) -> Document:
        """:meth:`document`, streamed into a file (a path) or a binary stream, which gets
        the whole document or nothing (``content`` is then empty)."""
        return self._run(ops.document(request, output), to)

    def preview(self, request: AnyRequest) -> str:
        """The picture (SVG) of a spiral's, path's or drawing's approximation."""
        return self._run(ops.preview(request))

    def health(self) -> HealthResponse:
        return self._run(ops.health())

    def ready(self) -> ReadyResponse:
        """``GET /readyz`` (a :class:`ServiceError` 503 while the workers are not ready)."""
        return self._run(ops.ready())

    def approximate_batch(
        self, requests: Iterable[AnyRequest]
    ) -> list[ApproximateResponse | ServiceError | httpx.TransportError]:
        """Many spirals through ``POST /v1/approximate/batch``, in chunks: one entry per
        request, in order: its response, the :class:`ServiceError` that refused it, or the
        connection failure that ended its chunk after every retry."""
        return self._batch("spiral", requests)  # type: ignore[return-value]

    def approximate_paths_batch(
        self, requests: Iterable[AnyRequest]
    ) -> list[PathResponse | ServiceError | httpx.TransportError]:
        """Many paths through ``POST /v1/paths/batch``, in chunks (as
        :meth:`approximate_batch`)."""
        return self._batch("path", requests)  # type: ignore[return-value]

    # -- sending -------------------------------------------------------------------------

    def _batch(self, kind: Kind, requests: Iterable[AnyRequest]) -> list[Entry]:
        batch = plan(kind, requests, self.config.batch_max_jobs, self.config.batch_max_bytes)
        results = Results(batch.size)
        with ThreadPoolExecutor(self.config.max_concurrency) as threads:
            for _ in threads.map(lambda chunk: self._chunk(batch, chunk, results), batch.chunks):
                pass
        return results.done()

    def _chunk(self, batch: BatchPlan, chunk: Chunk, results: Results) -> None:
        outcome: Outcome
        try:
            outcome = self._run(batch.call(chunk))
        except (ServiceError, httpx.TransportError) as error:
            outcome = error
        for part in settle(results, chunk, outcome):
            self._chunk(batch, part, results)

    def _run(self, call: Call[T], to: Destination | None = None) -> T:
        attempts = Attempts(self.config.retry if call.retried else NO_RETRY)
        while True:
            try:
                response = self._send(call) if to is None else self._stream(call, to)
            except httpx.TransportError as error:
                wait = attempts.after_error(error)
            else:
                if response.is_success:
                    read = call.read if to is None else ops.read_streamed
                    return read(response)  # type: ignore[return-value]
                wait = attempts.after_response(response)
            time.sleep(wait)

    def _send(self, call: Call[Any]) -> httpx.Response:
        return self._http.request(call.method, call.path, content=call.body, headers=call.headers)

    def _stream(self, call: Call[Any], to: Destination) -> httpx.Response:
        with self._http.stream(
            call.method, call.path, content=call.body, headers=call.headers
        ) as response:
            if not response.is_success:
                response.read()
                return response
            with atomic_writer(to) as file:
                for block in response.iter_bytes():
                    file.write(block)
            return response
