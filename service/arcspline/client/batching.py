"""Many requests as few batch calls: each job encoded once, packed into chunks under the
service's limits (jobs per batch, bytes per body), and answered in order whatever the
chunks went through.

A chunk the service refuses as too large (413 ``too-many-jobs`` with its ``limit``, or
``body-too-large``) is split and sent again, so a client set for a server's defaults still
works against one configured smaller; any other failure of a chunk (busy after every
retry, time limit) becomes the error entry of each of its jobs, and the other chunks still
finish.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass
from typing import Any, TypeAlias, get_args

import httpx
from pydantic import TypeAdapter

from arcspline.api.path_schemas import PathBatchResponse, PathResponse
from arcspline.api.schemas import NDJSON_MEDIA_TYPE, ApproximateResponse, BatchResponse
from arcspline.settings import Settings

from .errors import ServiceError
from .operations import ENDPOINTS, AnyRequest, Call, Kind, encode, kind_of
from .parsing import gc_paused

#: A batch's answer to one job: its response, or what ended it — the service's refusal, or
#: a connection that failed after every retry.
Entry: TypeAlias = ApproximateResponse | PathResponse | ServiceError | httpx.TransportError

#: The service's defaults (a server configured lower makes the client split further).
DEFAULT_MAX_JOBS: int = Settings.model_fields["batch_max_jobs"].default
DEFAULT_MAX_BYTES: int = Settings.model_fields["max_body_bytes"].default
_OPEN, _SEP, _CLOSE = b'{"jobs":[', b",", b"]}"
#: A stream of entries, one line each, has no total work budget (docs/http-api.md,
#: "Batches"); a server without streams answers the whole JSON.
_ACCEPT = f"{NDJSON_MEDIA_TYPE}, application/json;q=0.5"


@dataclass(frozen=True)
class Chunk:
    """Jobs ``start .. start + len(jobs)`` of a batch, encoded."""

    start: int
    jobs: Sequence[bytes]

    @property
    def body(self) -> bytes:
        return _OPEN + _SEP.join(self.jobs) + _CLOSE


@dataclass(frozen=True)
class BatchPlan:
    """A batch of one kind of request, cut into chunks; ``call(chunk)`` sends one."""

    kind: Kind
    chunks: list[Chunk]
    size: int

    def call(self, chunk: Chunk) -> Call[list[Entry]]:
        path = ENDPOINTS[self.kind][1]
        assert path is not None
        return Call("POST", path, chunk.body, _ACCEPT, _entries_reader(self.kind, len(chunk.jobs)))


def plan(kind: Kind, requests: Iterable[AnyRequest], max_jobs: int, max_bytes: int) -> BatchPlan:
    """The chunks of a batch of spirals or of paths (drawings have no batch endpoint)."""
    jobs: list[bytes] = []
    for i, request in enumerate(requests):
        given = kind_of(request)
        if given != kind:
            raise ValueError(f"request {i} is a {given} request; this batch takes {kind} ones")
        jobs.append(encode(request))
    return BatchPlan(kind, pack(jobs, 0, max_jobs, max_bytes), len(jobs))


def pack(jobs: Sequence[bytes], start: int, max_jobs: int, max_bytes: int) -> list[Chunk]:
    """Consecutive chunks of at most ``max_jobs`` jobs and (but for a single job larger than
    that) ``max_bytes`` of body."""
    chunks: list[Chunk] = []
    begin, size = 0, len(_OPEN) + len(_CLOSE)
    for i, job in enumerate(jobs):
        grown = size + len(job) + (1 if i > begin else 0)
        if i > begin and (i - begin >= max_jobs or grown > max_bytes):
            chunks.append(Chunk(start + begin, jobs[begin:i]))
            begin, grown = i, len(_OPEN) + len(_CLOSE) + len(job)
        size = grown
    if begin < len(jobs):
        chunks.append(Chunk(start + begin, jobs[begin:]))
    return chunks


def split(chunk: Chunk, error: ServiceError) -> list[Chunk] | None:
    """Smaller chunks to send instead of one the service refused as too large, or ``None``
    if the refusal is not about size (or a single job is itself too large). Each is
    smaller than ``chunk``, so splitting ends, whatever limit the refusal names."""
    if error.status != 413 or len(chunk.jobs) == 1:
        return None
    limit = error.limit if error.kind == "too-many-jobs" else None
    if limit is not None and 1 <= limit < len(chunk.jobs):
        return pack(chunk.jobs, chunk.start, int(limit), 2**62)
    half = len(chunk.jobs) // 2
    return [Chunk(chunk.start, chunk.jobs[:half]), Chunk(chunk.start + half, chunk.jobs[half:])]


#: What sending a chunk ended with: its entries, or the failure of the whole chunk.
Outcome: TypeAlias = list[Entry] | ServiceError | httpx.TransportError


_MODELS: dict[Kind, type[BatchResponse | PathBatchResponse]] = {
    "spiral": BatchResponse,
    "path": PathBatchResponse,
}
#: Each kind's entry (``results[i]``, one line of a stream), validated from its JSON bytes.
_ENTRIES: dict[Kind, TypeAdapter[Any]] = {
    kind: TypeAdapter(get_args(model.model_fields["results"].annotation)[0])
    for kind, model in _MODELS.items()
}


def _entries_reader(kind: Kind, jobs: int) -> Callable[[httpx.Response], list[Entry]]:
    """Reads a chunk's answer of ``jobs`` entries: a stream (a line each) or one JSON."""
    model, entry = _MODELS[kind], _ENTRIES[kind]

    def read(response: httpx.Response) -> list[Entry]:
        media_type = response.headers.get("content-type", "").split(";", 1)[0].strip()
        with gc_paused():
            if media_type == NDJSON_MEDIA_TYPE:
                lines = response.content.split(b"\n")
                entries = [entry.validate_json(line) for line in lines if line.strip()]
            else:
                entries = list(model.model_validate_json(response.content).results)
        if len(entries) != jobs:
            raise httpx.RemoteProtocolError(
                f"the answer ended after {len(entries)} of its {jobs} entries"
            )
        return [e.result if e.status == "ok" else ServiceError(e.error) for e in entries]

    return read


class Results:
    """A batch's answers as they arrive, in the jobs' order."""

    def __init__(self, size: int) -> None:
        self._entries: list[Entry | None] = [None] * size

    def fill(self, chunk: Chunk, outcome: Outcome) -> None:
        for i in range(len(chunk.jobs)):
            self._entries[chunk.start + i] = (
                outcome if isinstance(outcome, Exception) else outcome[i]
            )

    def done(self) -> list[Entry]:
        entries = [entry for entry in self._entries if entry is not None]
        assert len(entries) == len(self._entries), "every chunk was answered"
        return entries


def settle(results: Results, chunk: Chunk, outcome: Outcome) -> list[Chunk]:
    """Records ``chunk``'s outcome in ``results``; the chunks to send in its place when the
    service refused it as too large (none otherwise: a failure of the whole chunk becomes
    the entry of each of its jobs)."""
    if isinstance(outcome, ServiceError):
        smaller = split(chunk, outcome)
        if smaller is not None:
            return smaller
    results.fill(chunk, outcome)
    return []
