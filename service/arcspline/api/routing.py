"""The route class of every endpoint: FastAPI's declaration with a lean request path.

FastAPI's own request handler, for every request, solves the dependency tree (reading the
query string, headers and cookies for each level), enters exit stacks and telemetry, and
parses a JSON body with the standard library before pydantic validates the result: tens of
microseconds that the endpoints here do not need. :class:`LeanRoute` keeps FastAPI's route
declaration — path, OpenAPI document, response classes, exception handlers — and calls the
endpoint directly with what its signature asks for: the :class:`Request`, and at most one
JSON body model, validated by pydantic-core straight from the bytes
(``TypeAdapter.validate_json``). Failures are what FastAPI raises for a body: a
:class:`RequestValidationError` with paths under ``body``; a body that is not JSON at all is a
``malformed_json`` problem, one not declared JSON an ``unsupported_media_type`` one (415, which
the route declares in its contract).
"""

from __future__ import annotations

import inspect
import typing
from collections.abc import Awaitable, Callable
from typing import Any

from fastapi import Request
from fastapi.exceptions import RequestValidationError
from fastapi.routing import APIRoute
from pydantic import BaseModel, TypeAdapter, ValidationError
from starlette.concurrency import run_in_threadpool
from starlette.requests import ClientDisconnect
from starlette.responses import Response

from .duplicates import (
    MAX_MEMBERS,
    DuplicateKey,
    TooManyMembersError,
    first_duplicate,
    has_duplicate,
)
from .errors import ProblemError, problem, problem_responses, validation_problem

Endpoint = Callable[..., Awaitable[Response]]


class LeanRoute(APIRoute):
    """An :class:`APIRoute` whose endpoint takes only a ``Request`` and/or one body model and
    returns a ``Response``; anything else is refused when the route is declared."""

    def __init__(self, path: str, endpoint: Endpoint, **kwargs: Any) -> None:
        if _parameters(endpoint)[1] is not None:  # a body: 415 if it is not JSON
            kwargs["responses"] = {**(kwargs.get("responses") or {}), **problem_responses(415)}
        super().__init__(path, endpoint, **kwargs)

    def get_route_handler(self) -> Callable[[Request], typing.Coroutine[Any, Any, Response]]:
        endpoint: Endpoint = self.endpoint
        request_name, body = _parameters(endpoint)

        async def handler(request: Request) -> Response:
            arguments: dict[str, Any] = {}
            if request_name is not None:
                arguments[request_name] = request
            if body is not None:
                name, adapter = body
                arguments[name] = await json_body(request, adapter)
            return await endpoint(**arguments)

        return handler


def _parameters(endpoint: Endpoint) -> tuple[str | None, tuple[str, TypeAdapter[Any]] | None]:
    """The names of ``endpoint``'s ``Request`` parameter and of its body model, with a
    validator for the body."""
    hints = typing.get_type_hints(endpoint)
    request_name: str | None = None
    body: tuple[str, TypeAdapter[Any]] | None = None
    for name in inspect.signature(endpoint).parameters:
        kind = hints.get(name)
        if kind is Request:
            request_name = name
        elif isinstance(kind, type) and issubclass(kind, BaseModel) and body is None:
            body = name, TypeAdapter(kind)
        else:
            raise TypeError(
                f"{endpoint.__qualname__}: a LeanRoute endpoint takes the Request and at most "
                f"one body model; {name!r} is neither"
            )
    return request_name, body


async def read_body(request: Request) -> bytes:
    """The request's body: ``Request.body()`` without its stream machinery (nothing else
    reads these bodies)."""
    chunks: list[bytes] = []
    while True:
        message = await request.receive()
        if message["type"] != "http.request":  # the client went away
            raise ClientDisconnect()
        chunks.append(message.get("body", b""))
        if not message.get("more_body", False):
            return chunks[0] if len(chunks) == 1 else b"".join(chunks)


def is_json(content_type: str | None) -> bool:
    if not content_type:
        return False
    media = content_type.split(";", 1)[0].strip().lower()
    maintype, _, subtype = media.partition("/")
    return maintype == "application" and (subtype == "json" or subtype.endswith("+json"))


def unsupported_media_type(content_type: str | None) -> ProblemError:
    """415 for a body that is not declared JSON (docs/http-api.md#request-bodies): a body
    without a ``Content-Type`` too — nothing here reads one, and a browser may send a body
    with none without asking first (no CORS preflight)."""
    if not content_type:
        detail = (
            "the request has no Content-Type: send the body as application/json "
            "(curl: --json, or -H 'Content-Type: application/json'; -d alone sends "
            "application/x-www-form-urlencoded)"
        )
    else:
        media_type = content_type.split(";", 1)[0].strip()[:100]
        detail = (
            f"the body's media type {media_type!r} is not one this endpoint reads: "
            "application/json (or another JSON type, application/*+json)"
        )
    return ProblemError(problem("unsupported_media_type", detail))


#: Bodies larger than this are parsed and validated in a worker thread: a hostile 3 MB body
#: (200 000 unknown fields) takes some 0.9 s to check, validate and list its errors, which
#: on the event loop would stall every other request, /healthz included, for as long.
THREAD_BODY_BYTES = 64 * 1024


async def json_body(request: Request, adapter: TypeAdapter[Any]) -> Any:
    """The request's JSON body validated by ``adapter``, as FastAPI would take it (an empty
    body is a missing one), except: a body not declared JSON is a 415, and one that names a
    key twice in an object a 422 (:mod:`.duplicates`)."""
    raw = await read_body(request)
    if not raw:
        missing = {"type": "missing", "loc": ("body",), "msg": "Field required", "input": None}
        raise RequestValidationError([missing])
    content_type = request.headers.get("content-type")
    if not is_json(content_type):
        raise unsupported_media_type(content_type)
    if len(raw) > THREAD_BODY_BYTES:
        return await run_in_threadpool(parse_json, raw, adapter)
    return parse_json(raw, adapter)


def parse_json(raw: bytes, adapter: TypeAdapter[Any]) -> Any:
    """``raw`` validated by ``adapter``; a duplicated key, malformed JSON or invalid fields
    raised as their problems (:func:`json_body`)."""
    try:
        repeated = has_duplicate(raw)
    except TooManyMembersError as error:
        raise ProblemError(validation_problem([_too_many_members(error.members)], [])) from None
    if repeated:
        duplicate = first_duplicate(raw)
        if duplicate is not None:
            raise RequestValidationError([_duplicate_error(duplicate)])
    try:
        return adapter.validate_json(raw)
    except ValidationError as error:
        errors = error.errors(include_url=False)
        malformed = next((e for e in errors if e["type"] == "json_invalid"), None)
        if malformed is not None:
            reason = str(malformed["msg"]).removeprefix("Invalid JSON: ")
            detail = f"the body is not valid JSON: {_plainly(reason)}"
            raise ProblemError(problem("malformed_json", detail)) from None
        # The problem itself, made here: a hostile body's list of errors (one per unknown
        # field) is built, cut and freed in this function's thread, not on the event loop.
        body_errors = [{**e, "loc": ("body", *e["loc"])} for e in errors]
        raise ProblemError(validation_problem(body_errors, [])) from None


def _too_many_members(members: int) -> dict[str, Any]:
    return {
        "type": "too_many_members",
        "loc": ("body",),
        "msg": f"An object of the body has {members} members; at most {MAX_MEMBERS} are "
        "accepted (no request has more than a few dozen fields)",
    }


def _duplicate_error(duplicate: DuplicateKey) -> dict[str, Any]:
    return {
        "type": "duplicate_key",
        "loc": ("body", *duplicate.loc),
        "msg": f"Duplicate key: the object names it {duplicate.times} times (which value is "
        "meant is ambiguous)",
    }


#: pydantic-core's words for JSON it cannot take, said plainly (its own follow, with the
#: position).
_PLAIN_REASONS = {
    "recursion limit exceeded": "nested too deeply",
    "number out of range": "a number with too many digits",
    "invalid unicode code point": "not UTF-8 text",
}


def _plainly(reason: str) -> str:
    for words, plain in _PLAIN_REASONS.items():
        if reason.startswith(words):
            return f"{plain} ({reason})"
    return reason
