"""The committed contract (openapi/openapi.json) is exactly what the app serves."""

from __future__ import annotations

import json
from collections.abc import Iterator
from importlib.metadata import version
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


# -- contract quality ----------------------------------------------------------------------

APPROXIMATE_PATHS = ("/v1/approximate", "/v1/paths/approximate", "/v1/drawings/approximate")
DOCUMENT_MEDIA_TYPES = ("text/x-gcode", "image/vnd.dxf", "image/svg+xml")


def _operations(document: dict[str, Any]) -> list[tuple[str, str, dict[str, Any]]]:
    return [
        (path, method, operation)
        for path, item in document["paths"].items()
        for method, operation in item.items()
    ]


def test_the_document_says_who_and_what(served: dict[str, Any]) -> None:
    info = served["info"]
    assert info["version"] == version("arcspline") == "0.1.0"
    assert info["license"] == {"name": "MIT", "identifier": "MIT"}
    assert info["contact"]["name"] == "arcspline maintainers"
    assert "email" not in info["contact"]
    urls = [server["url"] for server in served["servers"]]
    assert "http://127.0.0.1:8000" in urls
    assert all(server["description"] for server in served["servers"])
    assert served["security"] == []  # none, said so (not forgotten)


def test_every_tag_used_is_declared_with_a_description(served: dict[str, Any]) -> None:
    declared = {tag["name"]: tag.get("description") for tag in served["tags"]}
    used = {tag for _, _, operation in _operations(served) for tag in operation["tags"]}
    assert used == set(declared)
    assert all(declared.values())


def _resolve(document: dict[str, Any], schema: dict[str, Any]) -> tuple[str | None, dict[str, Any]]:
    ref = schema.get("$ref")
    if ref is None:
        return None, schema
    name = ref.removeprefix("#/components/schemas/")
    resolved: dict[str, Any] = document["components"]["schemas"][name]
    return name, resolved


def _request_schemas(document: dict[str, Any]) -> Iterator[tuple[str, dict[str, Any]]]:
    """Every schema a request can meet (bodies and parameters, through every reference),
    with where it is."""
    pending: list[tuple[str, dict[str, Any]]] = []
    for path, method, operation in _operations(document):
        for media_type, media in operation.get("requestBody", {}).get("content", {}).items():
            pending.append((f"{method} {path} {media_type}", media["schema"]))
        for parameter in operation.get("parameters", []):
            pending.append((f"{method} {path} ?{parameter['name']}", parameter["schema"]))
    seen: set[str] = set()
    while pending:
        where, schema = pending.pop()
        name, schema = _resolve(document, schema)
        if name is not None:
            if name in seen:
                continue
            seen.add(name)
            where = name
        yield where, schema
        for key in ("anyOf", "oneOf", "allOf"):
            pending += [(f"{where}.{key}", s) for s in schema.get(key, [])]
        if "items" in schema:
            pending.append((f"{where}[]", schema["items"]))
        pending += [(f"{where}.{k}", s) for k, s in schema.get("properties", {}).items()]


def test_every_array_and_string_of_the_requests_is_bounded(served: dict[str, Any]) -> None:
    unbounded = [
        where
        for where, schema in _request_schemas(served)
        if (schema.get("type") == "array" and "maxItems" not in schema)
        or (schema.get("type") == "string" and not {"maxLength", "enum", "const"} & set(schema))
    ]
    assert unbounded == []
    jobs = served["components"]["schemas"]["BatchRequest"]["properties"]["jobs"]
    assert jobs["maxItems"] == Settings().batch_max_jobs


def test_request_schemas_require_only_what_has_no_default(served: dict[str, Any]) -> None:
    for where, schema in _request_schemas(served):
        defaulted = {k for k, s in schema.get("properties", {}).items() if "default" in s}
        assert not defaulted & set(schema.get("required", [])), where
    names = served["components"]["schemas"]
    assert not [name for name in names if name.endswith(("-Input", "-Output"))]
    assert names["ApproximateRequest"]["required"] == ["spiral", "tolerance"]


def test_batch_jobs_are_references_to_the_single_request(served: dict[str, Any]) -> None:
    schemas = served["components"]["schemas"]
    for batch, single in (
        ("BatchRequest", "ApproximateRequest"),
        ("PathBatchRequest", "PathRequest"),
    ):
        items = schemas[batch]["properties"]["jobs"]["items"]
        assert items == {"$ref": f"#/components/schemas/{single}"}


def test_every_response_declares_its_headers(served: dict[str, Any]) -> None:
    headers = served["components"]["headers"]
    assert headers["X-Request-ID"]["required"] is True
    assert headers["Retry-After"]["schema"] == {"type": "integer", "minimum": 1}
    assert headers["Content-Disposition"]["required"] is False
    statuses = set()
    for path, method, operation in _operations(served):
        for status, response in operation["responses"].items():
            statuses.add(status)
            declared = response["headers"]
            assert declared["X-Request-ID"] == {"$ref": "#/components/headers/X-Request-ID"}
            if status == "503":
                assert declared["Retry-After"] == {"$ref": "#/components/headers/Retry-After"}
            if DOCUMENT_MEDIA_TYPES[0] in response.get("content", {}):
                assert "Content-Disposition" in declared, (method, path)
    assert "503" in statuses


def test_the_approximate_endpoints_declare_every_answer(served: dict[str, Any]) -> None:
    for path in APPROXIMATE_PATHS:
        operation = served["paths"][path]["post"]
        content = operation["responses"]["200"]["content"]
        assert list(content) == ["application/json", *DOCUMENT_MEDIA_TYPES]
        assert "$ref" in content["application/json"]["schema"]
        for media_type in DOCUMENT_MEDIA_TYPES:
            assert content[media_type]["schema"] == {"type": "string"}
        assert {"406", "422"} <= set(operation["responses"])
        (output,) = (p for p in operation["parameters"] if p["name"] == "output")
        assert output["in"] == "query"
        assert output["schema"]["enum"] == ["json", "gcode", "dxf", "svg"]
    for path in ("/v1/drawings/approximate", "/v1/drawings/preview"):
        assert "415" in served["paths"][path]["post"]["responses"]


def test_every_operation_has_a_client_error_and_every_json_200_an_example(
    served: dict[str, Any],
) -> None:
    for path, method, operation in _operations(served):
        responses = operation["responses"]
        assert any(status.startswith("4") for status in responses), (method, path)
        json_answer = responses["200"].get("content", {}).get("application/json")
        if json_answer is not None:
            assert json_answer["examples"], (method, path)
        body = operation.get("requestBody", {}).get("content", {}).get("application/json")
        if body is not None:
            assert body["examples"], (method, path)


def test_a_raw_documents_query_parameters_have_their_fields_types(
    served: dict[str, Any],
) -> None:
    """Generated clients type ``?tolerance=`` as a number and ``?comments=`` as a flag."""
    operation = served["paths"]["/v1/drawings/approximate"]["post"]
    schemas = {p["name"]: p["schema"] for p in operation["parameters"]}
    assert schemas["tolerance"] == {"type": "number", "exclusiveMinimum": 0}
    assert schemas["decimals"]["type"] == "integer"
    assert schemas["comments"] == {"type": "boolean"}
    assert schemas["strategy"]["enum"] == ["subdivide", "fewest-arcs"]
    layers = next(p for p in operation["parameters"] if p["name"] == "layers")
    assert (layers["schema"]["type"], layers["style"], layers["explode"]) == (
        "array",
        "form",
        False,
    )
