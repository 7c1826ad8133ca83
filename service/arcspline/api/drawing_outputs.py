"""Which document a drawing request answers with, and the writer options for it: the
``output`` field, else the ``Accept`` header, else JSON."""

from __future__ import annotations

from arcspline.outputs.dxf import DxfOptions
from arcspline.outputs.gcode import GcodeOptions
from arcspline.outputs.svg_document import SvgDocumentOptions
from arcspline.worker.jobs import Output

from .drawing_schemas import OUTPUTS, DrawingOutput, DrawingRequest, DxfRequest
from .errors import ProblemError, problem
from .translate import gcode_options

#: The raw documents a drawing request may send, and their format (``None``: say it in
#: the ``format`` query parameter).
DOCUMENT_MEDIA_TYPES: dict[str, str | None] = {
    "image/svg+xml": "svg",
    "application/dxf": "dxf",
    "image/vnd.dxf": "dxf",
    "image/x-dxf": "dxf",
    "application/octet-stream": None,
}
#: Each output's media type.
OUTPUT_MEDIA_TYPES: dict[str, str] = {
    "json": "application/json",
    "gcode": "text/x-gcode",
    "dxf": "image/vnd.dxf",
    "svg": "image/svg+xml",
}
#: What an ``Accept`` header may name, beyond :data:`OUTPUT_MEDIA_TYPES`.
_ACCEPT_ALIASES = {"application/dxf": "dxf", "text/plain": "gcode", "*/*": "json"}
_EXTENSIONS = {"gcode": "ngc", "dxf": "dxf", "svg": "svg"}


def _accepted(accept: str) -> list[tuple[float, int, str]]:
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
    return sorted(ranked)


def output_of(body: DrawingRequest, accept: str | None) -> DrawingOutput:
    """The output asked for: ``output``, else the best output the ``Accept`` header names,
    else JSON (406 when the header names only media types the endpoint cannot give)."""
    if body.output is not None:
        return body.output
    if not accept:
        return "json"
    by_media = {media: name for name, media in OUTPUT_MEDIA_TYPES.items()} | _ACCEPT_ALIASES
    ranked = _accepted(accept)
    for _, _, media in ranked:
        name = by_media.get(media) or ("json" if media == "application/*" else None)
        if name is not None:
            assert name in OUTPUTS
            return name  # type: ignore[return-value]
    offered = ", ".join(OUTPUT_MEDIA_TYPES.values())
    raise ProblemError(
        problem(
            "not_acceptable",
            f"the Accept header ({accept}) names none of the outputs: {offered}",
        )
    )


def _program_options(body: DrawingRequest) -> GcodeOptions:
    """The program's options, in the request's unit (a 422 for options the writer refuses,
    or for a ``gcode`` output without them)."""
    if body.gcode is None:
        detail = "body.gcode: the gcode output needs the program's options (feed_rate at least)"
        item = {"loc": ["body", "gcode"], "msg": "required for the gcode output", "type": "missing"}
        raise ProblemError(problem("validation", detail, errors=[item]))
    return gcode_options(body.gcode, ["body"], "document", units=body.units)


def document_outputs(body: DrawingRequest, output: DrawingOutput) -> tuple[Output, ...]:
    """The writers a request needs: the program for JSON (if asked), else the one document."""
    if output == "json":
        return () if body.gcode is None else (("gcode", _program_options(body)),)
    if output == "gcode":
        return (("gcode", _program_options(body)),)
    if output == "dxf":
        dxf = body.dxf or DxfRequest()
        options = DxfOptions(body.units, dxf.polyline, dxf.layer_per_toolpath)
        return (("dxf", options),)
    return (("svg-document", SvgDocumentOptions(units=body.units)),)


def preview_output(body: DrawingRequest) -> Output:
    return ("drawing-preview", body.units)


def filename(output: DrawingOutput) -> str:
    return f"drawing.{_EXTENSIONS[output]}"
