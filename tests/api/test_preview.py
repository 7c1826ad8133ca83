"""POST /v1/preview: an SVG document that shows what the issue asks for."""

from __future__ import annotations

import re
import xml.etree.ElementTree as ET
from typing import Any

import httpx
import pytest

from arcspline.outputs.svg import COLOURS

from .conftest import locs, problem_of

pytestmark = pytest.mark.anyio

SVG = "{http://www.w3.org/2000/svg}"


async def test_the_preview_draws_the_spiral_arcs_centres_and_deviation(
    client: httpx.AsyncClient, paper_request: dict[str, Any]
) -> None:
    response = await client.post("/v1/preview", json=paper_request)
    assert response.status_code == 200, response.text
    assert response.headers["content-type"].startswith("image/svg+xml")
    root = ET.fromstring(response.text)
    assert root.tag == f"{SVG}svg"
    arcs = [p for p in root.iter(f"{SVG}path") if " A" in p.get("d", "")]
    assert len(arcs) == 12  # Table 1: 12 arcs at 0.001
    assert [p.get("stroke") for p in arcs] == [COLOURS[i % 2] for i in range(12)]
    centres = list(root.iter(f"{SVG}circle"))
    assert [c.get("fill") for c in centres] == [COLOURS[i % 2] for i in range(12)]
    # The spiral, plus one magnified-deviation curve per segment.
    assert len(list(root.iter(f"{SVG}polyline"))) == 1 + 12
    legend = " ".join(t.text or "" for t in root.iter(f"{SVG}text"))
    magnify = re.search(r"deviation ×(\S+)", legend)
    assert magnify is not None
    assert float(magnify.group(1)) > 1
    assert "12 arcs" in legend
    assert "tolerance 0.001" in legend


async def test_preview_errors_are_problems(client: httpx.AsyncClient) -> None:
    body = {"spiral": {"control_points": [[0, 0], [1, 0]]}, "tolerance": 0.1}
    problem = problem_of(await client.post("/v1/preview", json=body), 422)
    assert ["body", "spiral", "control_points"] in locs(problem)


async def test_a_spiral_at_the_edge_of_double_precision_draws_or_is_refused(
    client: httpx.AsyncClient,
) -> None:
    # Found by schemathesis: coordinates next to the largest double overflowed while drawing.
    body = {
        "spiral": {
            "start": [0.0, 1.7976931348623141e308],
            "start_tangent": [0.0, 1.0],
            "turn_angle_deg": 1.0,
            "end_curvature": -1.0,
        },
        "tolerance": 5.1093511924088776e294,
    }
    response = await client.post("/v1/preview", json=body)
    if response.status_code == 200:
        ET.fromstring(response.text)
        assert not re.search(r"nan|inf", response.text.split("<text")[0], re.IGNORECASE)
    else:
        assert locs(problem_of(response, 422))[0][:2] == ["body", "spiral"]


PATH = {"path": "M 0 0 L 10 0", "tolerance": 0.01}


@pytest.fixture(params=["/v1/preview", "/v1/paths/preview"])
def preview(request: pytest.FixtureRequest, paper_request: dict[str, Any]) -> tuple[str, Any]:
    """A preview endpoint and a request it draws."""
    url: str = request.param
    return url, paper_request if url == "/v1/preview" else PATH


async def test_a_preview_refuses_query_parameters(
    client: httpx.AsyncClient, preview: tuple[str, Any]
) -> None:
    url, body = preview
    response = await client.post(url + "?scale=2", json=body)
    assert locs(problem_of(response, 422)) == [["query", "scale"]]


async def test_a_preview_refuses_an_accept_other_than_svg(
    client: httpx.AsyncClient, preview: tuple[str, Any]
) -> None:
    url, body = preview
    response = await client.post(url, json=body, headers={"Accept": "application/json"})
    assert "image/svg+xml" in problem_of(response, 406)["detail"]
    for accept in ("image/svg+xml", "image/*", "text/html, */*;q=0.8"):
        response = await client.post(url, json=body, headers={"Accept": accept})
        assert response.status_code == 200, (accept, response.text)
        assert response.headers["content-type"].startswith("image/svg+xml")


async def test_a_drawing_preview_refuses_an_accept_other_than_svg(
    client: httpx.AsyncClient,
) -> None:
    svg = '<svg xmlns="http://www.w3.org/2000/svg"><path d="M 0 0 L 10 0"/></svg>'
    body = {"document": svg, "format": "svg", "tolerance": 0.01}
    response = await client.post(
        "/v1/drawings/preview", json=body, headers={"Accept": "application/json"}
    )
    assert "image/svg+xml" in problem_of(response, 406)["detail"]
    response = await client.post("/v1/drawings/preview", json=body)
    assert response.status_code == 200, response.text
