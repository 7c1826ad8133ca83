"""Every 4xx and 5xx answer as RFC 9457 problem details (``application/problem+json``).

A problem has ``type`` (a URI naming its kind), ``title``, ``status`` and ``detail``, and
where it applies ``errors`` (each naming the field path and the reason), ``limit`` (the
bound that was crossed) and ``request_id`` (the ``X-Request-ID`` of the request). The
``kind`` of each problem is also the label of the ``arcspline_errors_total`` metric.
"""

from __future__ import annotations

import http
import logging
import re
from collections.abc import Iterable, Mapping, Sequence
from typing import Any

import orjson
from asgi_correlation_id import correlation_id
from fastapi import FastAPI, Request
from fastapi.exceptions import RequestValidationError
from starlette.exceptions import HTTPException
from starlette.requests import ClientDisconnect
from starlette.responses import JSONResponse, Response

from arcspline.geometry import GeometryError
from arcspline.outputs.gcode import GcodeError
from arcspline.worker.pool import JobTimeoutError, PoolError, QueueFullError

from .path_schemas import PATH_TAGS
from .schemas import SPIRAL_TAGS

_UNION_TAGS = frozenset((*SPIRAL_TAGS, *PATH_TAGS))

log = logging.getLogger(__name__)

PROBLEM_MEDIA_TYPE = "application/problem+json"
REQUEST_ID_HEADER = "X-Request-ID"
TYPE_PREFIX = "urn:arcspline:problem:"

#: kind -> (status, title). Plain HTTP errors (404, 405, ...) use ``about:blank``.
KINDS: dict[str, tuple[int, str]] = {
    "malformed_json": (400, "Malformed JSON"),
    "malformed_http": (400, "Malformed HTTP request"),
    "request_timeout": (408, "Request timeout"),
    "headers_too_large": (431, "Request header fields too large"),
    "body_too_large": (413, "Request body too large"),
    "too_many_jobs": (413, "Too many jobs"),
    "work_too_large": (413, "Too much work for one batch"),
    "validation": (422, "Invalid request"),
    "invalid_input": (422, "Invalid curve"),
    "tolerance_floor": (422, "Tolerance below what can be reached"),
    "segment_limit": (422, "Too many segments"),
    "precision": (422, "Beyond double precision"),
    "tool_too_large": (422, "Tool too large"),
    "gcode": (422, "G-code cannot be written"),
    "invalid_document": (422, "Invalid document"),
    "unsupported_media_type": (415, "Unsupported media type"),
    "not_acceptable": (406, "Not acceptable"),
    "internal": (500, "Internal server error"),
    "queue_full": (503, "Server busy"),
    "too_many_connections": (503, "Too many connections"),
    "pool_unavailable": (503, "Workers unavailable"),
    "not_ready": (503, "Not ready"),
    "shutting_down": (503, "Shutting down"),
    "time_limit": (504, "Time limit exceeded"),
}
HTTP_KINDS = {404: "not_found", 405: "method_not_allowed", 413: "body_too_large"}
ALL_KINDS = (*KINDS, "not_found", "method_not_allowed", "http_error")

Loc = list[str | int]


class RawJSONResponse(JSONResponse):
    """JSON rendered by orjson; ``bytes`` content is taken as already-encoded JSON."""

    def render(self, content: Any) -> bytes:
        if isinstance(content, bytes):
            return content
        return orjson.dumps(content)


class ProblemJSONResponse(RawJSONResponse):
    media_type = PROBLEM_MEDIA_TYPE


class ProblemError(Exception):
    """Raised by routes to answer with a problem; carries its body and extra headers."""

    def __init__(self, problem: dict[str, Any], headers: Mapping[str, str] | None = None) -> None:
        super().__init__(problem["detail"])
        self.problem = problem
        self.headers = dict(headers or {})


def problem(
    kind: str,
    detail: str,
    *,
    status: int | None = None,
    title: str | None = None,
    errors: Sequence[dict[str, Any]] | None = None,
    limit: float | None = None,
) -> dict[str, Any]:
    """A problem body; ``status``/``title`` default to those of ``kind``."""
    known = KINDS.get(kind)
    if known is not None:
        type_ = TYPE_PREFIX + kind.replace("_", "-")
        status = status or known[0]
        title = title or known[1]
    else:
        type_ = "about:blank"
        assert status is not None, "a plain HTTP problem needs its status"
        title = title or http.HTTPStatus(status).phrase
    body: dict[str, Any] = {"type": type_, "title": title, "status": status, "detail": detail}
    request_id = correlation_id.get()
    if request_id:
        body["request_id"] = request_id
    if errors:
        body["errors"] = list(errors)
    if limit is not None:
        body["limit"] = limit
    return body


def problem_kind(body: Mapping[str, Any]) -> str:
    """The metric label of a problem body."""
    type_ = str(body["type"])
    if type_.startswith(TYPE_PREFIX):
        return type_.removeprefix(TYPE_PREFIX).replace("-", "_")
    return HTTP_KINDS.get(int(body["status"]), "http_error")


def problem_response(
    body: dict[str, Any], request: Request | None = None, headers: Mapping[str, str] | None = None
) -> ProblemJSONResponse:
    """The response for ``body``, counted in the error metrics when a request is given."""
    if request is not None:
        request.app.state.runtime.metrics.error(problem_kind(body))
    return ProblemJSONResponse(body, status_code=int(body["status"]), headers=headers)


_RESPONSE_DESCRIPTIONS = {
    400: "Malformed JSON",
    406: "The Accept header names no output the endpoint gives",
    413: "Request body too large, too many jobs, or too much work for one batch",
    415: "The body's media type is not one the endpoint reads",
    422: "Invalid request: the errors name each field",
    503: "Busy (queue full; see Retry-After) or workers unavailable",
    504: "Time limit exceeded",
}


def problem_responses(*statuses: int) -> dict[int | str, dict[str, Any]]:
    """OpenAPI ``responses`` entries for problems answered with these statuses."""
    schema = {"$ref": "#/components/schemas/ProblemResponse"}
    return {
        status: {
            "description": _RESPONSE_DESCRIPTIONS[status],
            "content": {PROBLEM_MEDIA_TYPE: {"schema": schema}},
        }
        for status in statuses
    }


# -- field paths -------------------------------------------------------------------------

_SPIRAL_FIELDS = {"start", "start_tangent", "turn_angle_deg", "end_curvature", "control_points"}
_CORE_FIELD = re.compile(r"(?P<name>[A-Za-z_]\w*)(?:\[(?P<index>\d+)\])?")


def core_field_loc(field: str) -> Loc:
    """The request path of a core parameter: ``control_points[2]`` → spiral.control_points.2."""
    if field.startswith(("path", "toolpaths", "offset.", "machining.")):
        # path.subpaths[0].segments[3] → path.subpaths.0.segments.3 (toolpaths[2] alike)
        return [int(part) if part.isdigit() else part for part in re.findall(r"\w+", field)]
    match = _CORE_FIELD.fullmatch(field)
    if match is None:
        return [field]
    name, index = match["name"], match["index"]
    loc: Loc = ["spiral", name] if name in _SPIRAL_FIELDS else [name]
    if index is not None:
        loc.append(int(index))
    return loc


def clean_loc(loc: Iterable[str | int]) -> Loc:
    """A validation path as the client wrote it (without the tags of the spiral, path and
    segment unions)."""
    return [part for part in loc if part not in _UNION_TAGS]


def dotted(loc: Sequence[str | int]) -> str:
    return ".".join(str(part) for part in loc)


#: Most errors a problem lists, and the longest name or message in each
#: (docs/errors.md#limits-of-a-problem): 2 MB of unknown fields answered 15 MB of errors.
MAX_ERRORS = 50
MAX_ERROR_TEXT = 200


def _cut(text: str) -> str:
    return text if len(text) <= MAX_ERROR_TEXT else text[: MAX_ERROR_TEXT - 1] + "…"


#: pydantic's messages that name a class of the code (a batch's jobs are validated from
#: Python objects: "... instance of ApproximateRequest"), said as JSON mode says them.
_PLAIN_MESSAGES = {"model_type": "Input should be an object"}


def _message(error: Mapping[str, Any]) -> str:
    return _cut(_PLAIN_MESSAGES.get(str(error["type"])) or str(error["msg"]))


def validation_problem(errors: Sequence[Mapping[str, Any]], prefix: Loc) -> dict[str, Any]:
    """422 for pydantic errors; ``prefix`` is prepended to each path. The first
    :data:`MAX_ERRORS` are listed (``errors_omitted`` counts the rest), each name in a path
    and each message cut to :data:`MAX_ERROR_TEXT` characters."""
    items = [
        {
            "loc": [_cut(p) if isinstance(p, str) else p for p in [*prefix, *clean_loc(e["loc"])]],
            "msg": _message(e),
            "type": str(e["type"]),
        }
        for e in errors[:MAX_ERRORS]
    ]
    shown = "; ".join(f"{dotted(i['loc'])}: {i['msg']}" for i in items[:3])
    more = f" (and {len(errors) - 3} more)" if len(errors) > 3 else ""
    body = problem("validation", f"{len(errors)} invalid field(s): {shown}{more}", errors=items)
    if len(errors) > MAX_ERRORS:
        body["errors_omitted"] = len(errors) - MAX_ERRORS
    return body


#: What the core and the writers call the whole curve when they refuse all of it (a result
#: double precision cannot hold): the request's own field for it is named instead.
_WHOLE_CURVE = frozenset({"spiral", "parts"})


def geometry_problem(error: GeometryError, prefix: Loc, curve: str = "spiral") -> dict[str, Any]:
    """422 for a :class:`GeometryError`, naming the field by its request path (``curve``:
    the request's field that holds the curve)."""
    field = curve if error.field in _WHOLE_CURVE else error.field
    loc = [*prefix, *core_field_loc(field)]
    detail = f"{dotted(loc)}: {error.message}"
    if error.limit is not None and error.kind in ("tolerance_floor", "segment_limit"):
        detail += f" (limit: {error.limit:g})"
    kind = error.kind if error.kind in KINDS else "invalid_input"
    item = {"loc": loc, "msg": error.message, "type": error.kind}
    return problem(kind, detail, errors=[item], limit=error.limit)


def gcode_problem(error: GcodeError, prefix: Loc, curve: str = "spiral") -> dict[str, Any]:
    """422 for a :class:`GcodeError`: the field is a ``gcode`` option, or the curve itself
    (the request's ``curve`` field: ``spiral`` or ``path``) when it cannot be written at all
    (coordinates beyond what a controller takes)."""
    parts = str(error.field).split(".")
    if parts[0] == "spiral":
        parts = [curve, *parts[1:]]
    elif parts[0] != "gcode":
        parts = ["gcode", *parts]
    loc: Loc = [*prefix, *parts]
    item = {"loc": loc, "msg": error.message, "type": "gcode"}
    return problem("gcode", f"{dotted(loc)}: {error.message}", errors=[item])


def pool_problem(error: PoolError) -> tuple[dict[str, Any], dict[str, str]]:
    """503 (busy, unavailable) or 504 (time limit), with ``Retry-After`` where it helps."""
    if isinstance(error, JobTimeoutError):
        return problem("time_limit", str(error), limit=error.time_limit_s), {}
    kind = "queue_full" if isinstance(error, QueueFullError) else "pool_unavailable"
    retry_after = error.retry_after_s if error.retry_after_s is not None else 1
    detail = f"{error}; retry in {retry_after:g} s"
    return problem(kind, detail), {"Retry-After": str(max(1, round(retry_after)))}


# -- handlers ----------------------------------------------------------------------------


async def _on_validation_error(request: Request, exc: Exception) -> Response:
    # Bodies are parsed by routing.LeanRoute: JSON it cannot parse is a malformed_json
    # problem already; what is left here are the fields that fail validation.
    assert isinstance(exc, RequestValidationError)
    return problem_response(validation_problem(exc.errors(), []), request)


async def _on_http_error(request: Request, exc: Exception) -> Response:
    assert isinstance(exc, HTTPException)
    status = exc.status_code
    if status == 413:
        body = problem("body_too_large", str(exc.detail))
        body["limit"] = request.app.state.runtime.settings.max_body_bytes
    else:
        detail = exc.detail if isinstance(exc.detail, str) else http.HTTPStatus(status).phrase
        body = problem("http", detail, status=status)
    return problem_response(body, request, headers=exc.headers)


async def _on_problem(request: Request, exc: Exception) -> Response:
    assert isinstance(exc, ProblemError)
    return problem_response(exc.problem, request, headers=exc.headers)


async def _on_pool_error(request: Request, exc: Exception) -> Response:
    assert isinstance(exc, PoolError)
    body, headers = pool_problem(exc)
    return problem_response(body, request, headers=headers)


async def _on_client_disconnect(request: Request, exc: Exception) -> Response:
    # The client left while its body was arriving (or timed out sending it): no one reads
    # this answer (the server drops it), and nothing went wrong here worth a traceback.
    log.debug("the client disconnected before its body was read")
    return problem_response(problem("http", "client closed request", status=400), request)


async def _on_unexpected(request: Request, exc: Exception) -> Response:
    log.error("unhandled error", exc_info=exc)
    body = problem("internal", "an unexpected error occurred; it has been logged")
    # Starlette answers this one outside every middleware: the request id's too.
    request_id = body.get("request_id")
    headers = {REQUEST_ID_HEADER: request_id} if request_id else None
    return problem_response(body, request, headers=headers)


def install_error_handlers(app: FastAPI) -> None:
    """Route every error the app can raise to a problem response."""
    app.add_exception_handler(RequestValidationError, _on_validation_error)
    app.add_exception_handler(HTTPException, _on_http_error)
    app.add_exception_handler(ProblemError, _on_problem)
    app.add_exception_handler(PoolError, _on_pool_error)
    app.add_exception_handler(ClientDisconnect, _on_client_disconnect)
    app.add_exception_handler(Exception, _on_unexpected)
