"""From validated requests to worker jobs, and from a job's failure to its problem."""

from __future__ import annotations

from typing import Any

from arcspline.geometry import GeometryError
from arcspline.outputs.gcode import GcodeError, GcodeOptions
from arcspline.worker.jobs import Job, Output, PathJob

from .errors import Loc, ProblemError, gcode_problem, geometry_problem
from .path_schemas import PathRequest
from .schemas import ApproximateRequest, GcodeRequest


def gcode_outputs(gcode: GcodeRequest | None, prefix: Loc) -> tuple[Output, ...]:
    """The G-code program a request asks for, as an output (options the writer refuses
    raise a 422)."""
    if gcode is None:
        return ()
    try:
        return (("gcode", GcodeOptions(**gcode.model_dump())),)
    except GcodeError as error:
        raise ProblemError(gcode_problem(error, prefix)) from None


def to_job(
    request: ApproximateRequest, prefix: Loc, outputs: tuple[Output, ...] | None = None
) -> Job:
    """The worker's job for ``request``: its curve, tolerance and strategy, and ``outputs``
    (by default the G-code program the request asks for)."""
    if outputs is None:
        outputs = gcode_outputs(request.gcode, prefix)
    return Job(request.spiral.spec(), request.tolerance, request.strategy, outputs)


def to_path_job(
    request: PathRequest, prefix: Loc, max_segments: int, outputs: tuple[Output, ...] | None = None
) -> PathJob:
    """The worker's job for a path ``request`` (at most ``max_segments`` input segments), and
    ``outputs`` (by default the G-code program the request asks for)."""
    if outputs is None:
        outputs = gcode_outputs(request.gcode, prefix)
    return PathJob(request.spec(max_segments), request.tolerance, request.strategy, outputs)


def job_problem(
    error: GeometryError | GcodeError, prefix: Loc, curve: str = "spiral"
) -> dict[str, Any]:
    """The problem of a job the worker could not complete (``curve``: the request's field
    that holds the curve)."""
    if isinstance(error, GeometryError):
        return geometry_problem(error, prefix)
    return gcode_problem(error, prefix, curve)
