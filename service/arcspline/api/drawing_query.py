"""A raw document's request (``/v1/drawings/...`` with an SVG or DXF body): its options from
the query string — the request's fields, and the G-code and DXF options by their own names —
and how the contract declares them (each with its field's type and bounds; no value may be
longer than a number, a word or a flag needs, checked before anything is parsed)."""

from __future__ import annotations

import base64
from typing import Any

from fastapi.exceptions import RequestValidationError
from pydantic import BaseModel, ValidationError
from starlette.datastructures import QueryParams

from .contract import OUTPUT_PARAMETER
from .drawing_outputs import DOCUMENT_MEDIA_TYPES
from .drawing_schemas import MAX_LAYER_NAME, MAX_LAYERS, DrawingRequest, DxfRequest
from .negotiation import unknown_parameters
from .offset_query import TOOL_PARAMETERS, query_loc, tool_field, tool_fields
from .schemas import MAX_BODY_BYTES, GcodeRequest

#: Query parameters of a raw document: the request's fields, and the G-code options.
_GCODE_FIELDS = frozenset(GcodeRequest.model_fields) - {"units"}
_DXF_FIELDS = frozenset(DxfRequest.model_fields)
_FIELDS = frozenset(DrawingRequest.model_fields) - {
    "document", "encoding", "gcode", "dxf", "offset", "machining",
}  # fmt: skip
#: The offset's and the machining's options, by the names of :mod:`.offset_query`.
_TOOL_FIELDS = frozenset(TOOL_PARAMETERS)
#: Longest query value: a number, a word or a flag fits in far less (``layers``: every name).
QUERY_VALUE_MAX = 100
_LAYERS_MAX = MAX_LAYERS * (MAX_LAYER_NAME + 1)


def _max_length(name: str) -> int:
    return _LAYERS_MAX if name == "layers" else QUERY_VALUE_MAX


def _check_query(query: QueryParams) -> None:
    """Refuses parameters the endpoint does not take, and values longer than the contract
    says (before any is parsed)."""
    errors = unknown_parameters(set(query) - _FIELDS - _GCODE_FIELDS - _DXF_FIELDS - _TOOL_FIELDS)
    errors += [
        {
            "type": "string_too_long",
            "loc": ("query", name),
            "msg": f"String should have at most {_max_length(name)} characters",
        }
        for name, value in query.multi_items()
        if len(value) > _max_length(name)
    ]
    if errors:
        raise RequestValidationError(errors)


def from_query(query: QueryParams, media_type: str, raw: bytes) -> DrawingRequest:
    """The request of a raw document: its bytes (as base64, so binary DXF fits too), its
    format from the media type (or ``format``), the options from the query string."""
    _check_query(query)
    fields: dict[str, Any] = {k: v for k, v in query.items() if k in _FIELDS}
    if "layers" in fields:
        fields["layers"] = [name for name in fields["layers"].split(",") if name]
    gcode = {k: v for k, v in query.items() if k in _GCODE_FIELDS}
    if gcode:
        fields["gcode"] = {**gcode, "units": fields.get("units", "mm")}
    dxf = {k: v for k, v in query.items() if k in _DXF_FIELDS}
    if dxf:
        fields["dxf"] = dxf
    fields |= tool_fields(query)
    fields.setdefault("format", DOCUMENT_MEDIA_TYPES.get(media_type))
    fields["document"] = base64.b64encode(raw).decode()
    fields["encoding"] = "base64"
    try:
        # Lax: query values are strings ("0.01", "true").
        return DrawingRequest.model_validate(fields, strict=False)
    except ValidationError as error:
        errors = error.errors(include_url=False)
        raise RequestValidationError([{**e, "loc": query_loc(e["loc"])} for e in errors]) from None


def _value_schema(model: type[BaseModel], name: str) -> dict[str, Any]:
    """The JSON schema of a field's value, as a query parameter declares it: its type and
    bounds (``null``, titles and defaults left out), so that a generated client types
    ``tolerance`` as a number, ``decimals`` as an integer, ``comments`` as a flag."""
    schema = dict(model.model_json_schema()["properties"][name])
    for kept in schema.pop("anyOf", []):
        if kept.get("type") != "null":
            schema.update(kept)
    return {k: v for k, v in schema.items() if k not in ("title", "description", "default")}


def _query_parameter(name: str) -> dict[str, Any]:
    """A raw document's query parameter: the field of the same name, with its type and
    bounds (``layers`` as one comma-separated value)."""
    if name == "output":
        return OUTPUT_PARAMETER
    if name in _TOOL_FIELDS:
        return _tool_parameter(name)
    model: type[BaseModel] = (
        GcodeRequest
        if name in _GCODE_FIELDS
        else DxfRequest
        if name in _DXF_FIELDS
        else DrawingRequest
    )
    field = model.model_fields[name]
    where = {GcodeRequest: "gcode.", DxfRequest: "dxf."}.get(model, "")
    layers = " (comma-separated)" if name == "layers" else ""
    parameter = {
        "name": name,
        "in": "query",
        "required": False,
        "description": f"Only with a raw document (refused with a JSON body): `{where}{name}`"
        f"{layers}. {field.description or ''}".strip(),
        "schema": _value_schema(model, name),
    }
    if name == "layers":
        parameter |= {"style": "form", "explode": False}
    return parameter


def _tool_parameter(name: str) -> dict[str, Any]:
    """A raw document's offset or machining option (:mod:`.offset_query`)."""
    model, field_name, where = tool_field(name)
    also = " (or `machining.join`, with a machining option)" if name == "join" else ""
    description = model.model_fields[field_name].description or ""
    return {
        "name": name,
        "in": "query",
        "required": False,
        "description": f"Only with a raw document (refused with a JSON body): `{where}`{also}. "
        f"{description}".strip(),
        "schema": _value_schema(model, field_name),
    }


#: A raw document's bytes: at most the body limit (its default here; the server's applies).
_RAW_DOCUMENT = {
    "type": "string",
    "format": "binary",
    "maxLength": MAX_BODY_BYTES,
    "description": "The document's bytes; ARCSPLINE_MAX_BODY_BYTES (4 MiB by default) applies.",
}
DOCUMENT_BODY: dict[str, Any] = {
    "requestBody": {
        "content": {media_type: {"schema": _RAW_DOCUMENT} for media_type in DOCUMENT_MEDIA_TYPES}
    },
    "parameters": [
        _query_parameter(name)
        for name in sorted(_FIELDS | _GCODE_FIELDS | _DXF_FIELDS | _TOOL_FIELDS)
    ],
}
