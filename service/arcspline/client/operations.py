"""The service's operations, without I/O: for each, the request to send and how to read the
answer. :class:`~arcspline.client.Client` and :class:`~arcspline.client.AsyncClient` differ
only in how they send (docs/client.md).

A request is the server's own model (``ApproximateRequest``, ``PathRequest``,
``DrawingRequest``) or a plain mapping of the same JSON; which endpoint it goes to follows
from its kind (the ``spiral``, ``path`` or ``document`` field).
"""

from __future__ import annotations

import re
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import Any, Generic, Literal, NamedTuple, TypeAlias, TypeVar

import httpx
import orjson
from pydantic import BaseModel

from arcspline.api.drawing_schemas import DrawingRequest, DrawingResponse
from arcspline.api.path_schemas import PathRequest, PathResponse
from arcspline.api.schemas import (
    OUTPUT_MEDIA_TYPES,
    ApproximateRequest,
    ApproximateResponse,
    HealthResponse,
    OutputFormat,
    ReadyResponse,
)

T = TypeVar("T")
M = TypeVar("M", bound=BaseModel)

Kind = Literal["spiral", "path", "drawing"]
#: What an approximation can be answered with: its JSON as the service wrote it, or one
#: document alone.
Output = OutputFormat
AnyRequest: TypeAlias = ApproximateRequest | PathRequest | DrawingRequest | Mapping[str, Any]

#: Each kind's endpoints: approximate, batch (none for drawings), preview.
ENDPOINTS: dict[Kind, tuple[str, str | None, str]] = {
    "spiral": ("/v1/approximate", "/v1/approximate/batch", "/v1/preview"),
    "path": ("/v1/paths/approximate", "/v1/paths/batch", "/v1/paths/preview"),
    "drawing": ("/v1/drawings/approximate", None, "/v1/drawings/preview"),
}
_MODELS: dict[type[BaseModel], Kind] = {
    ApproximateRequest: "spiral",
    PathRequest: "path",
    DrawingRequest: "drawing",
}
_CURVE_FIELDS: dict[str, Kind] = {"spiral": "spiral", "path": "path", "document": "drawing"}


@dataclass(frozen=True)
class Call(Generic[T]):
    """One HTTP exchange: what to send, and how to read a successful answer."""

    method: str
    path: str
    body: bytes | None
    accept: str
    read: Callable[[httpx.Response], T]
    #: Whether a busy answer or a dropped connection is tried again (not for the probes,
    #: whose answer is meant to be now).
    retried: bool = True

    @property
    def headers(self) -> dict[str, str]:
        headers = {"Accept": self.accept}
        if self.body is not None:
            headers["Content-Type"] = "application/json"
        return headers


class Document(NamedTuple):
    """A document answered alone: its bytes, media type and the file name the service
    suggests (``Content-Disposition``)."""

    content: bytes
    media_type: str
    filename: str | None


def kind_of(request: AnyRequest) -> Kind:
    """Which kind of curve ``request`` asks about (``ValueError`` if none)."""
    if isinstance(request, BaseModel):
        kind = _MODELS.get(type(request))
        if kind is not None:
            return kind
    elif isinstance(request, Mapping):
        for field, kind in _CURVE_FIELDS.items():
            if field in request:
                return kind
    raise ValueError(
        "a request is an ApproximateRequest, PathRequest or DrawingRequest, or a mapping with "
        "a 'spiral', 'path' or 'document' field"
    )


def encode(request: AnyRequest, **fields: Any) -> bytes:
    """``request`` as JSON (only the fields it sets), with ``fields`` added."""
    if isinstance(request, BaseModel):
        body: dict[str, Any] = request.model_dump(mode="json", exclude_unset=True)
    else:
        body = dict(request)
    body.update(fields)
    return orjson.dumps(body)


def model_reader(model: type[M]) -> Callable[[httpx.Response], M]:
    def read(response: httpx.Response) -> M:
        return model.model_validate_json(response.content)

    return read


def _read_text(response: httpx.Response) -> str:
    return response.text


_FILENAME = re.compile(r'filename="?([^";]+)"?')


def read_document(response: httpx.Response) -> Document:
    return read_streamed(response)._replace(content=response.content)


def read_streamed(response: httpx.Response) -> Document:
    """A document streamed into a file: its media type and name (no content kept)."""
    disposition = _FILENAME.search(response.headers.get("content-disposition", ""))
    media_type = response.headers.get("content-type", "").split(";", 1)[0].strip()
    return Document(b"", media_type, disposition[1] if disposition else None)


def approximate(request: AnyRequest) -> Call[ApproximateResponse]:
    return _post("spiral", request, model_reader(ApproximateResponse))


def approximate_path(request: AnyRequest) -> Call[PathResponse]:
    return _post("path", request, model_reader(PathResponse))


def approximate_drawing(request: AnyRequest) -> Call[DrawingResponse]:
    return _post("drawing", request, model_reader(DrawingResponse))


def _post(kind: Kind, request: AnyRequest, read: Callable[[httpx.Response], T]) -> Call[T]:
    given = kind_of(request)
    if given != kind:
        raise ValueError(f"this operation takes a {kind} request, not a {given} one")
    return Call("POST", ENDPOINTS[kind][0], encode(request), "application/json", read)


def document(request: AnyRequest, output: Output) -> Call[Document]:
    """The G-code program, DXF or SVG of ``request``'s approximation, alone (or its JSON,
    as the service's bytes)."""
    path = ENDPOINTS[kind_of(request)][0]
    body = encode(request, output=output)
    return Call("POST", path, body, OUTPUT_MEDIA_TYPES[output], read_document)


def preview(request: AnyRequest) -> Call[str]:
    """The picture of ``request``'s approximation (SVG text)."""
    path = ENDPOINTS[kind_of(request)][2]
    return Call("POST", path, encode(request), "image/svg+xml", _read_text)


def health() -> Call[HealthResponse]:
    return Call(
        "GET", "/healthz", None, "application/json", model_reader(HealthResponse), retried=False
    )


def ready() -> Call[ReadyResponse]:
    return Call(
        "GET", "/readyz", None, "application/json", model_reader(ReadyResponse), retried=False
    )
