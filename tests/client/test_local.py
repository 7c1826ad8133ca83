"""The service without a server (``local_client``): the same answers as a real server,
with jobs in a thread of this process or in a pool of worker processes."""

from __future__ import annotations

import asyncio
from typing import Any

import pytest

from arcspline.client import AsyncClient, ServiceError, local_client
from arcspline.settings import Settings
from tests.support.server import Server

from .test_sync import DRAWING, PATH


async def _answers(client: AsyncClient, paper_request: dict[str, Any]) -> list[Any]:
    program = {**DRAWING, "gcode": {"feed_rate": 600}}
    return [
        await client.approximate(paper_request),
        await client.approximate_path(PATH),
        await client.approximate_drawing(DRAWING),
        await client.document(program, "gcode"),
        await client.preview(PATH),
        await client.approximate_batch([paper_request, {**paper_request, "tolerance": 0.1}]),
    ]


@pytest.mark.parametrize("workers", [0, 2])
def test_local_answers_are_the_servers(
    server: Server, paper_request: dict[str, Any], workers: int
) -> None:
    async def run() -> tuple[list[Any], list[Any], int]:
        async with local_client(workers=workers) as local:
            ours = await _answers(local, paper_request)
            ready = (await local.ready()).workers
        async with AsyncClient(server.url) as remote:
            theirs = await _answers(remote, paper_request)
        return ours, theirs, ready

    ours, theirs, ready = asyncio.run(run())
    assert ours == theirs
    assert ready == max(1, workers)


def test_local_refusals_are_the_servers(paper_request: dict[str, Any]) -> None:
    async def run() -> ServiceError:
        async with local_client() as local:
            try:
                await local.approximate({**paper_request, "tolerance": 1e-300})
            except ServiceError as error:
                return error
        raise AssertionError("a tolerance of 1e-300 was accepted")

    error = asyncio.run(run())
    assert (error.status, error.kind) == (422, "tolerance-floor")
    assert error.limit is not None


def test_a_local_drawing_may_be_larger_than_the_services() -> None:
    # One line more than the service's default allows (50 000): answered locally, refused
    # when the local limit is set to the service's.
    lines = DEFAULT_DRAWING_MAX_SEGMENTS + 1
    svg = '<svg xmlns="http://www.w3.org/2000/svg">' + "".join(
        f'<line x1="{i}" y1="0" x2="{i}" y2="5"/>' for i in range(lines)
    ) + "</svg>"  # fmt: skip
    request = {"format": "svg", "document": svg, "tolerance": 0.01}

    async def run(**settings: Any) -> int | ServiceError:
        async with local_client(**settings) as local:
            try:
                answer = await local.approximate_drawing(request)
            except ServiceError as error:
                return error
            return answer.stats.segment_count

    assert asyncio.run(run()) == lines
    refused = asyncio.run(run(drawing_max_segments=DEFAULT_DRAWING_MAX_SEGMENTS))
    assert isinstance(refused, ServiceError)
    assert refused.status == 422


DEFAULT_DRAWING_MAX_SEGMENTS = Settings.model_fields["drawing_max_segments"].default
