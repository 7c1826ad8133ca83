"""Offsets and machining over HTTP (docs/http-api.md, "Offsets and machining"): the request
fields on paths (JSON, batch) and drawings (JSON body, raw document with query parameters),
the answer's tool-centre paths and its ``offset`` / ``machining`` block, the outputs (the
machining program read back as a controller would), the previews, and every refusal.

Geometric claims are checked against contours written out by hand with the independent
oracle (``tests/support/offset_oracle.py``), by Steiner's formula for the area of an outer
offset of a convex polygon (``A + P·d + π·d²``) and by plain lengths.
"""

from __future__ import annotations

import io
import math
import re
import xml.etree.ElementTree as ET
from typing import Any

import ezdxf
import httpx
import pytest

from arcspline.api.drawing_schemas import DrawingResponse
from arcspline.api.offset_schemas import MAX_LENGTH
from arcspline.api.path_schemas import PathResponse
from arcspline.machining import options as machining_options
from tests.support import gcode_reader
from tests.support import offset_oracle as oracle

from .conftest import locs, problem_of

pytestmark = pytest.mark.anyio

PATHS = "/v1/paths/approximate"
PATHS_BATCH = "/v1/paths/batch"
PATHS_PREVIEW = "/v1/paths/preview"
DRAWINGS = "/v1/drawings/approximate"
DRAWINGS_PREVIEW = "/v1/drawings/preview"
SVG_NS = "{http://www.w3.org/2000/svg}"

#: A 20 × 20 square, anticlockwise.
SQUARE = "M 0 0 L 20 0 L 20 20 L 0 20 Z"
SQUARE_BY_HAND = oracle.polygon([(0, 0), (20, 0), (20, 20), (0, 20)])
#: 60 × 40 mm, a user unit a millimetre: a 50 × 30 plate and a hole of radius 6 in it.
PLATE = (
    '<svg xmlns="http://www.w3.org/2000/svg" width="60mm" height="40mm" viewBox="0 0 60 40">'
    '<rect id="plate" x="5" y="5" width="50" height="30"/>'
    '<circle id="hole" cx="30" cy="20" r="6"/></svg>'
)
#: The plate by hand, in millimetres with y up (y ↦ 40 − y): it is symmetric.
PLATE_BY_HAND = oracle.polygon([(5, 5), (55, 5), (55, 35), (5, 35)])
HOLE_BY_HAND = oracle.circle((30, 20), 6)
#: What the oracle allows beyond the distance: the contours are exact lines and arcs (fit
#: deviation 0), so only rounding.
SLACK = 1e-7
#: A program's coordinates have 4 decimals: half a unit in the last one, each way.
PROGRAM_SLACK = 1e-4


async def _ok(client: httpx.AsyncClient, url: str, **kwargs: Any) -> dict[str, Any]:
    response = await client.post(url, **kwargs)
    assert response.status_code == 200, response.text
    body: dict[str, Any] = response.json()
    (DrawingResponse if url == DRAWINGS else PathResponse).model_validate(body)
    return body


def _segments(answer: list[dict[str, Any]]) -> list[list[oracle.OSeg]]:
    return [oracle.from_json(path["segments"]) for path in answer]


def _length(segs: list[oracle.OSeg]) -> float:
    return sum(s.length for s in segs)


def _plate_json(**more: Any) -> dict[str, Any]:
    return {"document": PLATE, "format": "svg", "tolerance": 0.01, **more}


def _by_source(body: dict[str, Any], name: str) -> list[dict[str, Any]]:
    return [t for t in body["toolpaths"] if any(name in s for s in t["sources"])]


# -- paths ------------------------------------------------------------------------------


async def test_an_outside_offset_of_a_square_is_at_the_distance_and_rounds_its_corners(
    client: httpx.AsyncClient,
) -> None:
    d = 3.0
    body = await _ok(
        client,
        PATHS,
        json={"path": SQUARE, "tolerance": 0.01, "offset": {"distance": d, "side": "outside"}},
    )
    offset = body["offset"]
    assert offset["distance"] == d
    assert offset["side"] == "outside"
    assert (offset["contours_in"], offset["paths_out"]) == (1, 1)
    assert offset["origin"] == [0]
    assert offset["source_max_deviation"] <= 0.01
    assert offset["notes"] == []
    (path,) = _segments(body["subpaths"])
    assert body["subpaths"][0]["closed"]
    report = oracle.check_offset([SQUARE_BY_HAND], [path], d, "outside")
    assert report.ok(d, SLACK), report.describe()
    # Round joins: the path turns smoothly everywhere, and encloses what Steiner's formula
    # says the outer parallel body of a convex polygon has.
    assert oracle.corners(path, closed=True) == []
    steiner = 20.0 * 20.0 + 80.0 * d + math.pi * d * d
    assert abs(oracle.signed_area(path)) == pytest.approx(steiner, rel=1e-12)


async def test_a_mitred_outside_offset_of_a_square_is_the_larger_square(
    client: httpx.AsyncClient,
) -> None:
    d = 3.0
    offset = {"distance": d, "side": "outside", "join": "mitre", "mitre_limit": 2.0}
    body = await _ok(client, PATHS, json={"path": SQUARE, "tolerance": 0.01, "offset": offset})
    (path,) = _segments(body["subpaths"])
    # A square's mitre reaches d·√2 < 2·d from its corner: every corner stays sharp.
    assert len(oracle.corners(path, closed=True)) == 4
    assert abs(oracle.signed_area(path)) == pytest.approx(26.0 * 26.0, rel=1e-12)
    assert _length(path) == pytest.approx(4 * 26.0, rel=1e-12)


async def test_an_inside_offset_of_a_square_is_the_smaller_square(
    client: httpx.AsyncClient,
) -> None:
    d = 3.0
    body = await _ok(
        client,
        PATHS,
        json={"path": SQUARE, "tolerance": 0.01, "offset": {"distance": d, "side": "inside"}},
    )
    (path,) = _segments(body["subpaths"])
    report = oracle.check_offset([SQUARE_BY_HAND], [path], d, "inside")
    assert report.ok(d, SLACK), report.describe()
    assert abs(oracle.signed_area(path)) == pytest.approx(14.0 * 14.0, rel=1e-12)


@pytest.mark.parametrize("side", ["left", "right"])
async def test_an_open_path_is_offset_to_either_side_of_its_travel(
    client: httpx.AsyncClient, side: oracle.Side
) -> None:
    d = 2.0
    body = await _ok(
        client,
        PATHS,
        json={
            "path": "M 0 0 L 20 0 L 20 20",
            "tolerance": 0.01,
            "offset": {"distance": d, "side": side},
        },
    )
    (answer,) = body["subpaths"]
    assert not answer["closed"]
    (path,) = _segments(body["subpaths"])
    contour = oracle.polygon([(0, 0), (20, 0), (20, 20)])[:-1]
    report = oracle.check_offset([contour], [path], d, side)
    assert report.ok(d, SLACK), report.describe()
    # Left is inside the turn: both legs shortened by d. Right: a quarter circle about the
    # corner joins them.
    expected = 2 * (20.0 - d) if side == "left" else 40.0 + math.pi * d / 2
    assert _length(path) == pytest.approx(expected, rel=1e-12)


async def test_a_batch_of_paths_takes_offsets_and_machining_job_by_job(
    client: httpx.AsyncClient,
) -> None:
    jobs = [
        {"path": SQUARE, "tolerance": 0.01, "offset": {"distance": 1.0, "side": "outside"}},
        {"path": SQUARE, "tolerance": 0.01, "machining": {"tool_diameter": 2.0, "lead_radius": 0}},
        {
            "path": SQUARE,
            "tolerance": 0.01,
            "offset": {"distance": 1.0, "side": "outside"},
            "machining": {"tool_diameter": 2.0},
        },
    ]
    response = await client.post(PATHS_BATCH, json={"jobs": jobs})
    assert response.status_code == 200, response.text
    first, second, third = response.json()["results"]
    assert first["status"] == "ok"
    assert first["result"]["offset"]["paths_out"] == 1
    assert second["status"] == "ok"
    assert [c["cut"] for c in second["result"]["machining"]["contours"]] == ["outside"]
    # The same tool centre either way: an outside offset by the tool radius.
    (offset,), (machined,) = (
        _segments(first["result"]["subpaths"]),
        _segments(second["result"]["subpaths"]),
    )
    for path in (offset, machined):
        report = oracle.check_offset([SQUARE_BY_HAND], [path], 1.0, "outside")
        assert report.ok(1.0, SLACK), report.describe()
    assert third["status"] == "error"
    assert third["error"]["status"] == 422
    assert "offset" in third["error"]["detail"]
    assert "machining" in third["error"]["detail"]
    assert third["error"]["errors"][0]["loc"] == ["body", "jobs", 2]


async def test_a_path_program_with_machining_cuts_the_tool_centre(
    client: httpx.AsyncClient,
) -> None:
    d = 1.5
    request = {
        "path": SQUARE,
        "tolerance": 0.01,
        "machining": {"tool_diameter": 2 * d, "lead_radius": 0},
        "gcode": {"feed_rate": 600, "safe_z": 5, "cut_z": -1},
    }
    body = await _ok(client, PATHS, json=request)
    assert body["gcode"]
    document = await client.post(PATHS, json={**request, "output": "gcode"})
    assert document.status_code == 200, document.text
    assert document.text == body["gcode"]
    moves = _cuts_at(document.text, -1.0)
    report = oracle.check_offset([SQUARE_BY_HAND], [moves], d, "outside")
    assert report.ok(d, PROGRAM_SLACK), report.describe()


# -- drawings ---------------------------------------------------------------------------


async def test_a_drawing_offset_keeps_each_contours_sources(client: httpx.AsyncClient) -> None:
    d = 2.0
    body = await _ok(client, DRAWINGS, json=_plate_json(offset={"distance": d, "side": "outside"}))
    offset = body["offset"]
    assert (offset["contours_in"], offset["paths_out"]) == (2, 2)
    assert sorted(offset["origin"]) == [0, 1]
    (plate,), (hole,) = _by_source(body, "plate"), _by_source(body, "hole")
    assert plate["sources"] == ["rect#plate"]
    assert hole["sources"] == ["circle#hole"]
    report = oracle.check_offset(
        [PLATE_BY_HAND, HOLE_BY_HAND], _segments(body["toolpaths"]), d, "outside"
    )
    assert report.ok(d, SLACK), report.describe()
    (plate_path,), (hole_path,) = _segments([plate]), _segments([hole])
    assert abs(oracle.signed_area(plate_path)) == pytest.approx(
        50.0 * 30.0 + 160.0 * d + math.pi * d * d, rel=1e-12
    )
    assert abs(oracle.signed_area(hole_path)) == pytest.approx(math.pi * 8.0**2, rel=1e-9)
    assert body["stats"]["toolpath_count"] == 2


async def test_a_raw_document_takes_the_offset_as_query_parameters(
    client: httpx.AsyncClient,
) -> None:
    offset = {"distance": 2.0, "side": "outside", "join": "mitre", "mitre_limit": 1.5}
    by_json = await _ok(client, DRAWINGS, json=_plate_json(offset=offset))
    params = {"offset": "2", "side": "outside", "join": "mitre", "mitre_limit": "1.5"}
    raw = await client.post(
        DRAWINGS,
        content=PLATE.encode(),
        headers={"Content-Type": "image/svg+xml"},
        params={"tolerance": "0.01", **params},
    )
    assert raw.status_code == 200, raw.text
    assert raw.json() == by_json
    assert by_json["offset"]["side"] == "outside"
    # Mitred: the plate's tool path is the 54 × 34 rectangle, its corners sharp.
    (plate,) = _segments(_by_source(by_json, "plate"))
    assert len(oracle.corners(plate, closed=True)) == 4
    assert abs(oracle.signed_area(plate)) == pytest.approx(54.0 * 34.0, rel=1e-12)


async def test_a_raw_document_takes_machining_as_query_parameters(
    client: httpx.AsyncClient,
) -> None:
    machining = {"tool_diameter": 3.0, "cut": "inside", "lead_radius": 0.0, "join": "mitre"}
    by_json = await _ok(client, DRAWINGS, json=_plate_json(machining=machining))
    params = {"tool_diameter": "3", "cut": "inside", "lead_radius": "0", "join": "mitre"}
    raw = await client.post(
        DRAWINGS,
        content=PLATE.encode(),
        headers={"Content-Type": "image/svg+xml"},
        params={"tolerance": "0.01", **params},
    )
    assert raw.status_code == 200, raw.text
    assert raw.json() == by_json
    assert {c["cut"] for c in by_json["machining"]["contours"]} == {"inside"}


async def test_machining_a_plate_cuts_the_hole_inside_first_then_the_plate_outside(
    client: httpx.AsyncClient,
) -> None:
    d = 2.0
    body = await _ok(
        client,
        DRAWINGS,
        json=_plate_json(
            machining={"tool_diameter": 2 * d, "lead_radius": 0},
            gcode={"feed_rate": 600, "safe_z": 5, "cut_z": -1},
        ),
    )
    machining = body["machining"]
    assert machining["tool_diameter"] == 2 * d
    assert machining["rapid_length"] > 0
    contours = machining["contours"]
    assert len(contours) == len(body["toolpaths"]) == 2
    # Inner contour (nesting depth 1, a hole: inside) before the one around it.
    assert [(c["cut"], c["depth"]) for c in contours] == [("inside", 1), ("outside", 0)]
    assert all(c["direction"] == "climb" for c in contours)
    assert body["toolpaths"][0]["sources"] == ["circle#hole"]
    assert body["toolpaths"][1]["sources"] == ["rect#plate"]
    hole, plate = _segments(body["toolpaths"])
    report = oracle.check_offset(
        [PLATE_BY_HAND, HOLE_BY_HAND], [hole, plate], d, ["outside", "inside"]
    )
    assert report.ok(d, SLACK), report.describe()
    # Climb milling with a clockwise spindle keeps the part on the tool's right: clockwise
    # around the outside, anticlockwise around a hole.
    assert oracle.signed_area(plate) < 0 < oracle.signed_area(hole)
    # The program (JSON's `gcode`) is the machining plan's, read back as a controller would.
    moves = _cuts_at(body["gcode"], -1.0)
    report = oracle.check_offset([PLATE_BY_HAND, HOLE_BY_HAND], [moves], d, ["outside", "inside"])
    assert report.ok(d, PROGRAM_SLACK), report.describe()


async def test_a_split_contour_is_noted_by_its_toolpath_and_elements(
    client: httpx.AsyncClient,
) -> None:
    # A V notched almost to the bottom edge: inside by 2 it splits into two loops.
    vee = (
        '<svg xmlns="http://www.w3.org/2000/svg" width="10mm" height="10mm" viewBox="0 0 10 10">'
        '<polygon id="vee" points="0 10 10 10 10 0 5 9 0 0"/></svg>'
    )
    request = {"document": vee, "format": "svg", "tolerance": 0.01}
    body = await _ok(
        client, DRAWINGS, json={**request, "offset": {"distance": 2, "side": "inside"}}
    )
    offset = body["offset"]
    assert (offset["contours_in"], offset["paths_out"]) == (1, 2)
    assert offset["origin"] == [0, 0]
    assert [t["sources"] for t in body["toolpaths"]] == [["polygon#vee"], ["polygon#vee"]]
    (note,) = offset["notes"]
    assert note["toolpath"] == 0
    assert note["kind"] == "split"
    assert note["message"].startswith("toolpaths[0] (drawn by polygon#vee): ")
    # y up: (x, y) ↦ (x, 10 − y).
    contour = oracle.polygon([(0, 0), (10, 0), (10, 10), (5, 1), (0, 10)])
    report = oracle.check_offset([contour], _segments(body["toolpaths"]), 2.0, "inside")
    assert report.ok(2.0, SLACK), report.describe()


async def test_the_dxf_output_draws_the_tool_centre_paths(client: httpx.AsyncClient) -> None:
    request = _plate_json(offset={"distance": 2.0, "side": "outside"})
    body = await _ok(client, DRAWINGS, json=request)
    response = await client.post(DRAWINGS, json={**request, "output": "dxf"})
    assert response.status_code == 200, response.text
    doc = ezdxf.read(io.StringIO(response.text))
    entities = [e for e in doc.modelspace() if e.dxftype() in ("LINE", "ARC")]
    answer = [s for t in body["toolpaths"] for s in t["segments"]]
    assert len(entities) == len(answer)
    radii = sorted(round(e.dxf.radius, 9) for e in entities if e.dxftype() == "ARC")
    assert radii == sorted(round(s["radius"], 9) for s in answer if s["type"] == "arc")
    # The hole's tool path (radius 6 + 2) and the plate's rounded corners (radius 2).
    assert set(radii) == {2.0, 8.0}


async def test_machining_tabs_leave_the_tool_above_the_cut_over_their_width(
    client: httpx.AsyncClient,
) -> None:
    tabs = {"count": 2, "width": 4.0, "height": 0.5}
    response = await client.post(
        DRAWINGS,
        json=_plate_json(
            machining={"tool_diameter": 4.0, "tabs": tabs},
            gcode={"feed_rate": 600, "safe_z": 5, "cut_z": -1},
            output="gcode",
        ),
    )
    assert response.status_code == 200, response.text
    program = gcode_reader.read(response.text)
    over_tabs = [m for m in program.cuts if m.start[2] == m.end[2] == -0.5]
    assert over_tabs, "no cut passes over a tab"


def _cuts_at(program: str, z: float) -> list[oracle.OSeg]:
    """The program's XY feed moves at depth ``z``, as the controller reads them."""
    segs = []
    for move in gcode_reader.read(program).cuts:
        if not move.start[2] == move.end[2] == z:
            continue
        if move.motion == 1:
            segs.append(oracle.line(move.xy_start, move.xy_end))
        else:
            assert move.centre is not None
            assert move.r_start is not None
            assert move.sweep_rad is not None
            angle = math.atan2(move.start[1] - move.centre[1], move.start[0] - move.centre[0])
            segs.append(oracle.arc(move.centre, move.r_start, angle, move.sweep_rad))
    assert segs, f"no cut at Z{z:g}"
    return segs


# -- previews ---------------------------------------------------------------------------


def _groups(svg: str) -> dict[str, ET.Element]:
    root = ET.fromstring(svg)
    return {g.get("class", ""): g for g in root.iter(f"{SVG_NS}g") if g.get("class")}


def _arc_radii_px(d: str) -> list[float]:
    return [float(r) for r in re.findall(r"A([\d.e+-]+),", d)]


async def test_the_drawing_preview_shows_contours_tool_paths_and_the_swept_band(
    client: httpx.AsyncClient,
) -> None:
    d = 2.0
    response = await client.post(
        DRAWINGS_PREVIEW, json=_plate_json(offset={"distance": d, "side": "outside"})
    )
    assert response.status_code == 200, response.text
    assert response.headers["content-type"].startswith("image/svg+xml")
    groups = _groups(response.text)
    contours = [p.get("d", "") for p in groups["contours"]]
    bands = [p.get("d", "") for p in groups["swept"]]
    assert len(contours) == 2
    assert len(bands) == 2
    # The picture's scale, from the hole's contour (radius 6 mm) drawn as arcs...
    (hole,) = [c for c in contours if _arc_radii_px(c)]
    scale = _arc_radii_px(hole)[0] / 6.0
    # ... puts the tool path around it at 6 + d, and makes the band the tool's diameter.
    tool_radii = sorted(r for band in bands for r in _arc_radii_px(band))
    assert tool_radii[-1] == pytest.approx((6.0 + d) * scale, rel=1e-5)
    width = float(groups["swept"].get("stroke-width", ""))
    assert width == pytest.approx(2 * d * scale, rel=1e-5)
    assert groups["swept"].get("stroke-linejoin") == "round"
    assert groups["swept"].get("stroke-linecap") == "round"
    assert float(groups["swept"].get("stroke-opacity", "")) < 1
    assert "offset 2 outside" in response.text


async def test_the_path_preview_with_machining_shows_the_tool(client: httpx.AsyncClient) -> None:
    response = await client.post(
        PATHS_PREVIEW,
        json={"path": SQUARE, "tolerance": 0.01, "machining": {"tool_diameter": 4.0}},
    )
    assert response.status_code == 200, response.text
    groups = _groups(response.text)
    assert len(list(groups["contours"])) == 1
    assert len(list(groups["swept"])) == 1
    assert "tool ⌀4" in response.text


# -- refusals ---------------------------------------------------------------------------


async def test_inside_of_an_open_path_names_its_subpath(client: httpx.AsyncClient) -> None:
    response = await client.post(
        PATHS,
        json={
            "path": "M 0 0 L 10 0 L 10 10 M 0 20 L 5 20",
            "tolerance": 0.01,
            "offset": {"distance": 1.0, "side": "inside"},
        },
    )
    problem = problem_of(response, 422)
    assert locs(problem) == [["body", "offset", "side"]]
    assert "path.subpaths[0]" in problem["detail"]
    assert "closed" in problem["detail"]


async def test_inside_of_an_open_contour_in_a_drawing_names_the_toolpath_and_its_element(
    client: httpx.AsyncClient,
) -> None:
    wire = '<polyline id="wire" points="10 10 20 10 20 15"/></svg>'
    document = PLATE.replace("</svg>", wire)
    body = await _ok(
        client,
        DRAWINGS,
        json={**_plate_json(offset={"distance": 1.0, "side": "inside"}), "document": document},
    )
    # The wire has no inside: left out, with a note naming it; the plate and hole are offset.
    ((note,),) = [[n for n in body["offset"]["notes"] if n["kind"] == "open"]]
    found = re.search(r"toolpaths\[(\d+)\] \(drawn by ([^)]*)\)", note["message"])
    assert found is not None, note["message"]
    assert found.group(2) == "polyline#wire"
    assert int(found.group(1)) == note["toolpath"]
    assert note["toolpath"] not in body["offset"]["origin"]
    assert body["offset"]["paths_out"] == 2
    # The toolpath named is the wire's in the answer's order (as it would be cut).
    ok = await _ok(client, DRAWINGS, json={**_plate_json(), "document": document})
    assert ok["toolpaths"][note["toolpath"]]["sources"] == ["polyline#wire"]
    # The wire alone: nothing to offset, refused naming it.
    alone = PLATE.split("<rect")[0] + wire
    response = await client.post(
        DRAWINGS,
        json={**_plate_json(offset={"distance": 1.0, "side": "inside"}), "document": alone},
    )
    problem = problem_of(response, 422)
    assert locs(problem) == [["body", "offset", "side"]]
    assert "toolpaths[0] is open (drawn by polyline#wire)" in problem["detail"]


@pytest.mark.parametrize(
    "tooling",
    [{"offset": {"distance": 1.0, "side": "outside"}}, {"machining": {"tool_diameter": 1.0}}],
)
async def test_a_contour_crossing_itself_has_no_inside_and_is_named(
    client: httpx.AsyncClient, tooling: dict[str, Any]
) -> None:
    bow_tie = "M 0 0 L 10 10 L 10 0 L 0 10 Z"
    response = await client.post(PATHS, json={"path": bow_tie, "tolerance": 0.01, **tooling})
    problem = problem_of(response, 422)
    assert problem["type"] == "urn:arcspline:problem:invalid-input"
    assert locs(problem) == [["body", "path", "subpaths", 0]]
    assert problem["errors"][0]["type"] == "crossing"
    assert "(5, 5)" in problem["detail"]


async def test_controller_compensation_refuses_a_concave_arc_tighter_than_the_tool(
    client: httpx.AsyncClient,
) -> None:
    # A notch of radius 2 in the top edge, cut outside by a tool of radius 3.
    notched = "M 0 0 L 20 0 L 20 20 L 12 20 A 2 2 0 0 0 8 20 L 0 20 Z"
    machining = {"tool_diameter": 6.0, "compensation": "controller"}
    response = await client.post(
        PATHS, json={"path": notched, "tolerance": 0.01, "machining": machining}
    )
    problem = problem_of(response, 422)
    assert locs(problem) == [["body", "path", "subpaths", 0]]
    assert "compensation" in problem["detail"]
    # Computed compensation cuts it: the tool centre simply does not enter the notch.
    computed = {"tool_diameter": 6.0, "lead_radius": 0}
    body = await _ok(
        client, PATHS, json={"path": notched, "tolerance": 0.01, "machining": computed}
    )
    contour = [*oracle.polygon([(0, 0), (20, 0), (20, 20), (12, 20)])[:-1]]
    contour += [oracle.arc((10, 20), 2.0, 0.0, -math.pi), oracle.line((8, 20), (0, 20))]
    contour += [oracle.line((0, 20), (0, 0))]
    (path,) = _segments(body["subpaths"])
    report = oracle.check_offset([contour], [path], 3.0, "outside")
    assert report.ok(3.0, SLACK), report.describe()


async def test_a_tool_larger_than_every_feature_is_refused(client: httpx.AsyncClient) -> None:
    response = await client.post(
        PATHS,
        json={
            "path": "M 0 0 L 4 0 L 4 4 L 0 4 Z",
            "tolerance": 0.01,
            "offset": {"distance": 3.0, "side": "inside"},
        },
    )
    problem = problem_of(response, 422)
    assert problem["type"] == "urn:arcspline:problem:tool-too-large"
    assert locs(problem) == [["body", "offset", "distance"]]


async def test_a_machining_tool_too_large_for_a_hole_names_the_holes_toolpath(
    client: httpx.AsyncClient,
) -> None:
    # The hole (⌀12) is left uncut with a warning naming it; the plate is cut.
    request = _plate_json(machining={"tool_diameter": 14.0, "cut": "inside"})
    body = await _ok(client, DRAWINGS, json=request)
    ((warning,),) = [[w for w in body["machining"]["warnings"] if "left uncut" in w["message"]]]
    assert "(drawn by circle#hole)" in warning["message"]
    assert "does not fit" in warning["message"]
    ok = await _ok(client, DRAWINGS, json=_plate_json())
    assert ok["toolpaths"][warning["toolpath"]]["sources"] == ["circle#hole"]
    assert [c["toolpath"] for c in body["machining"]["contours"]] == [1 - warning["toolpath"]]
    # A tool that fits nothing: refused, naming a contour.
    request = _plate_json(machining={"tool_diameter": 40.0, "cut": "inside"})
    problem = problem_of(await client.post(DRAWINGS, json=request), 422)
    assert problem["type"] == "urn:arcspline:problem:tool-too-large"
    ((where, toolpaths, _index),) = locs(problem)
    assert (where, toolpaths) == ("body", "toolpaths")
    assert "does not fit" in problem["detail"]


async def test_machining_an_open_contour_inside_names_its_toolpath_and_element(
    client: httpx.AsyncClient,
) -> None:
    document = PLATE.replace("</svg>", '<polyline id="wire" points="10 10 20 10 20 15"/></svg>')
    request = {
        **_plate_json(machining={"tool_diameter": 1.0, "cut": "inside"}),
        "document": document,
    }
    problem = problem_of(await client.post(DRAWINGS, json=request), 422)
    ((body, toolpaths, index),) = locs(problem)
    assert (body, toolpaths) == ("body", "toolpaths")
    assert "(drawn by polyline#wire)" in problem["detail"]
    ok = await _ok(client, DRAWINGS, json={**_plate_json(), "document": document})
    assert ok["toolpaths"][index]["sources"] == ["polyline#wire"]


@pytest.mark.parametrize("url", [PATHS, DRAWINGS])
async def test_offset_and_machining_together_are_refused(
    client: httpx.AsyncClient, url: str
) -> None:
    both = {"offset": {"distance": 1.0, "side": "outside"}, "machining": {"tool_diameter": 2.0}}
    request = {"path": SQUARE, "tolerance": 0.01, **both} if url == PATHS else _plate_json(**both)
    problem = problem_of(await client.post(url, json=request), 422)
    assert problem["type"] == "urn:arcspline:problem:validation"
    assert locs(problem) == [["body"]]
    assert "offset" in problem["errors"][0]["msg"]
    assert "machining" in problem["errors"][0]["msg"]


@pytest.mark.parametrize("url", [PATHS, DRAWINGS])
async def test_a_machining_program_needs_safe_z_and_cut_z(
    client: httpx.AsyncClient, url: str
) -> None:
    more = {"machining": {"tool_diameter": 2.0}, "gcode": {"feed_rate": 600}, "output": "gcode"}
    request = {"path": SQUARE, "tolerance": 0.01, **more} if url == PATHS else _plate_json(**more)
    problem = problem_of(await client.post(url, json=request), 422)
    assert locs(problem) == [["body", "gcode", "safe_z"], ["body", "gcode", "cut_z"]]
    # Only the one missing is named; JSON with a program asks for it too.
    request["gcode"] = {"feed_rate": 600, "safe_z": 5}
    del request["output"]
    problem = problem_of(await client.post(url, json=request), 422)
    assert locs(problem) == [["body", "gcode", "cut_z"]]


async def test_a_raw_documents_machining_program_needs_safe_z_too(
    client: httpx.AsyncClient,
) -> None:
    response = await client.post(
        DRAWINGS,
        content=PLATE.encode(),
        headers={"Content-Type": "image/svg+xml", "Accept": "text/x-gcode"},
        params={"tolerance": "0.01", "tool_diameter": "2", "feed_rate": "600", "cut_z": "-1"},
    )
    assert locs(problem_of(response, 422)) == [["body", "gcode", "safe_z"]]


@pytest.mark.parametrize(
    ("field", "value", "loc"),
    [
        ("offset", {"distance": 0.0, "side": "left"}, ["offset", "distance"]),
        ("offset", {"distance": 1.0, "side": "up"}, ["offset", "side"]),
        ("offset", {"distance": 1.0}, ["offset", "side"]),
        ("offset", {"distance": 1.0, "side": "left", "join": "bevel"}, ["offset", "join"]),
        (
            "offset",
            {"distance": 1.0, "side": "left", "mitre_limit": 0.5},
            ["offset", "mitre_limit"],
        ),
        ("offset", {"distance": 1e200, "side": "left"}, ["offset", "distance"]),
        ("machining", {"tool_diameter": -1.0}, ["machining", "tool_diameter"]),
        ("machining", {"tool_diameter": 1e6}, ["machining", "tool_diameter"]),
        ("machining", {"tool_diameter": 1.0, "lead_radius": 1e300}, ["machining", "lead_radius"]),
        ("machining", {"tool_diameter": 1.0, "cut": "through"}, ["machining", "cut"]),
        ("machining", {"tool_diameter": 1.0, "lead_radius": -0.5}, ["machining", "lead_radius"]),
        ("machining", {"tool_diameter": 1.0, "entry": "drop"}, ["machining", "entry"]),
        (
            "machining",
            {"tool_diameter": 1.0, "tabs": {"count": 0, "width": 1.0, "height": 1.0}},
            ["machining", "tabs", "count"],
        ),
        (
            "machining",
            {"tool_diameter": 1.0, "tabs": {"count": 65, "width": 1.0, "height": 1.0}},
            ["machining", "tabs", "count"],
        ),
        (
            "machining",
            {"tool_diameter": 1.0, "tabs": {"count": 2, "width": 0.0, "height": 1.0}},
            ["machining", "tabs", "width"],
        ),
        (
            "machining",
            {"tool_diameter": 1.0, "tabs": {"count": 2, "width": 1.0, "height": -1.0}},
            ["machining", "tabs", "height"],
        ),
        ("machining", {"tool_diameter": 1.0, "tool_number": 100000}, ["machining", "tool_number"]),
        ("machining", {"tool_diameter": 1.0, "tool_number": 0}, ["machining", "tool_number"]),
        ("machining", {"tool_diameter": 1.0, "spindle": "ccw"}, ["machining", "spindle"]),
    ],
)
async def test_each_option_out_of_its_range_is_named(
    client: httpx.AsyncClient, field: str, value: dict[str, Any], loc: list[str]
) -> None:
    request = {"path": SQUARE, "tolerance": 0.01, field: value}
    problem = problem_of(await client.post(PATHS, json=request), 422)
    assert problem["type"] == "urn:arcspline:problem:validation"
    assert locs(problem) == [["body", *loc]]


def test_the_longest_length_is_the_machining_packages() -> None:
    # One bound for a request's lengths and the core's check of them.
    assert MAX_LENGTH == machining_options.MAX_LENGTH


@pytest.mark.parametrize(
    ("params", "names"),
    [
        ({"offset": "-1", "side": "left"}, ["offset"]),
        ({"offset": "1", "side": "up"}, ["side"]),
        ({"side": "left"}, ["offset"]),
        ({"tool_diameter": "3", "tabs": "2", "tab_width": "1"}, ["tab_height"]),
        ({"tool_diameter": "3", "tool_number": "x"}, ["tool_number"]),
    ],
)
async def test_a_raw_documents_tool_parameters_are_named_as_given(
    client: httpx.AsyncClient, params: dict[str, str], names: list[str]
) -> None:
    response = await client.post(
        DRAWINGS,
        content=PLATE.encode(),
        headers={"Content-Type": "image/svg+xml"},
        params={"tolerance": "0.01", **params},
    )
    assert locs(problem_of(response, 422)) == [["query", name] for name in names]
