"""From validated requests to worker jobs, and from a job's failure to its problem."""

from __future__ import annotations

from typing import Any

from arcspline.drawings import DocumentError
from arcspline.geometry import GeometryError
from arcspline.outputs.gcode import GcodeError, GcodeOptions
from arcspline.worker.jobs import Job, Output, PathJob
from arcspline.worker.tooling import Tooling

from .drawing_schemas import DrawingRequest
from .errors import Loc, ProblemError, dotted, gcode_problem, geometry_problem, problem
from .negotiation import writers_for
from .path_schemas import PathRequest
from .schemas import ApproximateRequest, GcodeRequest, OutputFormat

#: What a machining program needs of the G-code options: where to retract, and to cut.
_MACHINING_HEIGHTS = ("safe_z", "cut_z")


def gcode_options(
    gcode: GcodeRequest, prefix: Loc, curve: str = "spiral", **overrides: Any
) -> GcodeOptions:
    """The writer's options of a request's ``gcode`` (with ``overrides``); options the
    writer refuses raise a 422 (``curve``: the request's field that holds the curve)."""
    try:
        return GcodeOptions(**{**gcode.model_dump(), **overrides})
    except GcodeError as error:
        raise ProblemError(gcode_problem(error, prefix, curve)) from None


def program_of(
    gcode: GcodeRequest | None, prefix: Loc, curve: str = "spiral", **overrides: Any
) -> GcodeOptions | None:
    """The program's options, if the request asks for one (see :func:`gcode_options`)."""
    return None if gcode is None else gcode_options(gcode, prefix, curve, **overrides)


def curve_outputs(
    request: ApproximateRequest | PathRequest, output: OutputFormat, prefix: Loc
) -> tuple[Output, ...]:
    """The writers of a spiral's or a path's answer: a DXF or SVG is in the program's unit
    (``gcode.units``), else in mm — the curve's numbers are taken in that unit as given."""
    gcode = request.gcode
    units = "mm" if gcode is None else gcode.units
    curve = "spiral" if isinstance(request, ApproximateRequest) else "path"
    return writers_for(output, program_of(gcode, prefix, curve), units)


def to_job(
    request: ApproximateRequest, prefix: Loc, outputs: tuple[Output, ...] | None = None
) -> Job:
    """The worker's job for ``request``: its curve, tolerance and strategy, and ``outputs``
    (by default those of its JSON answer: the G-code program, if asked for)."""
    if outputs is None:
        outputs = curve_outputs(request, "json", prefix)
    return Job(request.spiral.spec(), request.tolerance, request.strategy, outputs)


def to_path_job(
    request: PathRequest, prefix: Loc, max_segments: int, outputs: tuple[Output, ...] | None = None
) -> PathJob:
    """The worker's job for a path ``request`` (at most ``max_segments`` input segments), and
    ``outputs`` (by default those of its JSON answer: the G-code program, if asked for)."""
    if outputs is None:
        outputs = curve_outputs(request, "json", prefix)
    tooling = tooling_of(request, outputs, prefix)
    return PathJob(
        request.spec(max_segments), request.tolerance, request.strategy, outputs, tooling
    )


def tooling_of(
    request: PathRequest | DrawingRequest, outputs: tuple[Output, ...], prefix: Loc
) -> Tooling | None:
    """The core's options of the request's ``offset`` or ``machining``, if any; machining
    that writes a program (a ``gcode`` output) needs ``gcode.safe_z`` and ``gcode.cut_z``
    (a 422 naming those missing)."""
    if request.offset is not None:
        return request.offset.options()
    if request.machining is None:
        return None
    gcode = request.gcode
    if gcode is not None and any(name == "gcode" for name, _ in outputs):
        missing = [name for name in _MACHINING_HEIGHTS if getattr(gcode, name) is None]
        items = [
            {
                "loc": [*prefix, "gcode", name],
                "msg": "required with machining: the program retracts to safe_z between "
                "contours and over tabs, and cuts at cut_z",
                "type": "missing",
            }
            for name in missing
        ]
        if items:
            shown = "; ".join(f"{dotted(i['loc'])}: {i['msg']}" for i in items)
            raise ProblemError(problem("validation", shown, errors=items))
    return request.machining.options()


def path_preview(request: PathRequest) -> Output:
    """The picture of a path: the approximation's (``svg``), or with an offset or machining
    the drawing preview of the tool-centre paths, with the contours and the swept width (in
    the program's unit, mm without one)."""
    if request.offset is None and request.machining is None:
        return ("svg", None)
    return ("drawing-preview", "mm" if request.gcode is None else request.gcode.units)


def job_problem(
    error: GeometryError | GcodeError, prefix: Loc, curve: str = "spiral"
) -> dict[str, Any]:
    """The problem of a job the worker could not complete (``curve``: the request's field
    that holds the curve)."""
    if isinstance(error, GeometryError):
        return geometry_problem(error, prefix, curve)
    return gcode_problem(error, prefix, curve)


def drawing_problem(
    error: GeometryError | GcodeError | DocumentError, prefix: Loc
) -> dict[str, Any]:
    """The problem of a drawing job: a document the reader refuses names the element (its
    id, type or line) under ``document``; a request field it names (``layers``) directly."""
    if not isinstance(error, DocumentError):
        return job_problem(error, prefix, "document")
    field = error.where if error.where in DrawingRequest.model_fields else "document"
    loc: Loc = [*prefix, field]
    at = "" if error.where == field else f" ({error.where})"
    item = {"loc": loc, "msg": error.reason, "type": "invalid_document", "element": error.where}
    return problem("invalid_document", f"{dotted(loc)}{at}: {error.reason}", errors=[item])
