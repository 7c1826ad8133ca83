"""The contract's examples (``api/examples.py``) are true: each request is valid, each answer
is valid against its response model and the document's schema, and is what the service
answers for its request today."""

from __future__ import annotations

import json
import typing
from collections.abc import Iterator
from typing import Any

import httpx
import jsonschema
import pytest
from fastapi.routing import APIRoute
from pydantic import BaseModel, TypeAdapter

from arcspline.api import approximate, drawings, health, paths, preview
from arcspline.api.app import create_app
from arcspline.api.examples import OPERATIONS, shorten
from arcspline.api.path_schemas import PathBatchRequest, PathRequest
from arcspline.api.schemas import ApproximateRequest, BatchRequest
from arcspline.settings import Settings

from .spline_json import same_json

DOCUMENT: dict[str, Any] = create_app(Settings()).openapi()
ROUTES = {
    route.name: route
    for module in (approximate, paths, drawings, preview, health)
    for route in module.router.routes
    if isinstance(route, APIRoute)
}
#: The body each job of a batch must be (the batch's own schema takes any job).
JOB_MODELS: dict[type[BaseModel], type[BaseModel]] = {
    BatchRequest: ApproximateRequest,
    PathBatchRequest: PathRequest,
}


def _request_model(operation: str) -> type[BaseModel]:
    model: type[BaseModel] = typing.get_type_hints(ROUTES[operation].endpoint)["body"]
    return model


def _examples(where: str) -> Iterator[tuple[str, str, Any]]:
    """(operation, example name, value) of every example of ``where``."""
    for operation, places in OPERATIONS.items():
        for name, example in places.get(where, {}).items():
            yield operation, name, example["value"]


def _operation(operation: str) -> dict[str, Any]:
    route = ROUTES[operation]
    (method,) = route.methods
    found: dict[str, Any] = DOCUMENT["paths"][route.path][method.lower()]
    return found


def _valid_by_the_document(value: Any, media: dict[str, Any]) -> None:
    schema = {**media["schema"], "components": DOCUMENT["components"]}
    jsonschema.Draft202012Validator(schema).validate(value)


@pytest.mark.parametrize(("operation", "name", "value"), list(_examples("request")))
def test_every_request_example_is_valid(operation: str, name: str, value: Any) -> None:
    model = _request_model(operation)
    body = TypeAdapter(model).validate_json(json.dumps(value))  # strictly, as the service
    for job in getattr(body, "jobs", []):
        TypeAdapter(JOB_MODELS[model]).validate_json(json.dumps(job))
    media = _operation(operation)["requestBody"]["content"]["application/json"]
    _valid_by_the_document(value, media)
    assert media["examples"][name]["value"] == value


@pytest.mark.parametrize(("operation", "name", "value"), list(_examples("application/json")))
def test_every_answer_example_is_valid(operation: str, name: str, value: Any) -> None:
    model = ROUTES[operation].response_model
    assert isinstance(model, type)
    assert issubclass(model, BaseModel)
    model.model_validate(value)
    media = _operation(operation)["responses"]["200"]["content"]["application/json"]
    _valid_by_the_document(value, media)
    # As given: FastAPI would have dropped the nulls ("gcode": null) on the way.
    assert media["examples"][name]["value"] == value


def _without_request_ids(value: Any) -> Any:
    """``value`` without the ``request_id`` of its problems (one per request)."""
    if isinstance(value, dict):
        return {k: _without_request_ids(v) for k, v in value.items() if k != "request_id"}
    if isinstance(value, list):
        return [_without_request_ids(v) for v in value]
    return value


def _answer_example(operation: str, name: str) -> tuple[str, Any]:
    """The media type and value of the answer example named like the request example."""
    for media_type, named in OPERATIONS[operation].items():
        if media_type != "request" and name in named:
            return media_type, named[name]["value"]
    raise AssertionError(f"{operation}: no answer example named {name!r}")


@pytest.mark.anyio
@pytest.mark.parametrize(
    ("operation", "name", "value"),
    [case for case in _examples("request") if not case[0].startswith("preview")],
)
async def test_the_service_answers_what_the_examples_say(
    client: httpx.AsyncClient, operation: str, name: str, value: Any
) -> None:
    response = await client.post(ROUTES[operation].path, json=value)
    assert response.status_code == 200, response.text
    media_type, expected = _answer_example(operation, name)
    assert response.headers["content-type"].split(";")[0] == media_type
    if media_type != "application/json":
        assert response.text == expected
        return
    answer = _without_request_ids(shorten(response.json()))
    # Numbers to 1e-12: another CPU or compiler may round a last digit differently.
    fresh = json.dumps(answer, indent=1)
    assert same_json(answer, _without_request_ids(expected)), f"the service now says {fresh}"


@pytest.mark.anyio
async def test_the_probes_answer_as_their_examples(client: httpx.AsyncClient) -> None:
    (health,) = (example["value"] for example in OPERATIONS["healthz"]["application/json"].values())
    assert (await client.get("/healthz")).json() == health
    (ready,) = (example["value"] for example in OPERATIONS["readyz"]["application/json"].values())
    answer = (await client.get("/readyz")).json()
    assert answer.keys() == ready.keys()
    assert answer["status"] == ready["status"]
