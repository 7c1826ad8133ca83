"""From validated requests to worker jobs, and from a job's failure to its problem."""

from __future__ import annotations

from typing import Any

from arcspline.geometry import GeometryError
from arcspline.outputs.gcode import GcodeError, GcodeOptions
from arcspline.worker.jobs import ControlPointsSpec, Job, ParametersSpec, SpiralSpec

from .errors import Loc, ProblemError, gcode_problem, geometry_problem
from .schemas import ApproximateRequest, SpiralParameters


def to_job(request: ApproximateRequest, prefix: Loc, *, gcode: bool = True) -> Job:
    """The worker's job for ``request``; G-code options the writer refuses raise a 422."""
    spiral = request.spiral
    spec: SpiralSpec
    if isinstance(spiral, SpiralParameters):
        spec = ParametersSpec(
            start=(spiral.start[0], spiral.start[1]),
            start_tangent=(spiral.start_tangent[0], spiral.start_tangent[1]),
            turn_angle_deg=spiral.turn_angle_deg,
            end_curvature=spiral.end_curvature,
        )
    else:
        spec = ControlPointsSpec(tuple((p[0], p[1]) for p in spiral.control_points))
    options = None
    if gcode and request.gcode is not None:
        try:
            options = GcodeOptions(**request.gcode.model_dump())
        except GcodeError as error:
            raise ProblemError(gcode_problem(error, prefix)) from None
    return Job(spiral=spec, tolerance=request.tolerance, strategy=request.strategy, gcode=options)


def job_problem(error: GeometryError | GcodeError, prefix: Loc) -> dict[str, Any]:
    """The problem of a job the worker could not complete."""
    if isinstance(error, GeometryError):
        return geometry_problem(error, prefix)
    return gcode_problem(error, prefix)
