"""The OpenAPI document's own parts, beyond what FastAPI derives from the routes: who and
what (version, licence, contact, servers, tags), the response headers every answer carries,
and how the approximate endpoints' answers are declared (JSON, or one document alone).

The headers are added to every response of every operation once, here, when the document is
built (:func:`finish`), rather than route by route, so that no route can forget them.
"""

from __future__ import annotations

from importlib.metadata import version
from typing import Any

from .examples import OPERATIONS
from .schemas import NDJSON_MEDIA_TYPE, OUTPUT_FORMATS, OUTPUT_MEDIA_TYPES

#: ``info.version``: the package's version (the contract is versioned with the code).
VERSION = version("arcspline")

DESCRIPTION = """\
Approximates planar curves by G1 arc splines within a tolerance, for CNC tool paths: the cubic
Bézier spirals of D.J. Walton, D.S. Meek, *Approximation of a planar cubic Bézier spiral by
circular arcs*, J. Comput. Appl. Math. 75 (1996) 47–56; any path (lines, Béziers, circular and
elliptical arcs); whole SVG and DXF drawings. Each answer is JSON, or one document alone — a
G-code program, a DXF, an SVG — by the body's `output`, the `output` query parameter or the
Accept header. (Client generators that keep one media type per answer, such as
openapi-python-client, read the JSON one; for a document alone, read the body as bytes.)

Every error is RFC 9457 problem details (`application/problem+json`). Every response carries
`X-Request-ID` (yours if it is a UUID, else a new one). The bounds the schemas show for batch
sizes and documents are the server's defaults; its configured limits apply (413, 422)."""

LICENSE = {"name": "MIT", "identifier": "MIT"}
CONTACT = {"name": "arcspline maintainers"}
SERVERS = [
    {"url": "/", "description": "This server (where the document was read from)"},
    {
        "url": "http://127.0.0.1:8000",
        "description": "The default of `make run` (ARCSPLINE_HOST, ARCSPLINE_PORT)",
    },
]
TAGS = [
    {
        "name": "approximation",
        "description": "Cubic Bézier spirals (Walton & Meek 1996): one, many, or a picture.",
    },
    {
        "name": "paths",
        "description": "Any path — SVG path data or typed segments — one arc spline per "
        "subpath: one, many, or a picture.",
    },
    {
        "name": "drawings",
        "description": "Whole SVG and DXF documents, joined into toolpaths in cutting order.",
    },
    {
        "name": "operations",
        "description": "Liveness and readiness probes, and Prometheus metrics.",
    },
]

_HEADERS: dict[str, dict[str, Any]] = {
    "X-Request-ID": {
        "description": "The request's id: the client's own `X-Request-ID` if it is a UUID, "
        "else a new one (32 hex digits). Logs and problem details carry it too.",
        "required": True,
        "schema": {"type": "string"},
    },
    "Retry-After": {
        "description": "Seconds to wait before trying again (ARCSPLINE_RETRY_AFTER_S).",
        "required": True,
        "schema": {"type": "integer", "minimum": 1},
    },
    "Content-Disposition": {
        "description": 'With one document alone: `attachment; filename="spiral.ngc"` '
        "(`.dxf`, `.svg`; `path.*` and `drawing.*` for paths and drawings). Not sent with JSON.",
        "required": False,
        "schema": {"type": "string"},
    },
}


def header(name: str) -> dict[str, str]:
    """A reference to one of the shared response headers."""
    assert name in _HEADERS
    return {"$ref": f"#/components/headers/{name}"}


#: The ``output`` query parameter of the approximate endpoints.
OUTPUT_PARAMETER: dict[str, Any] = {
    "name": "output",
    "in": "query",
    "required": False,
    "description": "The answer, as the body's `output` field (which wins when both are given): "
    "for curl users who would rather not edit the body. Without either, the Accept header "
    "chooses (`text/x-gcode`, `image/vnd.dxf` or `application/dxf`, `image/svg+xml`, "
    "`application/json`), else JSON.",
    "schema": {"type": "string", "enum": list(OUTPUT_FORMATS)},
}


def answers(description: str) -> dict[int | str, dict[str, Any]]:
    """The 200 of an approximate endpoint: JSON (its schema is the route's response model),
    or one document alone, each media type it can be."""
    documents = {
        media_type: {"schema": {"type": "string"}}
        for name, media_type in OUTPUT_MEDIA_TYPES.items()
        if name != "json"
    }
    return {
        200: {
            "description": description,
            "headers": {"Content-Disposition": header("Content-Disposition")},
            "content": {OUTPUT_MEDIA_TYPES["json"]: {}, **documents},
        }
    }


def batch_answers(description: str, ok_entry: str) -> dict[int | str, dict[str, Any]]:
    """The 200 of a batch endpoint: JSON (the route's response model), or NDJSON when
    ``Accept`` asks for it — each line one entry of ``results`` (``ok_entry``: the schema
    of an ``ok`` entry), in the order of the jobs (docs/http-api.md, "Batches")."""
    ok, error = f"#/components/schemas/{ok_entry}", "#/components/schemas/BatchErrorResponse"
    line = {
        "oneOf": [{"$ref": ok}, {"$ref": error}],
        "discriminator": {"propertyName": "status", "mapping": {"ok": ok, "error": error}},
    }
    return {
        200: {
            "description": f"{description}: one JSON document, or with `Accept: "
            f"{NDJSON_MEDIA_TYPE}` one line per job, sent as the jobs finish",
            "content": {OUTPUT_MEDIA_TYPES["json"]: {}, NDJSON_MEDIA_TYPE: {"schema": line}},
        }
    }


def _add_examples(operation: dict[str, Any]) -> None:
    """The operation's examples (:data:`.examples.OPERATIONS`): of its JSON body, and of its
    200 answer by media type. Added to the finished document, not through FastAPI, which
    drops every ``null`` from what it is given (and answers hold ``"gcode": null``)."""
    for where, named in OPERATIONS.get(operation["operationId"], {}).items():
        if where == "request":
            operation["requestBody"]["content"]["application/json"]["examples"] = named
        else:
            operation["responses"]["200"]["content"][where]["examples"] = named


def finish(document: dict[str, Any]) -> dict[str, Any]:
    """``document`` with its examples, the shared headers declared on every response
    (``X-Request-ID``; ``Retry-After`` on 503), and no security (the service has none: it
    is meant to run behind whatever guards the network it serves)."""
    document.setdefault("components", {})["headers"] = _HEADERS
    document["security"] = []
    for item in document["paths"].values():
        for operation in item.values():
            _add_examples(operation)
            for status, response in operation["responses"].items():
                headers = response.setdefault("headers", {})
                headers["X-Request-ID"] = header("X-Request-ID")
                if status == "503":
                    headers["Retry-After"] = header("Retry-After")
    return document
