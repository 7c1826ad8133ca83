"""One document alone from the spiral and path endpoints (and the query parameter on the
drawing endpoint): G-code, DXF or SVG, chosen by the body's ``output``, the ``output`` query
parameter or the ``Accept`` header; each checked against the JSON answer to the same request
— the program byte for byte, the DXF read back by ezdxf entity by entity."""

from __future__ import annotations

import copy
import io
import math
import xml.etree.ElementTree as ET
from typing import Any

import ezdxf
import httpx
import pytest

from tests.conftest import PAPER_SPIRAL
from tests.support import gcode_reader

from .conftest import locs, problem_of

pytestmark = pytest.mark.anyio

SPIRAL = "/v1/approximate"
PATH = "/v1/paths/approximate"
DRAWING = "/v1/drawings/approximate"
SVG_NS = "{http://www.w3.org/2000/svg}"

#: A cubic, a line, a clockwise half circle and the closing line; then an open subpath.
PATH_DATA = "M 0 0 C 10 0 20 10 30 30 L 40 30 A 5 5 0 0 0 50 30 Z M 60 0 Q 70 10 80 0"
MEDIA_TYPES = {"gcode": "text/x-gcode", "dxf": "image/vnd.dxf", "svg": "image/svg+xml"}
EXTENSIONS = {"gcode": "ngc", "dxf": "dxf", "svg": "svg"}
PROGRAM = {"feed_rate": 600}


def _spiral_body() -> dict[str, Any]:
    return {"spiral": copy.deepcopy(PAPER_SPIRAL), "tolerance": 0.001}


def _path_body() -> dict[str, Any]:
    return {"path": PATH_DATA, "tolerance": 0.01, "strategy": "fewest-arcs"}


ENDPOINTS = [("spiral", SPIRAL, _spiral_body), ("path", PATH, _path_body)]
ENDPOINT_IDS = [stem for stem, _, _ in ENDPOINTS]


def _segments(answer: dict[str, Any]) -> list[dict[str, Any]]:
    """Every segment of a JSON answer, in order (a path's subpaths one after another)."""
    if "segments" in answer:
        return list(answer["segments"])
    return [segment for sub in answer["subpaths"] for segment in sub["segments"]]


def _contents(output: str, response: httpx.Response) -> bytes:
    """What a document says: all of it, but of a DXF its entities (ezdxf stamps the header
    with the time and fresh GUIDs)."""
    if output != "dxf":
        return response.content
    text = response.content
    start = text.index(b"ENTITIES")
    return text[start : text.index(b"ENDSEC", start)]


async def _document(
    client: httpx.AsyncClient, url: str, body: dict[str, Any], **kwargs: Any
) -> httpx.Response:
    response = await client.post(url, json=body, **kwargs)
    assert response.status_code == 200, response.text
    return response


@pytest.mark.parametrize("output", list(MEDIA_TYPES))
@pytest.mark.parametrize(("stem", "url", "make_body"), ENDPOINTS, ids=ENDPOINT_IDS)
async def test_each_output_by_field_query_and_accept_is_the_same_document(
    client: httpx.AsyncClient, stem: str, url: str, make_body: Any, output: str
) -> None:
    body = {**make_body(), "gcode": PROGRAM}
    answers = [
        await _document(client, url, {**body, "output": output}),
        await _document(client, url, body, params={"output": output}),
        await _document(client, url, body, headers={"Accept": MEDIA_TYPES[output]}),
    ]
    for response in answers:
        assert response.headers["content-type"].split(";")[0] == MEDIA_TYPES[output]
        disposition = response.headers["content-disposition"]
        assert disposition == f'attachment; filename="{stem}.{EXTENSIONS[output]}"'
        assert response.headers["x-request-id"]
        assert _contents(output, response) == _contents(output, answers[0])
    text = answers[0].text
    if output == "gcode":
        assert gcode_reader.read(text).cuts
    elif output == "dxf":
        assert len(ezdxf.read(io.StringIO(text)).modelspace()) > 0
    else:
        assert ET.fromstring(text).tag == f"{SVG_NS}svg"


@pytest.mark.parametrize(("stem", "url", "make_body"), ENDPOINTS, ids=ENDPOINT_IDS)
async def test_the_raw_program_is_the_json_answers_program_byte_for_byte(
    client: httpx.AsyncClient, stem: str, url: str, make_body: Any
) -> None:
    for options in (PROGRAM, {"feed_rate": 600, "units": "inch", "line_numbers": True}):
        body = {**make_body(), "gcode": options}
        program = (await _document(client, url, body)).json()["gcode"]
        raw = await _document(client, url, {**body, "output": "gcode"})
        assert raw.content == program.encode()


def _same_point(a: Any, b: Any) -> bool:
    return math.dist((a[0], a[1]), (b[0], b[1])) <= 1e-9


@pytest.mark.parametrize(("stem", "url", "make_body"), ENDPOINTS, ids=ENDPOINT_IDS)
async def test_the_dxf_read_back_has_the_json_answers_segments(
    client: httpx.AsyncClient, stem: str, url: str, make_body: Any
) -> None:
    body = make_body()
    segments = _segments((await _document(client, url, body)).json())
    raw = await _document(client, url, {**body, "output": "dxf"})
    doc = ezdxf.read(io.StringIO(raw.text))
    assert doc.header["$INSUNITS"] == 4  # mm, without G-code options
    entities = list(doc.modelspace().query("LINE ARC"))
    assert len(entities) == len(segments) == len(doc.modelspace())
    kinds = {"LINE": "line", "ARC": "arc"}
    for entity, segment in zip(entities, segments, strict=True):
        assert kinds[entity.dxftype()] == segment["type"]
        if entity.dxftype() == "LINE":
            ends = (entity.dxf.start, entity.dxf.end)
        else:
            # ezdxf's own end points (centre + radius·(cos, sin) of the angles); a DXF arc
            # runs anticlockwise, so a clockwise segment's ends come swapped.
            assert _same_point(entity.dxf.center, segment["center"])
            assert entity.dxf.radius == pytest.approx(segment["radius"], abs=1e-9)
            ends = (entity.start_point, entity.end_point)
            if segment["direction"] == "cw":
                ends = ends[::-1]
        assert _same_point(ends[0], segment["start"])
        assert _same_point(ends[1], segment["end"])
    if stem == "path":
        assert {s["direction"] for s in segments if s["type"] == "arc"} == {"ccw", "cw"}
        assert any(s["type"] == "line" for s in segments)


@pytest.mark.parametrize(("stem", "url", "make_body"), ENDPOINTS, ids=ENDPOINT_IDS)
async def test_documents_are_in_the_programs_units_else_millimetres(
    client: httpx.AsyncClient, stem: str, url: str, make_body: Any
) -> None:
    inch = {**make_body(), "gcode": {"feed_rate": 20, "units": "inch"}}
    dxf = ezdxf.read(io.StringIO((await _document(client, url, {**inch, "output": "dxf"})).text))
    assert (dxf.header["$INSUNITS"], dxf.header["$MEASUREMENT"]) == (1, 0)
    for body, unit in ((inch, "in"), (make_body(), "mm")):
        root = ET.fromstring((await _document(client, url, {**body, "output": "svg"})).text)
        assert root.get("width", "").endswith(unit)
        assert root.get("height", "").endswith(unit)
        toolpaths = [p for p in root.iter(f"{SVG_NS}path") if p.get("id", "").startswith("tool")]
        assert len(toolpaths) == (2 if stem == "path" else 1)


@pytest.mark.parametrize(("stem", "url", "make_body"), ENDPOINTS, ids=ENDPOINT_IDS)
async def test_json_is_the_default_and_can_be_asked_for(
    client: httpx.AsyncClient, stem: str, url: str, make_body: Any
) -> None:
    body = make_body()
    for kwargs in (
        {},
        {"headers": {"Accept": "*/*"}},
        {"headers": {"Accept": "application/json"}},
        {"headers": {"Accept": "text/html, application/*;q=0.8"}},
        {"params": {"output": "json"}, "headers": {"Accept": "text/x-gcode"}},
    ):
        response = await _document(client, url, {**body, "output": None}, **kwargs)
        assert response.headers["content-type"] == "application/json"
        assert "content-disposition" not in response.headers
        assert _segments(response.json())


@pytest.mark.parametrize(("stem", "url", "make_body"), ENDPOINTS, ids=ENDPOINT_IDS)
async def test_the_field_wins_over_the_query_which_wins_over_accept(
    client: httpx.AsyncClient, stem: str, url: str, make_body: Any
) -> None:
    body = {**make_body(), "gcode": PROGRAM}
    by_field = await _document(
        client, url, {**body, "output": "dxf"}, params={"output": "svg"},
        headers={"Accept": "text/x-gcode"},
    )  # fmt: skip
    assert by_field.headers["content-type"].startswith("image/vnd.dxf")
    by_query = await _document(
        client, url, body, params={"output": "svg"}, headers={"Accept": "text/x-gcode"}
    )
    assert by_query.headers["content-type"].startswith("image/svg+xml")


@pytest.mark.parametrize(("stem", "url", "make_body"), ENDPOINTS, ids=ENDPOINT_IDS)
async def test_accept_is_ranked_by_quality_and_takes_the_dxf_alias(
    client: httpx.AsyncClient, stem: str, url: str, make_body: Any
) -> None:
    body = {**make_body(), "gcode": PROGRAM}
    ranked = await _document(
        client, url, body, headers={"Accept": "image/svg+xml;q=0.5, text/x-gcode, */*;q=0.1"}
    )
    assert ranked.headers["content-type"].startswith("text/x-gcode")
    alias = await _document(
        client, url, body, headers={"Accept": "application/pdf, application/dxf"}
    )
    assert alias.headers["content-type"].startswith("image/vnd.dxf")


@pytest.mark.parametrize(("stem", "url", "make_body"), ENDPOINTS, ids=ENDPOINT_IDS)
async def test_an_accept_header_naming_nothing_we_give_is_a_406(
    client: httpx.AsyncClient, stem: str, url: str, make_body: Any
) -> None:
    for accept in ("application/pdf", "image/png, text/x-gcode;q=0"):
        response = await client.post(url, json=make_body(), headers={"Accept": accept})
        problem = problem_of(response, 406)
        assert problem["type"].endswith(":not-acceptable")
        assert "text/x-gcode" in problem["detail"]


@pytest.mark.parametrize(("stem", "url", "make_body"), ENDPOINTS, ids=ENDPOINT_IDS)
async def test_the_gcode_output_needs_the_programs_options(
    client: httpx.AsyncClient, stem: str, url: str, make_body: Any
) -> None:
    body = make_body()
    for kwargs in (
        {"json": {**body, "output": "gcode"}},
        {"json": body, "params": {"output": "gcode"}},
        {"json": body, "headers": {"Accept": "text/x-gcode"}},
    ):
        problem = problem_of(await client.post(url, **kwargs), 422)
        assert locs(problem) == [["body", "gcode"]]


@pytest.mark.parametrize(("stem", "url", "make_body"), ENDPOINTS, ids=ENDPOINT_IDS)
async def test_bad_query_parameters_are_named(
    client: httpx.AsyncClient, stem: str, url: str, make_body: Any
) -> None:
    body = make_body()
    unknown = problem_of(await client.post(url, json=body, params={"output": "pdf"}), 422)
    assert locs(unknown) == [["query", "output"]]
    # The body's field wins, but a bad query is still refused, as is a parameter it would
    # ignore (a typo).
    both = {"output": "GCODE", "ouptut": "gcode"}
    problem = problem_of(await client.post(url, json={**body, "output": "json"}, params=both), 422)
    assert sorted(locs(problem)) == sorted([["query", "output"], ["query", "ouptut"]])


@pytest.mark.parametrize(("stem", "url", "make_body"), ENDPOINTS, ids=ENDPOINT_IDS)
async def test_a_document_the_core_refuses_is_a_problem(
    client: httpx.AsyncClient, stem: str, url: str, make_body: Any
) -> None:
    body = {**make_body(), "tolerance": 1e-14, "output": "dxf"}
    problem = problem_of(await client.post(url, json=body), 422)
    assert problem["type"].endswith(":tolerance-floor")


async def test_a_batch_answers_json_only(client: httpx.AsyncClient) -> None:
    jobs = [{**_spiral_body(), "output": "dxf"}, {**_spiral_body(), "output": "json"}]
    response = await client.post("/v1/approximate/batch", json={"jobs": jobs})
    assert response.status_code == 200, response.text
    first, second = response.json()["results"]
    assert first["status"] == "error"
    assert [e["loc"] for e in first["error"]["errors"]] == [["body", "jobs", 0, "output"]]
    assert second["status"] == "ok"
    paths = {"jobs": [{**_path_body(), "output": "gcode", "gcode": PROGRAM}]}
    (entry,) = (await client.post("/v1/paths/batch", json=paths)).json()["results"]
    assert [e["loc"] for e in entry["error"]["errors"]] == [["body", "jobs", 0, "output"]]


async def test_a_preview_ignores_output(client: httpx.AsyncClient) -> None:
    response = await client.post("/v1/preview", json={**_spiral_body(), "output": "dxf"})
    assert response.status_code == 200, response.text
    assert response.headers["content-type"].startswith("image/svg+xml")
    assert "content-disposition" not in response.headers


# -- the drawing endpoint's query --------------------------------------------------------

DRAWING_BODY = {
    "document": '<svg xmlns="http://www.w3.org/2000/svg" width="60mm" height="40mm" '
    'viewBox="0 0 60 40"><circle cx="30" cy="20" r="6"/></svg>',
    "format": "svg",
    "tolerance": 0.01,
}


async def test_a_drawings_json_body_takes_the_output_query_parameter(
    client: httpx.AsyncClient,
) -> None:
    body = {**DRAWING_BODY, "gcode": PROGRAM}
    by_query = await _document(client, DRAWING, body, params={"output": "gcode"})
    assert by_query.headers["content-type"].startswith("text/x-gcode")
    assert by_query.headers["content-disposition"] == 'attachment; filename="drawing.ngc"'
    by_field = await _document(client, DRAWING, {**body, "output": "gcode"})
    assert by_query.content == by_field.content
    wins = await _document(client, DRAWING, {**body, "output": "json"}, params={"output": "svg"})
    assert wins.headers["content-type"] == "application/json"


async def test_a_drawings_json_body_refuses_the_raw_documents_parameters(
    client: httpx.AsyncClient,
) -> None:
    response = await client.post(DRAWING, json=DRAWING_BODY, params={"tolerance": "0.5"})
    assert locs(problem_of(response, 422)) == [["query", "tolerance"]]
    response = await client.post(DRAWING, json=DRAWING_BODY, params={"output": "ngc"})
    assert locs(problem_of(response, 422)) == [["query", "output"]]


async def test_a_raw_documents_query_values_are_bounded(client: httpx.AsyncClient) -> None:
    response = await client.post(
        DRAWING,
        content=DRAWING_BODY["document"].encode(),
        headers={"Content-Type": "image/svg+xml"},
        params={"tolerance": "0.01", "safe_z": "0" * 101},
    )
    problem = problem_of(response, 422)
    assert locs(problem) == [["query", "safe_z"]]
    assert problem["errors"][0]["type"] == "string_too_long"
