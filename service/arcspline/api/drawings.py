"""``POST /v1/drawings/approximate`` and ``/v1/drawings/preview``: a whole SVG or DXF
document in (a JSON body, or the raw file with the options as query parameters), toolpaths
out — as JSON, or as one document alone (G-code, DXF, SVG) chosen by ``output`` or the
``Accept`` header."""

from __future__ import annotations

import base64
import typing
from collections.abc import Callable, Mapping
from typing import Any

from fastapi import APIRouter, Request
from fastapi.exceptions import RequestValidationError
from pydantic import TypeAdapter, ValidationError
from starlette.responses import Response

from arcspline.drawings.model import DocumentLimits
from arcspline.worker.drawing_jobs import DrawingJob, approximate_drawing_one, render_drawing
from arcspline.worker.jobs import Document, Encoded, Output

from .drawing_outputs import (
    DOCUMENT_MEDIA_TYPES,
    OUTPUT_MEDIA_TYPES,
    document_outputs,
    filename,
    output_of,
    preview_output,
)
from .drawing_schemas import DrawingOutput, DrawingRequest, DrawingResponse, DxfRequest
from .errors import ProblemError, RawJSONResponse, problem, problem_responses
from .preview import SVGResponse, svg_responses
from .routing import LeanRoute, is_json, json_body, read_body
from .runtime import runtime_of
from .schemas import GcodeRequest
from .translate import drawing_problem

_ADAPTER: TypeAdapter[DrawingRequest] = TypeAdapter(DrawingRequest)
#: Query parameters of a raw document: the request's fields, and the G-code options.
_GCODE_FIELDS = frozenset(GcodeRequest.model_fields) - {"units"}
_DXF_FIELDS = frozenset(DxfRequest.model_fields)
_FIELDS = frozenset(DrawingRequest.model_fields) - {"document", "encoding", "gcode", "dxf"}


def _from_query(query: Mapping[str, str], media_type: str, raw: bytes) -> DrawingRequest:
    """The request of a raw document: its bytes (as base64, so binary DXF fits too), its
    format from the media type (or ``format``), the options from the query string."""
    unknown = sorted(set(query) - _FIELDS - _GCODE_FIELDS - _DXF_FIELDS)
    if unknown:
        raise RequestValidationError(
            [
                {"type": "extra_forbidden", "loc": ("query", name), "msg": "Unknown parameter"}
                for name in unknown
            ]
        )
    fields: dict[str, Any] = {k: v for k, v in query.items() if k in _FIELDS}
    if "layers" in fields:
        fields["layers"] = [name for name in fields["layers"].split(",") if name]
    gcode = {k: v for k, v in query.items() if k in _GCODE_FIELDS}
    if gcode:
        fields["gcode"] = {**gcode, "units": fields.get("units", "mm")}
    dxf = {k: v for k, v in query.items() if k in _DXF_FIELDS}
    if dxf:
        fields["dxf"] = dxf
    fields.setdefault("format", DOCUMENT_MEDIA_TYPES.get(media_type))
    fields["document"] = base64.b64encode(raw).decode()
    fields["encoding"] = "base64"
    try:
        # Lax: query values are strings ("0.01", "true").
        return DrawingRequest.model_validate(fields, strict=False)
    except ValidationError as error:
        errors = error.errors(include_url=False)
        raise RequestValidationError([{**e, "loc": ("query", *e["loc"])} for e in errors]) from None


class DocumentRoute(LeanRoute):
    """A route whose body is a :class:`DrawingRequest` as JSON, or a raw document (its media
    type in :data:`DOCUMENT_MEDIA_TYPES`) with the options in the query string."""

    def get_route_handler(self) -> Callable[[Request], typing.Coroutine[Any, Any, Response]]:
        endpoint = self.endpoint

        async def handler(request: Request) -> Response:
            content_type = request.headers.get("content-type", "")
            media_type = content_type.split(";", 1)[0].strip().lower()
            if is_json(content_type):
                body = await json_body(request, _ADAPTER)
            elif media_type in DOCUMENT_MEDIA_TYPES:
                raw = await read_body(request)
                body = _from_query(request.query_params, media_type, raw)
            else:
                accepted = ", ".join(["application/json", *DOCUMENT_MEDIA_TYPES])
                detail = (
                    f"the body's media type {media_type or '(none)'!r} is not one of {accepted}"
                )
                raise ProblemError(problem("unsupported_media_type", detail))
            response: Response = await endpoint(body=body, request=request)
            return response

        return handler


router = APIRouter(tags=["drawings"], route_class=DocumentRoute)

_DOCUMENT_BODY: dict[str, Any] = {
    "requestBody": {
        "content": {
            media_type: {"schema": {"type": "string", "format": "binary"}}
            for media_type in DOCUMENT_MEDIA_TYPES
        }
    },
    "parameters": [
        {
            "name": name,
            "in": "query",
            "required": False,
            "description": "With a raw document: the field of the same name "
            + (
                "of `gcode`."
                if name in _GCODE_FIELDS
                else "of `dxf`."
                if name in _DXF_FIELDS
                else "of the JSON body."
            ),
            "schema": {"type": "string"},
        }
        for name in sorted(_FIELDS | _GCODE_FIELDS | _DXF_FIELDS)
    ],
}


def _job(body: DrawingRequest, request: Request, outputs: tuple[Output, ...]) -> DrawingJob:
    settings = runtime_of(request).settings
    try:
        content = body.content()
    except ValueError as error:
        item = {"type": "value_error", "loc": ("body", "document"), "msg": str(error)}
        raise RequestValidationError([item]) from None
    limits = DocumentLimits(
        max_bytes=settings.max_body_bytes,
        max_elements=settings.drawing_max_elements,
        max_depth=settings.drawing_max_depth,
        # Every input segment gives at least one output segment: more cannot be cut.
        max_segments=settings.drawing_max_segments,
    )
    return DrawingJob(body.spec(content, limits), body.options(), outputs)


@router.post(
    "/v1/drawings/approximate",
    name="approximate_drawing",
    summary="Cut a whole SVG or DXF drawing: toolpaths, program, DXF or SVG",
    response_model=DrawingResponse,
    responses={
        200: {
            "description": "The toolpaths (JSON), or the one document asked for",
            "content": {media_type: {} for media_type in OUTPUT_MEDIA_TYPES.values()},
        },
        **problem_responses(400, 413, 415, 422, 503, 504),
    },
    openapi_extra=_DOCUMENT_BODY,
)
async def approximate_drawing(body: DrawingRequest, request: Request) -> Response:
    """Every element read (transforms, units, blocks applied exactly), joined end to end
    into toolpaths, ordered to shorten the rapids, and approximated within ``tolerance`` of
    the drawing as given; what the document held but could not be cut is listed in
    ``document.warnings``."""
    output = output_of(body, request.headers.get("accept"))
    job = _job(body, request, document_outputs(body, output))
    if output == "json":
        return await _as_json(job, request)
    return await _as_document(job, request, output)


async def _as_json(job: DrawingJob, request: Request) -> Response:
    runtime = runtime_of(request)
    settings = runtime.settings
    result = await runtime.running_pool().run(
        approximate_drawing_one, job, settings.drawing_limits,
        time_limit_s=settings.job_time_limit_s,
    )  # fmt: skip
    if not isinstance(result, Encoded):
        runtime.metrics.job_error("drawings")
        raise ProblemError(drawing_problem(result, ["body"]))
    runtime.metrics.job_ok("drawings", result.arc_count, result.line_count)
    return RawJSONResponse(result.body)


async def _as_document(job: DrawingJob, request: Request, output: DrawingOutput) -> Response:
    runtime = runtime_of(request)
    settings = runtime.settings
    result = await runtime.running_pool().run(
        render_drawing, job, settings.drawing_limits, time_limit_s=settings.job_time_limit_s
    )
    if not isinstance(result, Document):
        runtime.metrics.job_error("drawings")
        raise ProblemError(drawing_problem(result, ["body"]))
    runtime.metrics.job_ok("drawings", 0, 0)
    return Response(
        result.body,
        media_type=result.media_type,
        headers={"Content-Disposition": f'attachment; filename="{filename(output)}"'},
    )


@router.post(
    "/v1/drawings/preview",
    name="preview_drawing",
    summary="Draw a drawing's toolpaths in cutting order (SVG)",
    response_class=SVGResponse,
    responses=svg_responses(),
    openapi_extra=_DOCUMENT_BODY,
)
async def preview_drawing(body: DrawingRequest, request: Request) -> SVGResponse:
    """The toolpaths numbered in cutting order, rapids dashed, corners marked, a scale bar
    in the drawing's units, and each toolpath's deviation magnified (``output`` and
    ``gcode`` ignored)."""
    runtime = runtime_of(request)
    settings = runtime.settings
    job = _job(body, request, (preview_output(body),))
    result = await runtime.running_pool().run(
        render_drawing, job, settings.drawing_limits, time_limit_s=settings.job_time_limit_s
    )
    if not isinstance(result, Document):
        raise ProblemError(drawing_problem(result, ["body"]))
    return SVGResponse(result.body)
