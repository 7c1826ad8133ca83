"""From validated requests to worker jobs, and from a job's failure to its problem."""

from __future__ import annotations

from typing import Any

from arcspline.geometry import GeometryError
from arcspline.outputs.gcode import GcodeError, GcodeOptions
from arcspline.worker.jobs import Job, Output

from .errors import Loc, ProblemError, gcode_problem, geometry_problem
from .schemas import ApproximateRequest


def to_job(
    request: ApproximateRequest, prefix: Loc, outputs: tuple[Output, ...] | None = None
) -> Job:
    """The worker's job for ``request``: its curve, tolerance and strategy, and ``outputs``
    (by default the G-code program the request asks for; options the writer refuses raise a
    422)."""
    if outputs is None:
        outputs = ()
        if request.gcode is not None:
            try:
                outputs = (("gcode", GcodeOptions(**request.gcode.model_dump())),)
            except GcodeError as error:
                raise ProblemError(gcode_problem(error, prefix)) from None
    return Job(request.spiral.spec(), request.tolerance, request.strategy, outputs)


def job_problem(
    error: GeometryError | GcodeError, prefix: Loc, curve: str = "spiral"
) -> dict[str, Any]:
    """The problem of a job the worker could not complete (``curve``: the request's field
    that holds the curve)."""
    if isinstance(error, GeometryError):
        return geometry_problem(error, prefix)
    return gcode_problem(error, prefix, curve)
