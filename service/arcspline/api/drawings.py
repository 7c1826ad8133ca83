"""``POST /v1/drawings/approximate`` and ``/v1/drawings/preview``: a whole SVG or DXF
document in (a JSON body, or the raw file with the options as query parameters), toolpaths
out — as JSON, or as one document alone (G-code, DXF, SVG) chosen by ``output`` (the field
or the query parameter) or the ``Accept`` header (:mod:`.negotiation`)."""

from __future__ import annotations

import typing
from collections.abc import Callable
from typing import Any

from fastapi import APIRouter, Request
from fastapi.exceptions import RequestValidationError
from pydantic import TypeAdapter
from starlette.responses import Response

from arcspline.drawings.model import DocumentLimits
from arcspline.outputs.svg import MEDIA_TYPE as SVG_MEDIA_TYPE
from arcspline.worker.drawing_jobs import DrawingJob, approximate_drawing_one, render_drawing
from arcspline.worker.jobs import Encoded, Output

from .contract import answers
from .drawing_outputs import DOCUMENT_MEDIA_TYPES, document_outputs, preview_output
from .drawing_query import DOCUMENT_BODY, from_query
from .drawing_schemas import DrawingRequest, DrawingResponse
from .errors import ProblemError, RawJSONResponse, problem, problem_responses
from .negotiation import answer_document, media_type_for, negotiate, query_output
from .preview import SVGResponse, draw, svg_responses
from .routing import LeanRoute, is_json, json_body, read_body
from .runtime import runtime_of
from .translate import drawing_problem, tooling_of

_ADAPTER: TypeAdapter[DrawingRequest] = TypeAdapter(DrawingRequest)


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
                # Of the query, a JSON body takes only ``output``: as if it were the field.
                output = query_output(request)
                if body.output is None and output is not None:
                    body = body.model_copy(update={"output": output})
            elif media_type in DOCUMENT_MEDIA_TYPES:
                raw = await read_body(request)
                body = from_query(request.query_params, media_type, raw)
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
    tooling = tooling_of(body, outputs, ["body"])
    return DrawingJob(body.spec(content, limits), body.options(), outputs, tooling)


@router.post(
    "/v1/drawings/approximate",
    name="approximate_drawing",
    summary="Cut a whole SVG or DXF drawing: toolpaths, program, DXF or SVG",
    response_model=DrawingResponse,
    responses={
        **answers("The toolpaths (JSON), or the one document asked for"),
        **problem_responses(400, 406, 413, 415, 422, 503, 504),
    },
    openapi_extra=DOCUMENT_BODY,
)
async def approximate_drawing(body: DrawingRequest, request: Request) -> Response:
    """Every element read (transforms, units, blocks applied exactly), joined end to end
    into toolpaths, ordered to shorten the rapids, and approximated within ``tolerance`` of
    the drawing as given; what the document held but could not be cut is listed in
    ``document.warnings``."""
    output = negotiate(body.output, request.headers.get("accept"))
    job = _job(body, request, document_outputs(body, output))
    if output == "json":
        return await _as_json(job, request)
    settings = runtime_of(request).settings
    return await answer_document(
        request, render_drawing, job, settings.drawing_limits, endpoint="drawings",
        stem="drawing", output=output, problem_of=lambda error: drawing_problem(error, ["body"]),
    )  # fmt: skip


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


@router.post(
    "/v1/drawings/preview",
    name="preview_drawing",
    summary="Draw a drawing's toolpaths in cutting order (SVG)",
    response_class=SVGResponse,
    responses=svg_responses(415),
    openapi_extra=DOCUMENT_BODY,
)
async def preview_drawing(body: DrawingRequest, request: Request) -> SVGResponse:
    """The toolpaths numbered in cutting order, rapids dashed, corners marked, a scale bar
    in the drawing's units, and each toolpath's deviation magnified (``output`` and
    ``gcode`` ignored)."""
    # (Its query holds a raw document's options, checked with them.)
    media_type_for(request.headers.get("accept"), (SVG_MEDIA_TYPE,))
    job = _job(body, request, (preview_output(body),))
    return await draw(
        request, render_drawing, job, runtime_of(request).settings.drawing_limits,
        endpoint="drawings_preview", problem_of=lambda error: drawing_problem(error, ["body"]),
    )  # fmt: skip
