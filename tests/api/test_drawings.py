"""POST /v1/drawings/approximate and /v1/drawings/preview in process: an SVG or DXF document
as a JSON body or as the raw file, the toolpaths checked against the drawing written out by
hand (union Hausdorff distance by the independent path oracle), the outputs (JSON, G-code,
DXF, SVG by ``output`` or ``Accept``), and every refusal as problem details."""

from __future__ import annotations

import base64
import io
import math
import xml.etree.ElementTree as ET
from typing import Any

import ezdxf
import httpx
import pytest

from arcspline.api.drawing_schemas import DrawingResponse
from arcspline.geometry.curves.segments import CircularArc, Cubic, Line, Subpath
from tests.support import gcode_reader, path_oracle

from .conftest import locs, problem_of

pytestmark = pytest.mark.anyio

URL = "/v1/drawings/approximate"
PREVIEW = "/v1/drawings/preview"

#: 60 × 40 mm, one user unit a millimetre: a closed cubic lens and a circle.
SVG = (
    '<svg xmlns="http://www.w3.org/2000/svg" width="60mm" height="40mm" viewBox="0 0 60 40">'
    '<path id="lens" d="M 5 35 C 15 5 45 5 55 35 Z"/>'
    '<circle id="hole" cx="30" cy="25" r="6"/>'
    "<text>label</text></svg>"
)
#: The same drawing by hand, in millimetres with y up (y ↦ 40 − y).
SVG_BY_HAND = Subpath(
    (
        Cubic((5.0, 5.0), (15.0, 35.0), (45.0, 35.0), (55.0, 5.0)),
        Line((55.0, 5.0), (5.0, 5.0)),
        CircularArc((36.0, 15.0), (24.0, 15.0), (30.0, 15.0), 6.0, 0.0, math.pi),
        CircularArc((24.0, 15.0), (36.0, 15.0), (30.0, 15.0), 6.0, math.pi, math.pi),
    )
)


def _dxf(**header: Any) -> bytes:
    """A DXF (R2000) of an L of two LINEs drawn end to start and an ARC, by ezdxf."""
    doc = ezdxf.new("R2000")
    for name, value in header.items():
        doc.header[name] = value
    msp = doc.modelspace()
    msp.add_line((0, 0), (10, 0))
    msp.add_line((10, 10), (10, 0))  # reversed: must be joined to the first
    msp.add_arc((20, 20), 5, 0, 90)
    stream = io.StringIO()
    doc.write(stream)
    return stream.getvalue().encode()


#: The DXF above by hand (mm): the L, and the quarter arc about (20, 20).
DXF_BY_HAND = Subpath(
    (
        Line((0.0, 0.0), (10.0, 0.0)),
        Line((10.0, 0.0), (10.0, 10.0)),
        CircularArc((25.0, 20.0), (20.0, 25.0), (20.0, 20.0), 5.0, 0.0, math.pi / 2),
    )
)


async def _ok(client: httpx.AsyncClient, **kwargs: Any) -> dict[str, Any]:
    response = await client.post(URL, **kwargs)
    assert response.status_code == 200, response.text
    body: dict[str, Any] = response.json()
    DrawingResponse.model_validate(body)
    return body


def _all_segments(body: dict[str, Any]) -> list[dict[str, Any]]:
    # The oracle measures against the whole drawing: no segment claims a source of its own.
    return [
        {k: v for k, v in seg.items() if k != "source_segment"}
        for toolpath in body["toolpaths"]
        for seg in toolpath["segments"]
    ]


def _assert_follows(body: dict[str, Any], by_hand: Subpath, tolerance: float) -> None:
    distance = path_oracle.union_hausdorff(by_hand, _all_segments(body))
    slack = path_oracle.rounding_slack(100.0)
    assert distance.hausdorff <= tolerance + slack, distance


@pytest.mark.parametrize("strategy", ["subdivide", "fewest-arcs"])
async def test_an_svg_drawing_comes_back_within_tolerance_of_the_drawing_by_hand(
    client: httpx.AsyncClient, strategy: str
) -> None:
    body = await _ok(
        client,
        json={"document": SVG, "format": "svg", "tolerance": 0.01, "strategy": strategy},
    )
    assert len(body["toolpaths"]) == 2
    assert all(t["closed"] for t in body["toolpaths"])
    assert sorted(s for t in body["toolpaths"] for s in t["sources"]) == [
        "circle#hole",
        "path#lens",
    ]
    assert body["stats"]["max_deviation"] <= 0.01
    document = body["document"]
    assert document["elements_in"] == document["elements_read"] + document["elements_skipped"]
    assert document["elements_read"] == 2
    assert [w["element"] for w in document["warnings"]] == ["text (line 1)"]
    assert body["rapids"]["after"] <= body["rapids"]["before"]
    _assert_follows(body, SVG_BY_HAND, 0.01)


async def test_the_raw_file_with_query_options_answers_the_same(client: httpx.AsyncClient) -> None:
    as_json = await _ok(client, json={"document": SVG, "format": "svg", "tolerance": 0.01})
    raw = await _ok(
        client,
        content=SVG.encode(),
        headers={"Content-Type": "image/svg+xml"},
        params={"tolerance": "0.01"},
    )
    assert raw == as_json


async def test_a_dxf_drawing_is_joined_into_toolpaths_and_follows_the_drawing(
    client: httpx.AsyncClient,
) -> None:
    body = await _ok(
        client,
        content=_dxf(**{"$INSUNITS": 4}),
        headers={"Content-Type": "application/dxf"},
        params={"tolerance": "0.001"},
    )
    assert len(body["toolpaths"]) == 2  # the L joined, the arc alone
    assert sorted(len(t["sources"]) for t in body["toolpaths"]) == [1, 2]
    assert body["document"]["units"] == "mm"
    _assert_follows(body, DXF_BY_HAND, 0.001)


async def test_inch_drawings_come_out_in_millimetres_or_inches(client: httpx.AsyncClient) -> None:
    dxf = base64.b64encode(_dxf(**{"$INSUNITS": 1})).decode()
    common = {"document": dxf, "format": "dxf", "encoding": "base64", "tolerance": 0.01}
    in_mm = await _ok(client, json=common)
    in_inch = await _ok(client, json={**common, "units": "inch", "tolerance": 0.01 / 25.4})
    ends_mm = [s["end"] for t in in_mm["toolpaths"] for s in t["segments"]]
    ends_inch = [s["end"] for t in in_inch["toolpaths"] for s in t["segments"]]
    assert in_mm["units"] == "mm"
    assert in_inch["units"] == "inch"
    assert max(abs(c) for p in ends_mm for c in p) == pytest.approx(25 * 25.4, rel=1e-12)
    assert max(abs(c) for p in ends_inch for c in p) == pytest.approx(25, rel=1e-12)


async def test_the_request_overrides_the_units_a_drawing_declares(
    client: httpx.AsyncClient,
) -> None:
    dxf = base64.b64encode(_dxf(**{"$INSUNITS": 6})).decode()  # claims metres
    body = await _ok(
        client,
        json={
            "document": dxf, "format": "dxf", "encoding": "base64", "tolerance": 0.001,
            "source_units": "mm",
        },
    )  # fmt: skip
    assert body["document"]["units"] == "mm"
    _assert_follows(body, DXF_BY_HAND, 0.001)


async def test_gcode_by_accept_header_is_the_program_itself(client: httpx.AsyncClient) -> None:
    response = await client.post(
        URL,
        content=SVG.encode(),
        headers={"Content-Type": "image/svg+xml", "Accept": "text/x-gcode"},
        params={"tolerance": "0.01", "feed_rate": "600", "safe_z": "5", "cut_z": "-1"},
    )
    assert response.status_code == 200, response.text
    assert response.headers["content-type"].startswith("text/x-gcode")
    assert 'filename="drawing.ngc"' in response.headers["content-disposition"]
    program = gcode_reader.read(response.text)
    moves = [_as_segment(m) for m in program.cuts]
    assert moves
    # The program, as the controller reads it, follows the drawing both ways within the
    # tolerance plus the rounding of its 4 decimals.
    distance = path_oracle.union_hausdorff(SVG_BY_HAND, moves)
    assert distance.hausdorff <= 0.01 + 1e-4, distance


def _as_segment(move: gcode_reader.Move) -> dict[str, Any]:
    """A program's move as the oracle's segment (the controller's own centre and sweep)."""
    if move.motion == 1:
        return {"type": "line", "start": list(move.xy_start), "end": list(move.xy_end)}
    assert move.centre is not None
    assert move.r_start is not None
    return {
        "type": "arc", "start": list(move.xy_start), "end": list(move.xy_end),
        "center": list(move.centre), "radius": move.r_start,
        "direction": "ccw" if move.motion == 3 else "cw", "sweep_rad": move.sweep_rad,
    }  # fmt: skip


@pytest.mark.parametrize(
    ("output", "media_type"), [("dxf", "image/vnd.dxf"), ("svg", "image/svg+xml")]
)
async def test_dxf_and_svg_outputs_by_field(
    client: httpx.AsyncClient, output: str, media_type: str
) -> None:
    response = await client.post(
        URL, json={"document": SVG, "format": "svg", "tolerance": 0.01, "output": output}
    )
    assert response.status_code == 200, response.text
    assert response.headers["content-type"].startswith(media_type)
    if output == "dxf":
        doc = ezdxf.read(io.StringIO(response.text))
        assert len(doc.modelspace()) > 0
    else:
        ET.fromstring(response.text)


async def test_the_dxf_output_as_polylines_with_bulges(client: httpx.AsyncClient) -> None:
    response = await client.post(
        URL,
        json={
            "document": SVG, "format": "svg", "tolerance": 0.01, "output": "dxf",
            "dxf": {"polyline": True, "layer_per_toolpath": True},
        },
    )  # fmt: skip
    assert response.status_code == 200, response.text
    doc = ezdxf.read(io.StringIO(response.text))
    polylines = list(doc.modelspace().query("LWPOLYLINE"))
    assert len(polylines) == 2
    assert {p.dxf.layer for p in polylines} == {"TOOLPATH_1", "TOOLPATH_2"}
    assert all(p.closed for p in polylines)
    # the circle (6 mm about (30, 15)): every vertex on it, and its bulges turn a full circle
    circle = next(p for p in polylines if p.has_arc and len(p) <= 4)
    points = circle.get_points("xyb")
    assert all(math.hypot(x - 30, y - 15) == pytest.approx(6, abs=1e-9) for x, y, _ in points)
    # (clockwise: SVG draws a circle from angle 0 towards +y, which is down)
    assert sum(4 * math.atan(b) for _, _, b in points) == pytest.approx(-2 * math.pi, abs=1e-9)


async def test_dxf_options_as_query_parameters(client: httpx.AsyncClient) -> None:
    response = await client.post(
        URL,
        content=SVG.encode(),
        headers={"Content-Type": "image/svg+xml", "Accept": "image/vnd.dxf"},
        params={"tolerance": "0.01", "polyline": "true"},
    )
    assert response.status_code == 200, response.text
    doc = ezdxf.read(io.StringIO(response.text))
    assert len(doc.modelspace().query("LWPOLYLINE")) == 2
    assert len(doc.modelspace().query("LINE ARC")) == 0


async def test_preview_draws_the_toolpaths(client: httpx.AsyncClient) -> None:
    response = await client.post(
        PREVIEW, json={"document": SVG, "format": "svg", "tolerance": 0.01}
    )
    assert response.status_code == 200, response.text
    assert response.headers["content-type"].startswith("image/svg+xml")
    ET.fromstring(response.text)


# -- refusals --------------------------------------------------------------------------

BOMB = (
    '<?xml version="1.0"?><!DOCTYPE svg [<!ENTITY a "aaaaaaaaaa">'
    '<!ENTITY b "&a;&a;&a;&a;&a;&a;&a;&a;&a;&a;">]>'
    '<svg xmlns="http://www.w3.org/2000/svg"><text>&b;</text></svg>'
)


@pytest.mark.parametrize(
    ("document", "words"),
    [
        (BOMB, "entit"),
        ('<svg xmlns="http://www.w3.org/2000/svg"><path d="M 0 0 L', "line"),
        ('<svg xmlns="http://www.w3.org/2000/svg"><path id="p" d="M 0 0 X 1"/></svg>', "path#p"),
        ('<svg xmlns="http://www.w3.org/2000/svg"><text>only</text></svg>', "nothing to cut"),
    ],
)
async def test_a_bad_document_is_a_422_naming_where(
    client: httpx.AsyncClient, document: str, words: str
) -> None:
    response = await client.post(
        URL, json={"document": document, "format": "svg", "tolerance": 0.1}
    )
    body = problem_of(response, 422)
    assert body["type"].endswith("invalid-document")
    assert words in body["detail"].lower() or words in body["detail"]
    assert locs(body) == [["body", "document"]]


async def test_an_unknown_media_type_is_a_415(client: httpx.AsyncClient) -> None:
    for url in (URL, PREVIEW):
        response = await client.post(url, content=b"x", headers={"Content-Type": "text/csv"})
        body = problem_of(response, 415)
        assert "text/csv" in body["detail"]


async def test_an_unknown_query_parameter_is_named(client: httpx.AsyncClient) -> None:
    response = await client.post(
        URL,
        content=SVG.encode(),
        headers={"Content-Type": "image/svg+xml"},
        params={"tolerance": "0.01", "tolerence": "1"},
    )
    assert ["query", "tolerence"] in locs(problem_of(response, 422))


async def test_a_bad_query_value_is_named(client: httpx.AsyncClient) -> None:
    response = await client.post(
        URL,
        content=SVG.encode(),
        headers={"Content-Type": "image/svg+xml"},
        params={"tolerance": "fine"},
    )
    assert ["query", "tolerance"] in locs(problem_of(response, 422))


async def test_the_gcode_output_needs_its_options(client: httpx.AsyncClient) -> None:
    response = await client.post(
        URL, json={"document": SVG, "format": "svg", "tolerance": 0.01, "output": "gcode"}
    )
    assert ["body", "gcode"] in locs(problem_of(response, 422))


async def test_an_accept_header_naming_nothing_we_give_is_a_406(client: httpx.AsyncClient) -> None:
    response = await client.post(
        URL,
        json={"document": SVG, "format": "svg", "tolerance": 0.01},
        headers={"Accept": "application/pdf"},
    )
    problem_of(response, 406)


async def test_bad_base64_is_named(client: httpx.AsyncClient) -> None:
    response = await client.post(
        URL,
        json={"document": "@@@", "format": "dxf", "encoding": "base64", "tolerance": 0.01},
    )
    assert ["body", "document"] in locs(problem_of(response, 422))


async def test_an_unknown_layer_is_named(client: httpx.AsyncClient) -> None:
    dxf = base64.b64encode(_dxf()).decode()
    response = await client.post(
        URL,
        json={
            "document": dxf, "format": "dxf", "encoding": "base64", "tolerance": 0.01,
            "layers": ["NOPE"],
        },
    )  # fmt: skip
    body = problem_of(response, 422)
    assert ["body", "layers"] in locs(body)
    assert "NOPE" in body["detail"]


async def test_a_join_tolerance_not_below_the_tolerance_is_refused(
    client: httpx.AsyncClient,
) -> None:
    response = await client.post(
        URL, json={"document": SVG, "format": "svg", "tolerance": 0.01, "join_tolerance": 0.005}
    )
    assert ["body", "join_tolerance"] in locs(problem_of(response, 422))
