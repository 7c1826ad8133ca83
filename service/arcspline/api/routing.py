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
``malformed_json`` problem.
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
from starlette.requests import ClientDisconnect
from starlette.responses import Response

from .errors import ProblemError, problem

Endpoint = Callable[..., Awaitable[Response]]


class LeanRoute(APIRoute):
    """An :class:`APIRoute` whose endpoint takes only a ``Request`` and/or one body model and
    returns a ``Response``; anything else is refused when the route is declared."""

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


async def json_body(request: Request, adapter: TypeAdapter[Any]) -> Any:
    """The request's JSON body validated by ``adapter``, as FastAPI would take it: an empty
    body is a missing one, a body not declared as JSON is not an object."""
    raw = await read_body(request)
    if not raw:
        missing = {"type": "missing", "loc": ("body",), "msg": "Field required", "input": None}
        raise RequestValidationError([missing])
    try:
        if is_json(request.headers.get("content-type")):
            return adapter.validate_json(raw)
        return adapter.validate_python(raw)  # bytes: "a valid dictionary" is what fails
    except ValidationError as error:
        errors = error.errors(include_url=False)
        malformed = next((e for e in errors if e["type"] == "json_invalid"), None)
        if malformed is not None:
            reason = str(malformed["msg"]).removeprefix("Invalid JSON: ")
            detail = f"the body is not valid JSON: {_plainly(reason)}"
            raise ProblemError(problem("malformed_json", detail)) from None
        raise RequestValidationError([{**e, "loc": ("body", *e["loc"])} for e in errors]) from None


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
