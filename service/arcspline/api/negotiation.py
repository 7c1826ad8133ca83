"""Which answer an approximation gets — JSON, or one document alone (a G-code program, a DXF,
an SVG) — the writers that answer needs, and the document's response.

The three approximate endpoints (spiral, path, drawing) share all of it: the body's
``output``, else the ``output`` query parameter, else the best output the ``Accept`` header
names, else JSON; 406 when the header names only media types we cannot give. The endpoints
that answer one kind of thing (a batch, a preview) check their query and ``Accept`` alike
(:func:`fixed_answer`).
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Sequence
from typing import Any, TypeVar

from fastapi import Request
from fastapi.exceptions import RequestValidationError
from pydantic import TypeAdapter, ValidationError
from starlette.responses import Response

from arcspline.geometry import Limits
from arcspline.outputs.dxf import DxfOptions, Units
from arcspline.outputs.gcode import GcodeOptions
from arcspline.outputs.svg_document import SvgDocumentOptions
from arcspline.worker.jobs import Document, Output

from .drawing_schemas import DxfRequest
from .errors import ProblemError, problem
from .runtime import runtime_of
from .schemas import NDJSON_MEDIA_TYPE, OUTPUT_MEDIA_TYPES, OutputFormat

JobT = TypeVar("JobT")

#: What an ``Accept`` header may name, beyond :data:`OUTPUT_MEDIA_TYPES`.
_ACCEPT_ALIASES: dict[str, OutputFormat] = {
    "application/dxf": "dxf",
    "text/plain": "gcode",
    "*/*": "json",
    "application/*": "json",
    # Ranges (RFC 9110 §12.5.1) answer with the one output of the range, or the first.
    "text/*": "gcode",
    "image/*": "svg",
}
_BY_MEDIA_TYPE = {media: name for name, media in OUTPUT_MEDIA_TYPES.items()} | _ACCEPT_ALIASES
_EXTENSIONS = {"gcode": "ngc", "dxf": "dxf", "svg": "svg"}
_OUTPUT: TypeAdapter[OutputFormat] = TypeAdapter(OutputFormat)


def unknown_parameters(names: Iterable[str]) -> list[dict[str, Any]]:
    """Validation errors for query parameters the endpoint does not take."""
    return [
        {"type": "extra_forbidden", "loc": ("query", name), "msg": "Unknown parameter"}
        for name in sorted(names)
    ]


def query_output(request: Request) -> OutputFormat | None:
    """The ``output`` query parameter of a request with a JSON body — for curl users, who
    would rather not edit the body — and the only parameter such a request takes (its
    options are in the body; a parameter it would ignore is refused, so a typo is not)."""
    if not request.scope.get("query_string"):
        return None
    query = request.query_params
    errors = unknown_parameters(set(query) - {"output"})
    value = query.get("output")
    output: OutputFormat | None = None
    if value is not None:
        try:
            output = _OUTPUT.validate_python(value, strict=True)
        except ValidationError as error:
            errors += [{**e, "loc": ("query", "output")} for e in error.errors(include_url=False)]
    if errors:
        raise RequestValidationError(errors)
    return output


def _ranked(accept: str) -> list[str]:
    """The media types ``accept`` names, best first (by ``q``, then as written); those
    with ``q=0`` (or a ``q`` that is not a number) are left out."""
    ranked = []
    for position, item in enumerate(accept.split(",")):
        media, *params = (part.strip() for part in item.split(";"))
        quality = 1.0
        for param in params:
            name, _, value = param.partition("=")
            if name.strip() == "q":
                try:
                    quality = float(value)
                except ValueError:
                    quality = 0.0
        if quality > 0.0:
            ranked.append((-quality, position, media.lower()))
    return [media for _, _, media in sorted(ranked)]


def negotiate(chosen: OutputFormat | None, accept: str | None) -> OutputFormat:
    """``chosen`` (by the body or the query), else the best output ``accept`` names, else
    JSON; a 406 when the header names only media types the endpoint cannot give."""
    if chosen is not None:
        return chosen
    if not accept:
        return "json"
    alone = _BY_MEDIA_TYPE.get(accept)  # what most clients send: `*/*`, or one media type
    if alone is not None:
        return alone
    for media in _ranked(accept):
        name = _BY_MEDIA_TYPE.get(media)
        if name is not None:
            return name
    offered = ", ".join(OUTPUT_MEDIA_TYPES.values())
    detail = f"the Accept header ({accept}) names none of the outputs: {offered}"
    raise ProblemError(problem("not_acceptable", detail))


#: What a batch answers: one JSON document, or NDJSON (a line per job) when Accept asks.
BATCH_MEDIA_TYPES = ("application/json", NDJSON_MEDIA_TYPE)


def media_type_for(accept: str | None, offered: Sequence[str]) -> str:
    """The one of ``offered`` that ``accept`` ranks best (a range such as ``image/*`` or
    ``*/*`` takes the first it covers); the first when there is no ``Accept``; a 406 when
    it names none."""
    if not accept:
        return offered[0]
    for media in _ranked(accept):
        if media in offered:
            return media
        if media.endswith("/*"):
            covered = [o for o in offered if media == "*/*" or o.startswith(media[:-1])]
            if covered:
                return covered[0]
    detail = f"the Accept header ({accept}) names none of the answers: {', '.join(offered)}"
    raise ProblemError(problem("not_acceptable", detail))


def refuse_query(request: Request) -> None:
    """A 422 naming each query parameter: the request's options are all in its body."""
    if request.scope.get("query_string"):
        errors = unknown_parameters(request.query_params)
        if errors:
            raise RequestValidationError(errors)


def fixed_answer(request: Request, offered: Sequence[str]) -> str:
    """For an endpoint that takes no query parameters and answers one of ``offered`` (a
    batch, a preview), as the approximate endpoints check theirs: a 422 for any query
    parameter, a 406 for an ``Accept`` it cannot satisfy; else the media type to answer."""
    refuse_query(request)
    return media_type_for(request.headers.get("accept"), offered)


def output_of(field: OutputFormat | None, request: Request) -> OutputFormat:
    """The output a request with a JSON body asks for: its ``output`` field, else the
    ``output`` query parameter, else its ``Accept`` header (the query is checked either way)."""
    query = query_output(request)
    return negotiate(field if field is not None else query, request.headers.get("accept"))


def _needed(program: GcodeOptions | None) -> GcodeOptions:
    if program is None:
        detail = "body.gcode: the gcode output needs the program's options (feed_rate at least)"
        item = {"loc": ["body", "gcode"], "msg": "required for the gcode output", "type": "missing"}
        raise ProblemError(problem("validation", detail, errors=[item]))
    return program


def writers_for(
    output: OutputFormat, program: GcodeOptions | None, units: Units, dxf: DxfRequest | None = None
) -> tuple[Output, ...]:
    """The writers an answer needs: the program for JSON (if asked for), else the one
    document — ``program`` is the request's G-code options (a 422 for ``gcode`` without
    them), ``units`` the unit of a DXF or SVG, ``dxf`` the DXF's options."""
    if output == "json":
        return () if program is None else (("gcode", program),)
    if output == "gcode":
        return (("gcode", _needed(program)),)
    if output == "dxf":
        dxf = dxf or DxfRequest()
        return (("dxf", DxfOptions(units, dxf.polyline, dxf.layer_per_toolpath)),)
    return (("svg-document", SvgDocumentOptions(units=units)),)


def filename(stem: str, output: OutputFormat) -> str:
    """The name a document is offered under: ``spiral.ngc``, ``path.dxf``, ``drawing.svg``."""
    return f"{stem}.{_EXTENSIONS[output]}"


async def rendered(
    request: Request,
    render: Callable[[JobT, Limits], object],
    job: JobT,
    limits: Limits,
    endpoint: str,
    problem_of: Callable[[Any], dict[str, Any]],
) -> Document:
    """The :class:`Document` ``render`` writes for ``job`` in a worker, counted in the job
    metrics under ``endpoint``; anything else it returns is a refusal, raised as the problem
    ``problem_of`` makes of it."""
    runtime = runtime_of(request)
    result = await runtime.running_pool().run(
        render, job, limits, time_limit_s=runtime.settings.job_time_limit_s
    )
    if not isinstance(result, Document):
        runtime.metrics.job_error(endpoint)
        raise ProblemError(problem_of(result))
    runtime.metrics.job_ok(endpoint, 0, 0)
    return result


async def answer_document(
    request: Request,
    render: Callable[[JobT, Limits], object],
    job: JobT,
    limits: Limits,
    *,
    endpoint: str,
    stem: str,
    output: OutputFormat,
    problem_of: Callable[[Any], dict[str, Any]],
) -> Response:
    """The :class:`Document` ``render`` writes for ``job`` in a worker, as an attachment
    named after ``stem`` (see :func:`rendered`)."""
    result = await rendered(request, render, job, limits, endpoint, problem_of)
    disposition = f'attachment; filename="{filename(stem, output)}"'
    return Response(
        result.body, media_type=result.media_type, headers={"Content-Disposition": disposition}
    )
