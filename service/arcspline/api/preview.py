"""``POST /v1/preview``: the picture of an approximation (``arcspline.outputs.svg``), drawn
in a worker — and how every preview (spiral, path, drawing) is drawn and counted."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any, TypeVar

from fastapi import APIRouter, Request
from starlette.responses import Response

from arcspline.geometry import Limits
from arcspline.outputs.svg import MEDIA_TYPE
from arcspline.worker.jobs import render

from .errors import problem_responses
from .negotiation import fixed_answer, rendered
from .routing import LeanRoute
from .runtime import runtime_of
from .schemas import ApproximateRequest
from .translate import job_problem, to_job

router = APIRouter(tags=["approximation"], route_class=LeanRoute)
JobT = TypeVar("JobT")


class SVGResponse(Response):
    media_type = MEDIA_TYPE


def svg_responses(*more: int) -> dict[int | str, dict[str, Any]]:
    """The picture, or a problem (of the usual statuses and ``more``)."""
    return {
        200: {
            "description": "The picture",
            "content": {MEDIA_TYPE: {"schema": {"type": "string"}}},
        },
        **problem_responses(*sorted({400, 406, 413, 422, 503, 504, *more})),
    }


async def draw(
    request: Request,
    render: Callable[[JobT, Limits], object],
    job: JobT,
    limits: Limits,
    *,
    endpoint: str,
    problem_of: Callable[[Any], dict[str, Any]],
) -> SVGResponse:
    """The picture ``render`` draws of ``job`` in a worker (see
    :func:`.negotiation.rendered`)."""
    result = await rendered(request, render, job, limits, endpoint, problem_of)
    return SVGResponse(result.body)


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
    fixed_answer(request, (MEDIA_TYPE,))
    job = to_job(body, ["body"], outputs=(("svg", None),))
    return await draw(
        request, render, job, runtime_of(request).settings.limits, endpoint="preview",
        problem_of=lambda error: job_problem(error, ["body"]),
    )  # fmt: skip
