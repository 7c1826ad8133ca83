"""Probes: ``/healthz`` (the process answers) and ``/readyz`` (the pool accepts work)."""

from __future__ import annotations

from fastapi import APIRouter, Request

from .errors import ProblemError, RawJSONResponse, problem, problem_responses
from .routing import LeanRoute
from .runtime import runtime_of
from .schemas import HealthResponse, ReadyResponse

router = APIRouter(tags=["operations"], route_class=LeanRoute)

_HEALTHY = HealthResponse(status="ok").model_dump_json().encode()


@router.get(
    "/healthz",
    name="healthz",
    summary="Liveness",
    response_model=HealthResponse,
    # 413: the body limit applies to every request, before routing (even a GET's body).
    responses={
        200: {"description": "The process answers"},
        **problem_responses(413),
    },
)
async def healthz() -> RawJSONResponse:
    """The process is up and its event loop answers."""
    return RawJSONResponse(_HEALTHY)


@router.get(
    "/readyz",
    name="readyz",
    summary="Readiness",
    response_model=ReadyResponse,
    responses={
        200: {"description": "The pool accepts work"},
        **problem_responses(413),
        503: {
            **problem_responses(503)[503],
            "description": "Starting, restarting its workers, or draining",
        },
    },
)
async def readyz(request: Request) -> RawJSONResponse:
    """Ready when the worker pool is up and accepting work; 503 otherwise."""
    pool = runtime_of(request).pool
    if pool is None or not pool.ready:
        state: str = "stopped" if pool is None else pool.state
        if state == "ready":  # ready by state, but a worker has died: about to restart
            state = "restarting its workers"
        retry_after = str(runtime_of(request).settings.retry_after_s)
        raise ProblemError(
            problem("not_ready", f"the worker pool is {state}"),
            headers={"Retry-After": retry_after},
        )
    ready = ReadyResponse(
        status="ready", workers=pool.size, in_flight=pool.in_flight, queue_capacity=pool.capacity
    )
    return RawJSONResponse(ready.model_dump_json().encode())
