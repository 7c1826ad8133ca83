"""``POST /v1/preview``: the picture of an approximation (``arcspline.outputs.svg``), drawn
in a worker."""

from __future__ import annotations

from typing import Any

from fastapi import APIRouter, Request
from starlette.responses import Response

from arcspline.outputs.svg import MEDIA_TYPE
from arcspline.worker.jobs import Document, render

from .errors import ProblemError, problem_responses
from .routing import LeanRoute
from .runtime import runtime_of
from .schemas import ApproximateRequest
from .translate import job_problem, to_job

router = APIRouter(tags=["approximation"], route_class=LeanRoute)


class SVGResponse(Response):
    media_type = MEDIA_TYPE


def svg_responses(*more: int) -> dict[int | str, dict[str, Any]]:
    """The picture, or a problem (of the usual statuses and ``more``)."""
    return {
        200: {
            "description": "The picture",
            "content": {MEDIA_TYPE: {"schema": {"type": "string"}}},
        },
        **problem_responses(*sorted({400, 413, 422, 503, 504, *more})),
    }


@router.post(
    "/v1/preview",
    name="preview",
    summary="Draw an approximation (SVG)",
    response_class=SVGResponse,
    responses=svg_responses(),
)
async def preview(body: ApproximateRequest, request: Request) -> SVGResponse:
    """The spiral, its arcs with their centres, the deviation magnified (``gcode`` and
    ``output`` ignored)."""
    runtime = runtime_of(request)
    job = to_job(body, ["body"], outputs=(("svg", None),))
    settings = runtime.settings
    result = await runtime.running_pool().run(
        render, job, settings.limits, time_limit_s=settings.job_time_limit_s
    )
    if not isinstance(result, Document):
        raise ProblemError(job_problem(result, ["body"]))
    return SVGResponse(result.body)
