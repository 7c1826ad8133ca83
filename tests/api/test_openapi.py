"""The committed contract (openapi/openapi.json) is exactly what the app serves."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import httpx
import pytest

from arcspline.api.app import create_app
from arcspline.api.export import render
from arcspline.api.schemas import PAPER_EXAMPLE, ApproximateRequest
from arcspline.settings import Settings

OPENAPI = Path(__file__).resolve().parents[2] / "openapi" / "openapi.json"


@pytest.fixture(scope="module")
def served() -> dict[str, Any]:
    document: dict[str, Any] = create_app(Settings()).openapi()
    return document


def test_the_committed_document_is_what_the_app_serves(served: dict[str, Any]) -> None:
    committed = json.loads(OPENAPI.read_text(encoding="utf-8"))
    assert committed == served, "openapi/openapi.json is out of date: run `make openapi`"
    assert OPENAPI.read_text(encoding="utf-8") == render(served), "run `make openapi`"


def test_operation_ids_are_stable(served: dict[str, Any]) -> None:
    ids = {
        (path, method): operation["operationId"]
        for path, item in served["paths"].items()
        for method, operation in item.items()
    }
    assert ids == {
        ("/v1/approximate", "post"): "approximate",
        ("/v1/approximate/batch", "post"): "approximate_batch",
        ("/v1/preview", "post"): "preview",
        ("/v1/paths/approximate", "post"): "approximate_path",
        ("/v1/paths/batch", "post"): "approximate_paths_batch",
        ("/v1/paths/preview", "post"): "preview_path",
        ("/v1/drawings/approximate", "post"): "approximate_drawing",
        ("/v1/drawings/preview", "post"): "preview_drawing",
        ("/healthz", "get"): "healthz",
        ("/readyz", "get"): "readyz",
        ("/metrics", "get"): "metrics",
    }


def test_the_request_example_is_the_papers_and_is_valid(served: dict[str, Any]) -> None:
    example = served["components"]["schemas"]["ApproximateRequest"]["examples"][0]
    assert example == PAPER_EXAMPLE
    assert example["spiral"]["turn_angle_deg"] == 51.34
    ApproximateRequest.model_validate(example)


def test_every_error_response_is_problem_json(served: dict[str, Any]) -> None:
    for item in served["paths"].values():
        for operation in item.values():
            for status, response in operation["responses"].items():
                if int(status) >= 400:
                    assert list(response["content"]) == ["application/problem+json"]


@pytest.mark.anyio
async def test_the_app_serves_the_document(served: dict[str, Any]) -> None:
    transport = httpx.ASGITransport(app=create_app(Settings()))
    async with httpx.AsyncClient(transport=transport, base_url="http://testserver") as client:
        response = await client.get("/openapi.json")
    assert response.status_code == 200
    assert response.json() == served
