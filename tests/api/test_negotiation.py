"""The choice of answer the three approximate endpoints share (``api/negotiation.py``), and
the writers each answer needs, without a server."""

from __future__ import annotations

from typing import Any

import httpx
import pytest

from arcspline.api.drawing_schemas import DxfRequest
from arcspline.api.errors import ProblemError
from arcspline.api.negotiation import (
    BATCH_MEDIA_TYPES,
    filename,
    media_type_for,
    negotiate,
    writers_for,
)
from arcspline.outputs import WRITERS
from arcspline.outputs.dxf import DxfOptions
from arcspline.outputs.gcode import GcodeOptions
from arcspline.outputs.svg_document import SvgDocumentOptions

from .conftest import locs, problem_of


@pytest.mark.parametrize(
    ("accept", "output"),
    [
        (None, "json"),
        ("", "json"),
        ("*/*", "json"),
        ("application/json", "json"),
        ("application/*", "json"),
        ("text/x-gcode", "gcode"),
        ("text/plain", "gcode"),
        ("image/vnd.dxf", "dxf"),
        ("application/dxf", "dxf"),
        ("IMAGE/SVG+XML", "svg"),
        ("image/svg+xml;q=0.4, image/vnd.dxf;q=0.5", "dxf"),
        ("image/svg+xml, image/vnd.dxf", "svg"),  # equal quality: as written
        ("text/x-gcode;q=0, */*", "json"),  # q=0: not acceptable
        ("text/x-gcode;q=zero, image/svg+xml;q=0.1", "svg"),  # a bad q counts as 0
        ("text/html, application/xhtml+xml, */*;q=0.8", "json"),  # a browser
        ("text/*", "gcode"),  # a range: its one output
        ("image/*", "svg"),  # a range: its first output
    ],
)
def test_accept_chooses_the_best_output_it_names(accept: str | None, output: str) -> None:
    assert negotiate(None, accept) == output


def test_what_the_request_chose_wins_over_accept() -> None:
    assert negotiate("dxf", "text/x-gcode") == "dxf"
    assert negotiate("json", "application/pdf") == "json"


@pytest.mark.parametrize("accept", ["application/pdf", "audio/*", "text/x-gcode;q=0"])
def test_an_accept_naming_nothing_we_give_is_not_acceptable(accept: str) -> None:
    with pytest.raises(ProblemError) as info:
        negotiate(None, accept)
    assert info.value.problem["status"] == 406
    assert accept in info.value.problem["detail"]


def test_writers_for_each_output() -> None:
    program = GcodeOptions(feed_rate=100.0)
    assert writers_for("json", None, "mm") == ()
    assert writers_for("json", program, "mm") == (("gcode", program),)
    assert writers_for("gcode", program, "inch") == (("gcode", program),)
    assert writers_for("dxf", None, "inch") == (("dxf", DxfOptions("inch")),)
    polyline = DxfRequest(polyline=True, layer_per_toolpath=True)
    assert writers_for("dxf", None, "mm", polyline) == (("dxf", DxfOptions("mm", True, True)),)
    assert writers_for("svg", program, "inch") == (
        ("svg-document", SvgDocumentOptions(units="inch")),
    )
    for output in ("gcode", "dxf", "svg"):
        ((name, _),) = writers_for(output, program, "mm")  # type: ignore[arg-type]
        assert name in WRITERS


def test_the_gcode_output_without_its_options_names_them() -> None:
    with pytest.raises(ProblemError) as info:
        writers_for("gcode", None, "mm")
    problem = info.value.problem
    assert problem["status"] == 422
    assert [e["loc"] for e in problem["errors"]] == [["body", "gcode"]]


def test_filenames() -> None:
    assert filename("spiral", "gcode") == "spiral.ngc"
    assert filename("path", "dxf") == "path.dxf"
    assert filename("drawing", "svg") == "drawing.svg"


@pytest.mark.parametrize(
    ("accept", "media_type"),
    [
        (None, "application/json"),
        ("*/*", "application/json"),
        ("application/*", "application/json"),
        ("application/json; charset=utf-8", "application/json"),
        ("application/x-ndjson", "application/x-ndjson"),
        ("application/json;q=0.5, application/x-ndjson", "application/x-ndjson"),
        ("text/html, */*;q=0.1", "application/json"),
    ],
)
def test_a_batch_answers_what_accept_names(accept: str | None, media_type: str) -> None:
    assert media_type_for(accept, BATCH_MEDIA_TYPES) == media_type


@pytest.mark.parametrize("accept", ["text/plain", "image/*", "application/json;q=0"])
def test_a_batch_refuses_an_accept_it_cannot_answer(accept: str) -> None:
    with pytest.raises(ProblemError) as info:
        media_type_for(accept, BATCH_MEDIA_TYPES)
    assert info.value.problem["status"] == 406
    assert "application/x-ndjson" in info.value.problem["detail"]


BATCHES = ["/v1/approximate/batch", "/v1/paths/batch"]


@pytest.mark.anyio
@pytest.mark.parametrize("url", BATCHES)
async def test_a_batch_refuses_query_parameters_as_the_approximate_endpoints_do(
    client: httpx.AsyncClient, paper_request: dict[str, Any], url: str
) -> None:
    response = await client.post(url + "?output=gcode&tolerence=1", json={"jobs": [{}]})
    problem = problem_of(response, 422)
    assert locs(problem) == [["query", "output"], ["query", "tolerence"]]


@pytest.mark.anyio
@pytest.mark.parametrize("url", BATCHES)
async def test_a_batch_refuses_an_accept_it_cannot_answer_with_406(
    client: httpx.AsyncClient, url: str
) -> None:
    response = await client.post(url, json={"jobs": [{}]}, headers={"Accept": "text/x-gcode"})
    assert "text/x-gcode" in problem_of(response, 406)["detail"]
    response = await client.post(url, json={"jobs": [{}]}, headers={"Accept": "application/*"})
    assert response.status_code == 200, response.text
