"""What a drawing request is read from and written to: the raw documents it may send, and
the writers of its answer (the choice of answer itself is :mod:`.negotiation`'s, shared with
the spiral and path endpoints)."""

from __future__ import annotations

from arcspline.worker.jobs import Output

from .drawing_schemas import DrawingRequest
from .negotiation import writers_for
from .schemas import OutputFormat
from .translate import program_of

#: The raw documents a drawing request may send, and their format (``None``: say it in
#: the ``format`` query parameter).
DOCUMENT_MEDIA_TYPES: dict[str, str | None] = {
    "image/svg+xml": "svg",
    "application/dxf": "dxf",
    "image/vnd.dxf": "dxf",
    "image/x-dxf": "dxf",
    "application/octet-stream": None,
}


def document_outputs(body: DrawingRequest, output: OutputFormat) -> tuple[Output, ...]:
    """The writers a drawing's answer needs, all in the request's ``units`` (a 422 for
    G-code options the writer refuses, or for a ``gcode`` output without them)."""
    program = program_of(body.gcode, ["body"], "document", units=body.units)
    return writers_for(output, program, body.units, body.dxf)


def preview_output(body: DrawingRequest) -> Output:
    return ("drawing-preview", body.units)
