"""Probes: ``/healthz`` (the process answers) and ``/readyz`` (the pool accepts work)."""

from __future__ import annotations

from fastapi import APIRouter, Request

from .errors import PROBLEM_MEDIA_TYPE, ProblemError, RawJSONResponse, problem
from .routing import LeanRoute
from .runtime import runtime_of
from .schemas import HealthResponse, ReadyResponse

router = APIRouter(tags=["operations"], route_class=LeanRoute)

_HEALTHY = HealthResponse(status="ok").model_dump_json().encode()


@router.get("/healthz", name="healthz", summary="Liveness", response_model=HealthResponse)
async def healthz() -> RawJSONResponse:
    """The process is up and its event loop answers."""
    return RawJSONResponse(_HEALTHY)


@router.get(
    "/readyz",
    name="readyz",
    summary="Readiness",
    response_model=ReadyResponse,
    responses={
        503: {
            "description": "Starting, restarting its workers, or draining",
            "content": {
                PROBLEM_MEDIA_TYPE: {"schema": {"$ref": "#/components/schemas/ProblemResponse"}}
            },
        }
    },
)
async def readyz(request: Request) -> RawJSONResponse:
    """Ready when the worker pool is up and accepting work; 503 otherwise."""
    pool = runtime_of(request).pool
    if pool is None or not pool.ready:
        state: str = "stopped" if pool is None else pool.state
        if state == "ready":  # ready by state, but a worker has died: about to restart
            state = "restarting its workers"
        raise ProblemError(problem("not_ready", f"the worker pool is {state}"))
    ready = ReadyResponse(
        status="ready", workers=pool.size, in_flight=pool.in_flight, queue_capacity=pool.capacity
    )
    return RawJSONResponse(ready.model_dump_json().encode())
