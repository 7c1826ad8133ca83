"""POST /v1/paths/approximate, /v1/paths/batch and /v1/paths/preview in process: SVG path
data and the JSON form, each output segment's source, the statistics, the geometry by the
independent path oracle, one G-code program per path, the preview, and every refusal as
problem details (never a 500, never a NaN)."""

from __future__ import annotations

import itertools
import json
import math
import re
import xml.etree.ElementTree as ET
from collections.abc import AsyncIterator
from typing import Any

import httpx
import pytest
from fastapi import FastAPI

from arcspline.api.path_schemas import PathBatchResponse, PathResponse
from arcspline.geometry.curves.segments import Path
from arcspline.paths import parse_path_data
from arcspline.paths.specs import (
    ArcAbout,
    CubicTo,
    EllipticalArcTo,
    LineTo,
    PathFromSegments,
    QuadraticTo,
    SegmentForm,
    SubpathForm,
)
from tests.support import gcode_reader, path_oracle

from .conftest import locs, problem_of, running_app
from .spline_json import same_json

pytestmark = pytest.mark.anyio

URL = "/v1/paths/approximate"
BATCH = "/v1/paths/batch"
PREVIEW = "/v1/paths/preview"
STRATEGIES = ["subdivide", "fewest-arcs"]
SVG = "{http://www.w3.org/2000/svg}"

#: Two subpaths: a cubic, a line, a half circle (rx == ry) and the closing line of ``Z``;
#: then an elliptical arc (rotated 30°) and a line, left open.
MIXED = "M 0 0 C 10 0 20 10 30 30 L 40 30 A 5 5 0 0 1 50 30 Z M 60 0 A 8 4 30 0 1 80 10 L 90 0"
#: The same path in the JSON form (the half circle as an arc about its centre).
MIXED_JSON: dict[str, Any] = {
    "subpaths": [
        {
            "start": [0, 0],
            "segments": [
                {"type": "cubic", "control1": [10, 0], "control2": [20, 10], "to": [30, 30]},
                {"type": "line", "to": [40, 30]},
                {"type": "arc", "center": [45, 30], "sweep_deg": 180},
            ],
            "closed": True,
        },
        {
            "start": [60, 0],
            "segments": [
                {
                    "type": "elliptical_arc",
                    "radii": [8, 4],
                    "rotation_deg": 30,
                    "large_arc": False,
                    "anticlockwise": True,
                    "to": [80, 10],
                },
                {"type": "line", "to": [90, 0]},
            ],
        },
    ]
}
#: Input segments per subpath of MIXED (Z adds the closing line).
MIXED_SIZES = [4, 2]
#: Paths without elliptical arcs or circular arcs of more than 180°, for the oracle: a cubic,
#: lines, a half circle, quadratics with a reflected control point (T).
PLAIN = "M 0 0 C 10 0 20 10 30 30 L 40 30 A 5 5 0 0 1 50 30 Z M 60 0 Q 70 20 80 0 T 100 0"
PLAIN_JSON: dict[str, Any] = {
    "subpaths": [
        {
            "start": [0, 0],
            "segments": [
                {"type": "quadratic", "control": [5, 10], "to": [10, 0]},
                {"type": "arc", "center": [15, 0], "sweep_deg": -120},
                {"type": "line", "to": [25, 10]},
            ],
            "closed": True,
        },
        {
            "start": [40, 0],
            "segments": [
                {"type": "cubic", "control1": [40, 10], "control2": [55, 10], "to": [60, -5]}
            ],
        },
    ]
}


@pytest.fixture(scope="module")
async def limited() -> AsyncIterator[tuple[FastAPI, httpx.AsyncClient]]:
    """An app with small path limits: 10 output segments, 3 input segments, 3 jobs a batch."""
    async with running_app(
        path_max_segments=10, path_max_input_segments=3, batch_max_jobs=3
    ) as pair:
        yield pair


# -- helpers -----------------------------------------------------------------------------


def _refuse_constant(token: str) -> Any:
    raise AssertionError(f"the response holds {token}, which is not JSON")


def _finite_numbers(value: Any, where: str = "") -> None:
    """Every number in a JSON value is finite (a NaN read back as a float fails too)."""
    if isinstance(value, dict):
        for key, item in value.items():
            _finite_numbers(item, f"{where}.{key}")
    elif isinstance(value, list):
        for i, item in enumerate(value):
            _finite_numbers(item, f"{where}[{i}]")
    elif isinstance(value, float):
        assert math.isfinite(value), where


def strict_json(response: httpx.Response) -> Any:
    """The body as strict JSON: no NaN or Infinity tokens, every number finite."""
    body = json.loads(response.text, parse_constant=_refuse_constant)
    _finite_numbers(body)
    return body


async def approximate(client: httpx.AsyncClient, body: dict[str, Any]) -> dict[str, Any]:
    response = await client.post(URL, json=body)
    assert response.status_code == 200, response.text
    assert response.headers["content-type"] == "application/json"
    result: dict[str, Any] = strict_json(response)
    PathResponse.model_validate(result)
    return result


def source_of(path: str | dict[str, Any]) -> Path:
    """The source path as the parser builds it (SVG data, or the JSON form by its specs)."""
    if isinstance(path, str):
        return parse_path_data(path)
    return PathFromSegments(
        tuple(
            SubpathForm(
                _xy(sub["start"]),
                tuple(_form(s) for s in sub["segments"]),
                sub.get("closed", False),
            )
            for sub in path["subpaths"]
        )
    ).build()


def _xy(v: list[float]) -> tuple[float, float]:
    return (float(v[0]), float(v[1]))


def _form(s: dict[str, Any]) -> SegmentForm:
    kind = s["type"]
    if kind == "line":
        return LineTo(_xy(s["to"]))
    if kind == "quadratic":
        return QuadraticTo(_xy(s["control"]), _xy(s["to"]))
    if kind == "cubic":
        return CubicTo(_xy(s["control1"]), _xy(s["control2"]), _xy(s["to"]))
    if kind == "arc":
        return ArcAbout(_xy(s["center"]), float(s["sweep_deg"]))
    return EllipticalArcTo(
        _xy(s["radii"]),
        float(s.get("rotation_deg", 0.0)),
        s.get("large_arc", False),
        s.get("anticlockwise", True),
        _xy(s["to"]),
    )


def check_stats(body: dict[str, Any], tolerance: float, strategy: str) -> None:
    """The statistics of each subpath and of the whole path, from the segments themselves."""
    every: list[dict[str, Any]] = []
    worst_subpath = max(
        range(len(body["subpaths"])), key=lambda i: body["subpaths"][i]["stats"]["max_deviation"]
    )
    for sub in body["subpaths"]:
        segments, stats = sub["segments"], sub["stats"]
        _check_group(segments, stats, tolerance, strategy)
        k = max(range(len(segments)), key=lambda n: segments[n]["max_deviation"])
        assert stats["max_deviation_segment"] == segments[k]["source_segment"]
        assert stats["t_at_max_deviation"] == segments[k]["u_at_max_deviation"]
        assert stats["curve_length"] == pytest.approx(stats["spline_length"], rel=1e-3)
        every += segments
    overall = body["stats"]
    _check_group(every, overall, tolerance, strategy)
    assert overall["subpath_count"] == len(body["subpaths"])
    assert overall["max_deviation_subpath"] == worst_subpath
    worst = body["subpaths"][worst_subpath]["stats"]
    assert overall["max_deviation_segment"] == worst["max_deviation_segment"]
    assert overall["t_at_max_deviation"] == worst["t_at_max_deviation"]
    assert overall["curve_length"] == pytest.approx(
        sum(s["stats"]["curve_length"] for s in body["subpaths"]), rel=1e-12
    )
    for name in ("arc_count", "line_count", "segment_count"):
        assert overall[name] == sum(s["stats"][name] for s in body["subpaths"]), name


def _check_group(
    segments: list[dict[str, Any]], stats: dict[str, Any], tolerance: float, strategy: str
) -> None:
    arcs = [s for s in segments if s["type"] == "arc"]
    assert stats["arc_count"] == len(arcs)
    assert stats["line_count"] == len(segments) - len(arcs)
    assert stats["segment_count"] == len(segments) == stats["arc_count"] + stats["line_count"]
    deviations = [s["max_deviation"] for s in segments]
    assert stats["max_deviation"] == max(deviations)
    assert 0.0 <= stats["max_deviation"] <= tolerance
    assert stats["deviation_ratio"] == pytest.approx(stats["max_deviation"] / tolerance, rel=1e-12)
    assert stats["deviation_ratio"] <= 1.0
    assert stats["mean_segment_deviation"] == pytest.approx(
        sum(deviations) / len(deviations), rel=1e-9
    )
    assert stats["spline_length"] == pytest.approx(sum(s["length"] for s in segments), rel=1e-9)
    radii = [s["radius"] for s in arcs]
    assert stats["min_radius"] == (min(radii) if radii else None)
    assert stats["max_radius"] == (max(radii) if radii else None)
    assert stats["tolerance"] == tolerance
    assert stats["strategy"] == strategy


def check_sources(body: dict[str, Any], sizes: list[int]) -> None:
    """Per subpath: ``source_segment`` runs through every input segment in order, and each
    input segment's ``u`` ranges start at 0, join end to end and finish at 1 (to rounding:
    exactness is :func:`test_u_ranges_tile_each_input_segment_exactly`'s)."""
    assert len(body["subpaths"]) == len(sizes)
    for sub, size in zip(body["subpaths"], sizes, strict=True):
        segments = sub["segments"]
        sources = [s["source_segment"] for s in segments]
        assert all(isinstance(j, int) for j in sources)
        assert sources == sorted(sources)
        assert set(sources) == set(range(size))
        for j in range(size):
            mine = [s for s in segments if s["source_segment"] == j]
            assert mine[0]["u_start"] == 0.0
            assert mine[-1]["u_end"] == pytest.approx(1.0, abs=1e-12)
            for a, b in itertools.pairwise(mine):
                assert a["u_end"] == b["u_start"]
            for s in mine:
                assert s["u_start"] < s["u_end"]
                assert s["u_start"] <= s["u_at_max_deviation"] <= s["u_end"]
        # The chain is continuous.
        for a, b in itertools.pairwise(segments):
            assert math.dist(a["end"], b["start"]) <= 1e-9


# -- results -------------------------------------------------------------------------------


@pytest.mark.parametrize("strategy", STRATEGIES)
async def test_svg_data_gives_each_subpath_its_segments_sources_and_statistics(
    client: httpx.AsyncClient, strategy: str
) -> None:
    body = await approximate(client, {"path": MIXED, "tolerance": 0.05, "strategy": strategy})
    assert [sub["closed"] for sub in body["subpaths"]] == [True, False]
    check_sources(body, MIXED_SIZES)
    check_stats(body, 0.05, strategy)
    assert body["gcode"] is None
    # Each input line (the L and the closing line of Z, the last L) is one output line.
    first, second = body["subpaths"]
    assert [s["type"] for s in first["segments"] if s["source_segment"] in (1, 3)] == ["line"] * 2
    assert [s["type"] for s in second["segments"] if s["source_segment"] == 1] == ["line"]
    # The cubic and the ellipse need several arcs at 0.05.
    assert sum(s["source_segment"] == 0 for s in first["segments"]) > 2
    assert sum(s["source_segment"] == 0 for s in second["segments"]) > 2


async def test_fewest_arcs_needs_no_more_segments_than_subdivide(
    client: httpx.AsyncClient,
) -> None:
    counts = {}
    for strategy in STRATEGIES:
        body = await approximate(client, {"path": MIXED, "tolerance": 0.05, "strategy": strategy})
        counts[strategy] = [sub["stats"]["segment_count"] for sub in body["subpaths"]]
    assert all(f <= s for f, s in zip(counts["fewest-arcs"], counts["subdivide"], strict=True))
    assert counts["fewest-arcs"] != counts["subdivide"]


@pytest.mark.parametrize("strategy", STRATEGIES)
async def test_the_json_form_gives_what_the_same_svg_data_gives(
    client: httpx.AsyncClient, strategy: str
) -> None:
    by_data = await approximate(client, {"path": MIXED, "tolerance": 0.05, "strategy": strategy})
    by_json = await approximate(
        client, {"path": MIXED_JSON, "tolerance": 0.05, "strategy": strategy}
    )
    check_sources(by_json, MIXED_SIZES)
    check_stats(by_json, 0.05, strategy)
    assert [s["closed"] for s in by_json["subpaths"]] == [True, False]
    # The arc about (45, 30) ends at (50, 30) up to the rounding of sin(2π): not bit for bit.
    assert _close(by_json, by_data)


def _close(a: Any, b: Any) -> bool:
    """Equal JSON values, numbers to 1e-9 (relative or absolute)."""
    if isinstance(a, dict) and isinstance(b, dict):
        return a.keys() == b.keys() and all(_close(a[k], b[k]) for k in a)
    if isinstance(a, list) and isinstance(b, list):
        return len(a) == len(b) and all(_close(x, y) for x, y in zip(a, b, strict=True))
    if isinstance(a, float) or isinstance(b, float):
        return math.isclose(a, b, rel_tol=1e-9, abs_tol=1e-9)
    return bool(a == b)


@pytest.mark.parametrize("strategy", STRATEGIES)
@pytest.mark.parametrize(
    ("path", "tolerance"),
    [(PLAIN, 0.05), (PLAIN_JSON, 0.1)],
    ids=["svg-data", "json-form"],
)
async def test_the_oracle_finds_every_subpath_within_tolerance(
    client: httpx.AsyncClient, path: str | dict[str, Any], tolerance: float, strategy: str
) -> None:
    body = await approximate(client, {"path": path, "tolerance": tolerance, "strategy": strategy})
    assert len(body["subpaths"]) == 2
    verdict = path_oracle.check_path(
        source_of(path), [sub["segments"] for sub in body["subpaths"]], tolerance
    )
    assert verdict.ok, verdict.describe()
    for sub, measured in zip(body["subpaths"], verdict.subpath_max, strict=True):
        assert measured <= sub["stats"]["max_deviation"] * (1 + 1e-6) + 1e-12


async def test_the_oracle_finds_a_path_with_an_elliptical_arc_within_tolerance(
    client: httpx.AsyncClient,
) -> None:
    body = await approximate(client, {"path": MIXED, "tolerance": 0.05})
    verdict = path_oracle.check_path(
        parse_path_data(MIXED), [sub["segments"] for sub in body["subpaths"]], 0.05
    )
    assert verdict.ok, verdict.describe()


@pytest.mark.parametrize(
    "path",
    [
        "M 0 0 C 10 0 20 10 30 30 Q 40 40 50 30 L 60 0",
        "M 0 0 A 4 2 30 0 1 4 0",
        "M 0 0 A 10 10 0 1 1 5 5",
    ],
    ids=["cubic-quadratic-line", "elliptical-arc", "large-circular-arc"],
)
async def test_u_ranges_tile_each_input_segment_exactly(
    client: httpx.AsyncClient, path: str
) -> None:
    # u is "that segment's own parameter t": each input segment's outputs cover [0, 1]
    # exactly, end to end, and never leave it.
    body = await approximate(client, {"path": path, "tolerance": 0.01})
    for sub in body["subpaths"]:
        segments = sub["segments"]
        for j in {s["source_segment"] for s in segments}:
            mine = [s for s in segments if s["source_segment"] == j]
            assert [mine[0]["u_start"], mine[-1]["u_end"]] == [0.0, 1.0], (j, mine[-1]["u_end"])
            assert all(0.0 <= s["u_start"] < s["u_end"] <= 1.0 for s in mine)
            assert all(a["u_end"] == b["u_start"] for a, b in itertools.pairwise(mine))


@pytest.mark.parametrize("strategy", STRATEGIES)
async def test_an_input_line_stays_exactly_one_line(
    client: httpx.AsyncClient, strategy: str
) -> None:
    # L, H, V and relative l between curves: each its own output line, with its own ends.
    path = "M 1 2 L 11 2 C 15 2 18 5 18 9 V 20 h -7.5 Q 0 20 0 10 l 1 -8"
    corners = [(1, 2), (11, 2), (18, 9), (18, 20), (10.5, 20), (0, 10), (1, 2)]
    body = await approximate(client, {"path": path, "tolerance": 0.05, "strategy": strategy})
    (sub,) = body["subpaths"]
    for j in (0, 2, 3, 5):
        (line,) = [s for s in sub["segments"] if s["source_segment"] == j]
        assert line["type"] == "line"
        assert line["start"] == list(map(float, corners[j]))
        assert line["end"] == pytest.approx(list(corners[j + 1]), abs=1e-12)
        assert (line["u_start"], line["u_end"]) == (0.0, 1.0)
        assert line["max_deviation"] == pytest.approx(0.0, abs=1e-12)
        assert line["length"] == pytest.approx(math.dist(corners[j], corners[j + 1]))
    assert sub["segments"][-1]["end"] == pytest.approx([1.0, 2.0], abs=1e-12)


def _one_arc(sub: dict[str, Any], j: int) -> dict[str, Any]:
    mine = [s for s in sub["segments"] if s["source_segment"] == j]
    assert len(mine) == 1, [s["type"] for s in mine]
    assert mine[0]["type"] == "arc"
    assert mine[0]["max_deviation"] <= 1e-9
    arc: dict[str, Any] = mine[0]
    return arc


@pytest.mark.parametrize("strategy", STRATEGIES)
async def test_an_input_circular_arc_stays_exactly_one_arc(
    client: httpx.AsyncClient, strategy: str
) -> None:
    # SVG arcs with rx == ry: a half circle, a large arc of radius 10 (ccw), a small one cw.
    data = "M 40 30 A 5 5 0 0 1 50 30 L 60 30 A 10 10 0 1 1 70 40 A 10 10 0 0 0 80 30"
    body = await approximate(client, {"path": data, "tolerance": 0.01, "strategy": strategy})
    (sub,) = body["subpaths"]
    half = _one_arc(sub, 0)
    assert half["center"] == pytest.approx([45.0, 30.0], abs=1e-12)
    assert half["radius"] == pytest.approx(5.0, rel=1e-12)
    assert half["sweep_rad"] == pytest.approx(math.pi, rel=1e-12)
    assert (half["start"], half["end"], half["direction"]) == ([40.0, 30.0], [50.0, 30.0], "ccw")
    large = _one_arc(sub, 2)
    assert large["radius"] == pytest.approx(10.0, rel=1e-12)
    assert large["direction"] == "ccw"
    assert math.pi < large["sweep_rad"] < 2 * math.pi
    # The centre: 10 from both ends, and on the side that makes the arc large.
    for end in ((60.0, 30.0), (70.0, 40.0)):
        assert math.dist(large["center"], end) == pytest.approx(10.0, rel=1e-12)
    assert large["center"] == pytest.approx([70.0, 30.0], abs=1e-9)
    small = _one_arc(sub, 3)
    assert small["direction"] == "cw"
    assert small["radius"] == pytest.approx(10.0, rel=1e-12)
    assert -math.pi < small["sweep_rad"] < 0
    assert small["end"] == [80.0, 30.0]


@pytest.mark.parametrize("strategy", STRATEGIES)
async def test_a_json_arc_about_a_centre_stays_exactly_one_arc(
    client: httpx.AsyncClient, strategy: str
) -> None:
    path = {
        "subpaths": [
            {
                "start": [3, 4],
                "segments": [
                    {"type": "arc", "center": [0, 0], "sweep_deg": 270},
                    {"type": "line", "to": [10, 0]},
                    {"type": "arc", "center": [10, 5], "sweep_deg": -120},
                ],
            }
        ]
    }
    body = await approximate(client, {"path": path, "tolerance": 0.01, "strategy": strategy})
    (sub,) = body["subpaths"]
    first = _one_arc(sub, 0)
    assert first["center"] == [0.0, 0.0]
    assert first["radius"] == 5.0
    assert first["start"] == [3.0, 4.0]
    assert first["sweep_rad"] == pytest.approx(math.radians(270), rel=1e-12)
    assert first["start_angle_rad"] == pytest.approx(math.atan2(4, 3), rel=1e-12)
    assert first["direction"] == "ccw"
    a = math.atan2(4, 3) + math.radians(270)
    assert first["end"] == pytest.approx([5 * math.cos(a), 5 * math.sin(a)], abs=1e-12)
    assert first["length"] == pytest.approx(5 * math.radians(270), rel=1e-12)
    third = _one_arc(sub, 2)
    assert third["center"] == [10.0, 5.0]
    assert third["radius"] == pytest.approx(5.0, rel=1e-15)
    assert third["start"] == [10.0, 0.0]
    assert third["sweep_rad"] == pytest.approx(math.radians(-120), rel=1e-12)
    assert third["direction"] == "cw"


@pytest.mark.parametrize(
    ("path", "sizes"),
    [
        # Z with a closing line; Z where the data already returned to the start (a circle of
        # two arcs); and the JSON form's closed flag.
        ("M 0 0 L 10 0 Q 10 10 0 10 Z", [3]),
        ("M 0 0 A 5 5 0 0 1 10 0 A 5 5 0 0 1 0 0 Z M 20 0 L 30 0 L 30 5 z", [2, 3]),
        (
            {
                "subpaths": [
                    {
                        "start": [1, 1],
                        "segments": [
                            {"type": "cubic", "control1": [5, 1], "control2": [9, 4], "to": [9, 9]}
                        ],
                        "closed": True,
                    },
                    {
                        "start": [20, 0],
                        "segments": [{"type": "arc", "center": [25, 0], "sweep_deg": -180}],
                        "closed": True,
                    },
                ]
            },
            [2, 2],
        ),
    ],
    ids=["z-adds-a-line", "z-at-the-start", "json-closed"],
)
async def test_closed_subpaths_end_exactly_at_their_start(
    client: httpx.AsyncClient, path: str | dict[str, Any], sizes: list[int]
) -> None:
    body = await approximate(client, {"path": path, "tolerance": 0.05})
    check_sources(body, sizes)
    for sub in body["subpaths"]:
        assert sub["closed"] is True
        assert sub["segments"][-1]["end"] == sub["segments"][0]["start"]


async def test_an_open_subpath_is_not_closed_even_when_it_returns(
    client: httpx.AsyncClient,
) -> None:
    body = await approximate(client, {"path": "M 0 0 L 5 0 L 5 5 L 0 0", "tolerance": 0.1})
    (sub,) = body["subpaths"]
    assert sub["closed"] is False
    assert len(sub["segments"]) == 3


# -- G-code ----------------------------------------------------------------------------


@pytest.mark.parametrize(
    "options",
    [
        {"feed_rate": 600},
        {"feed_rate": 600, "safe_z": 5, "cut_z": -1.25, "plunge_feed_rate": 100},
        {"feed_rate": 20, "units": "inch", "safe_z": 0.2, "cut_z": -0.05, "decimals": 5},
    ],
    ids=["plain", "z", "inch-z"],
)
async def test_the_gcode_is_one_program_for_the_whole_path(
    client: httpx.AsyncClient, options: dict[str, Any]
) -> None:
    body = await approximate(client, {"path": MIXED, "tolerance": 0.05, "gcode": options})
    text = body["gcode"]
    assert isinstance(text, str)
    program = gcode_reader.read(text)
    decimals = options.get("decimals", 4)
    half = 0.5 * 10.0**-decimals * (1 + 1e-9)
    assert [b.m for b in program.blocks if b.m] == [(2,)]
    assert program.blocks[-1].m == (2,)
    assert program.preamble_modes["units"] == (20 if options.get("units") == "inch" else 21)
    z = "safe_z" in options
    rapids_xy = [m for m in program.moves if m.motion == 0 and m.block.has("X", "Y")]
    assert len(rapids_xy) == len(body["subpaths"])
    assert text.count("G0 X") == len(body["subpaths"])
    # Split the moves at the XY rapids: one group per subpath.
    groups: list[list[gcode_reader.Move]] = []
    for move in program.moves:
        if move in rapids_xy:
            groups.append([])
        if groups:
            groups[-1].append(move)
    for sub, group in zip(body["subpaths"], groups, strict=True):
        rapid, *rest = group
        assert rapid.xy_end == pytest.approx(sub["segments"][0]["start"], abs=half)
        cuts = [m for m in rest if m.is_cut]
        assert len(cuts) == len(sub["segments"])
        assert cuts[0].xy_start == rapid.xy_end
        for move, segment in zip(cuts, sub["segments"], strict=True):
            assert move.xy_end == pytest.approx(segment["end"], abs=half), move.block.text
            if segment["type"] == "arc" and move.motion != 1:
                assert move.motion == (3 if segment["direction"] == "ccw" else 2)
        if sub["closed"]:
            assert cuts[-1].xy_end == cuts[0].xy_start
        if z:
            # Retracted before the rapid, plunged after it, cut at cut_z throughout.
            assert rapid.start[2] == options["safe_z"]
            plunge = rest[0]
            assert plunge.motion == 1
            assert plunge.xy_start == plunge.xy_end
            assert plunge.end[2] == options["cut_z"]
            assert all(m.end[2] == options["cut_z"] for m in cuts)
    if z:
        retracts = [m for m in program.moves if m.motion == 0 and not m.block.has("X")]
        assert len(retracts) == len(body["subpaths"]) + 1
        assert all(m.end[2] == options["safe_z"] for m in retracts)
        assert program.moves[-1] == retracts[-1]
    else:
        assert all(m.end[2] == 0.0 for m in program.moves)
        assert "Z" not in text


async def test_gcode_option_errors_name_the_gcode_field(client: httpx.AsyncClient) -> None:
    body = {"path": MIXED, "tolerance": 0.05, "gcode": {"feed_rate": 100, "safe_z": 5}}
    problem = problem_of(await client.post(URL, json=body), 422)
    assert problem["type"].endswith(":gcode")
    assert locs(problem) == [["body", "gcode", "cut_z"]]


# -- preview ---------------------------------------------------------------------------


async def test_the_preview_draws_every_subpath_and_its_arcs(client: httpx.AsyncClient) -> None:
    request = {"path": MIXED, "tolerance": 0.05, "strategy": "fewest-arcs"}
    body = await approximate(client, request)
    # G-code options are ignored by the preview.
    response = await client.post(PREVIEW, json={**request, "gcode": {"feed_rate": 100}})
    assert response.status_code == 200, response.text
    assert response.headers["content-type"].startswith("image/svg+xml")
    root = ET.fromstring(response.text)
    assert root.tag == f"{SVG}svg"
    curves = [p for p in root.iter(f"{SVG}polyline") if p.get("stroke") == "black"]
    assert len(curves) == len(body["subpaths"]) == 2
    segments = [s for sub in body["subpaths"] for s in sub["segments"]]
    arcs = [s for s in segments if s["type"] == "arc"]
    assert len(list(root.iter(f"{SVG}circle"))) == len(arcs)
    drawn = [p for p in root.iter(f"{SVG}path") if p.get("stroke-width") == "3.00"]
    assert len(drawn) == len(segments)
    # Each subpath's curve starts where its first drawn segment starts.
    firsts = [0, len(body["subpaths"][0]["segments"])]
    for curve, k in zip(curves, firsts, strict=True):
        start = (curve.get("points") or "").split()[0]
        assert (drawn[k].get("d") or "").startswith(f"M{start} ")
    legend = " ".join(t.text or "" for t in root.iter(f"{SVG}text"))
    assert f"{len(arcs)} arcs, {len(segments) - len(arcs)} lines (fewest-arcs)" in legend
    assert not re.search(r"nan|inf", response.text, re.IGNORECASE)


async def test_preview_errors_are_problems(client: httpx.AsyncClient) -> None:
    problem = problem_of(await client.post(PREVIEW, json={"path": "M 0 0 L", "tolerance": 1}), 422)
    assert locs(problem) == [["body", "path"]]
    assert "at character 7" in problem["errors"][0]["msg"]


# -- batch -----------------------------------------------------------------------------


async def test_a_batch_answers_every_path_in_order_and_isolates_bad_ones(
    client: httpx.AsyncClient,
) -> None:
    degenerate = {
        "subpaths": [
            {"start": [0, 0], "segments": [{"type": "line", "to": [1, 0]}]},
            {
                "start": [5, 5],
                "segments": [
                    {"type": "line", "to": [6, 5]},
                    {"type": "arc", "center": [6, 5], "sweep_deg": 90},
                ],
            },
        ]
    }
    jobs: list[Any] = [
        {"path": MIXED, "tolerance": 0.05},
        {"path": "M 0 0 L 1 1 K", "tolerance": 0.05},
        {"path": PLAIN_JSON, "tolerance": 0.1, "strategy": "fewest-arcs"},
        "not an object",
        {"path": PLAIN, "tolerance": 1e-14},
        {"path": PLAIN, "tolerance": 0.1, "tolerence": 1},
        {"path": degenerate, "tolerance": 0.1},
        {"path": PLAIN, "tolerance": 0.1, "gcode": {"feed_rate": 100}},
    ]
    response = await client.post(BATCH, json={"jobs": jobs})
    assert response.status_code == 200, response.text
    body = strict_json(response)
    PathBatchResponse.model_validate(body)
    results = body["results"]
    assert [r["status"] for r in results] == [
        "ok",
        "error",
        "ok",
        "error",
        "error",
        "error",
        "error",
        "ok",
    ]
    for i in (0, 2, 7):
        single = await approximate(client, jobs[i])
        assert same_json(results[i]["result"], single), i
    assert isinstance(results[7]["result"]["gcode"], str)
    errors = {i: results[i]["error"] for i in (1, 3, 4, 5, 6)}
    assert all(e["status"] == 422 for e in errors.values())
    assert locs(errors[1]) == [["body", "jobs", 1, "path"]]
    assert "at character 12" in errors[1]["errors"][0]["msg"]
    assert locs(errors[3]) == [["body", "jobs", 3]]
    assert errors[4]["type"].endswith(":tolerance-floor")
    assert locs(errors[4]) == [["body", "jobs", 4, "tolerance"]]
    assert ["body", "jobs", 5, "tolerence"] in locs(errors[5])
    assert locs(errors[6]) == [["body", "jobs", 6, "path", "subpaths", 1, "segments", 1]]


async def test_a_batch_over_its_job_limit_is_a_413(
    limited: tuple[FastAPI, httpx.AsyncClient],
) -> None:
    _, client = limited
    job = {"path": "M 0 0 L 1 1", "tolerance": 0.1}
    problem = problem_of(await client.post(BATCH, json={"jobs": [job] * 4}), 413)
    assert problem["type"].endswith(":too-many-jobs")
    assert problem["limit"] == 3
    response = await client.post(BATCH, json={"jobs": [job] * 3})
    assert [r["status"] for r in strict_json(response)["results"]] == ["ok"] * 3


# -- refusals --------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("data", "offset"),
    [
        ("M 0 0 L 1 X", 10),
        ("L 1 1", 0),
        ("M 0 0 Z 5", 8),
        ("M 0 0 L 1,,2", 10),
        ("M 0 0 C 1 1 2 2", 15),
        ("M 0 0 A 1 1 0 2 0 3 3", 14),
        ("M 0 0 L 1e999 1", 8),
    ],
    ids=["letter", "no-moveto", "number-after-z", "two-commas", "short-cubic", "bad-flag", "inf"],
)
async def test_malformed_path_data_names_the_path_and_the_character(
    client: httpx.AsyncClient, data: str, offset: int
) -> None:
    problem = problem_of(await client.post(URL, json={"path": data, "tolerance": 0.1}), 422)
    assert problem["type"].endswith(":invalid-input")
    assert problem["errors"][0]["loc"] == ["body", "path"]
    assert re.match(rf"at character {offset}\b", problem["errors"][0]["msg"])


@pytest.mark.parametrize(
    ("path", "loc"),
    [
        (
            {
                "subpaths": [
                    {
                        "start": [1, 2],
                        "segments": [{"type": "arc", "center": [1, 2], "sweep_deg": 90}],
                    }
                ]
            },
            ["subpaths", 0, "segments", 0],
        ),
        (
            {
                "subpaths": [
                    {"start": [0, 0], "segments": [{"type": "line", "to": [1, 0]}]},
                    {
                        "start": [0, 5],
                        "segments": [
                            {"type": "line", "to": [3, 5]},
                            {"type": "line", "to": [4, 5]},
                            {"type": "arc", "center": [4, 5], "sweep_deg": -30},
                        ],
                    },
                ]
            },
            ["subpaths", 1, "segments", 2],
        ),
        (
            {
                "subpaths": [
                    {"start": [0, 0], "segments": [{"type": "line", "to": [1, 0]}]},
                    {"start": [2, 2], "segments": [{"type": "line", "to": [2, 2]}]},
                ]
            },
            ["subpaths", 1],
        ),
    ],
    ids=["arc-centred-on-its-start", "in-the-second-subpath", "subpath-without-length"],
)
async def test_a_degenerate_json_segment_is_named(
    client: httpx.AsyncClient, path: dict[str, Any], loc: list[str | int]
) -> None:
    problem = problem_of(await client.post(URL, json={"path": path, "tolerance": 0.1}), 422)
    assert problem["type"].endswith(":invalid-input")
    assert problem["errors"][0]["loc"] == ["body", "path", *loc]


async def test_a_tolerance_below_the_floor_names_the_tolerance_and_the_floor(
    client: httpx.AsyncClient,
) -> None:
    problem = problem_of(await client.post(URL, json={"path": MIXED, "tolerance": 1e-14}), 422)
    assert problem["type"].endswith(":tolerance-floor")
    assert problem["errors"][0]["loc"] == ["body", "tolerance"]
    assert 1e-14 < problem["limit"] < 1e-6
    assert f"{problem['limit']:g}" in problem["detail"]
    assert "path.subpaths[" in problem["detail"]


async def test_too_many_output_segments_is_a_segment_limit(
    limited: tuple[FastAPI, httpx.AsyncClient],
) -> None:
    _, client = limited
    cubic = "M 0 0 C 10 0 20 10 30 30"
    ok = await approximate(client, {"path": cubic, "tolerance": 0.01})
    assert ok["stats"]["segment_count"] <= 10
    for body in (
        {"path": cubic, "tolerance": 0.001},
        # Each cubic alone fits in 10; the three together do not (the limit is per path).
        {"path": f"{cubic} M 40 0 c 10 0 20 10 30 30 M 80 0 c 10 0 20 10 30 30", "tolerance": 0.01},
    ):
        problem = problem_of(await client.post(URL, json=body), 422)
        assert problem["type"].endswith(":segment-limit")
        assert problem["limit"] == 10
        assert problem["errors"][0]["loc"] == ["body", "tolerance"]
        assert "10" in problem["detail"]


async def test_too_many_input_segments_in_svg_data_is_a_segment_limit(
    limited: tuple[FastAPI, httpx.AsyncClient],
) -> None:
    _, client = limited
    ok = await approximate(client, {"path": "M 0 0 L 1 0 L 1 1 Z", "tolerance": 0.1})
    assert ok["stats"]["segment_count"] == 3
    data = "M 0 0 L 1 0 L 1 1 L 0 1 Z"  # the closing line is the fourth segment
    problem = problem_of(await client.post(URL, json={"path": data, "tolerance": 0.1}), 422)
    assert problem["type"].endswith(":segment-limit")
    assert problem["limit"] == 3
    assert problem["errors"][0]["loc"] == ["body", "path"]
    assert problem["errors"][0]["msg"].startswith(f"at character {data.index('Z')}:")
    # The preview and a batch take the same limit.
    problem = problem_of(await client.post(PREVIEW, json={"path": data, "tolerance": 0.1}), 422)
    assert problem["limit"] == 3
    response = await client.post(BATCH, json={"jobs": [{"path": data, "tolerance": 0.1}]})
    (entry,) = strict_json(response)["results"]
    assert entry["error"]["type"].endswith(":segment-limit")
    assert locs(entry["error"]) == [["body", "jobs", 0, "path"]]


@pytest.mark.parametrize(
    ("body", "loc"),
    [
        ({"path": MIXED, "tolerance": 0.1, "strategy": "greedy"}, ["strategy"]),
        ({"path": MIXED, "tolerance": 0.1, "tolerence": 1}, ["tolerence"]),
        ({"path": MIXED, "tolerance": 0}, ["tolerance"]),
        ({"path": MIXED}, ["tolerance"]),
        ({"tolerance": 0.1}, ["path"]),
        (
            {"path": MIXED, "tolerance": 0.1, "gcode": {"feed_rate": 1, "feedrate": 2}},
            ["gcode", "feedrate"],
        ),
    ],
    ids=[
        "unknown-strategy",
        "extra-field",
        "zero-tolerance",
        "no-tolerance",
        "no-path",
        "gcode-extra",
    ],
)
async def test_invalid_requests_are_refused_naming_the_field(
    client: httpx.AsyncClient, body: dict[str, Any], loc: list[str | int]
) -> None:
    problem = problem_of(await client.post(URL, json=body), 422)
    assert problem["type"].endswith(":validation")
    assert problem["errors"][0]["loc"] == ["body", *loc]


def _one(segment: dict[str, Any], **subpath: Any) -> dict[str, Any]:
    return {"subpaths": [{"start": [0, 0], "segments": [segment], **subpath}]}


@pytest.mark.parametrize(
    ("path", "loc"),
    [
        (_one({"type": "line", "to": [1, 1], "control": [0, 1]}), ["segments", 0, "control"]),
        (_one({"type": "line", "to": [1, 1]}, colsed=True), ["colsed"]),
        (_one({"type": "arc", "center": [1, 0], "sweep_deg": 0}), ["segments", 0, "sweep_deg"]),
        (_one({"type": "elliptical_arc", "radii": [0, 1], "to": [1, 1]}), ["segments", 0, "radii"]),
        (_one({"type": "line", "to": [1]}), ["segments", 0, "to"]),
    ],
    ids=["segment-extra-field", "subpath-extra-field", "zero-sweep", "zero-radius", "short-vector"],
)
async def test_json_form_schema_errors_name_the_field_as_written(
    client: httpx.AsyncClient, path: dict[str, Any], loc: list[str | int]
) -> None:
    problem = problem_of(await client.post(URL, json={"path": path, "tolerance": 0.1}), 422)
    assert problem["type"].endswith(":validation")
    assert problem["errors"][0]["loc"] == ["body", "path", "subpaths", 0, *loc]


@pytest.mark.parametrize("token", ["NaN", "Infinity", "-Infinity", "1e999"])
async def test_non_finite_numbers_in_the_json_form_are_refused(
    client: httpx.AsyncClient, token: str
) -> None:
    raw = (
        '{"path": {"subpaths": [{"start": [0, 0], "segments": '
        f'[{{"type": "line", "to": [{token}, 1]}}]}}]}}, "tolerance": 0.1}}'
    )
    response = await client.post(URL, content=raw, headers={"content-type": "application/json"})
    problem = problem_of(response, 422)
    assert problem["type"].endswith(":validation")
    strict_json(response)


@pytest.mark.parametrize(
    ("path", "tolerance"),
    [
        ("M 0 0 L 1e200 1e200", 1e197),
        ("M 0 0 C 1e149 0 0 1e149 1 1", 1e140),
        ("M 0 0 L 1e-300 0", 1e-303),
        ("M 0 0 C 10 0 20 10 30 30", 1e300),
        ("M 0 0 C 10 0 20 10 30 30", 5e-324),
        ("M 0 0 C 10 10 0 10 10 0", 0.01),  # a cusp
        ("M 0 0 C 10 0 0 0 10 0", 0.01),  # straight control points that turn back
        ("M 0 0 C 1 0 1 0 0 0", 0.01),  # a closed loop of one cubic
        ("M 0 0 L 0 0 L 0 0", 0.1),
        ("M 0 0 A 1 1e-12 45 1 1 1 0", 0.001),
        ("M 0 0 A 5 3 1e300 0 0 10 0", 0.01),
        ("M 0 0 A 0 5 0 0 1 10 0", 0.1),  # a zero radius is a line
        ("m 1e308 1e308 l 1e308 1e308", 1.0),
        (_one({"type": "arc", "center": [1e-300, 0], "sweep_deg": 359.999999}), 1e-3),
        (_one({"type": "elliptical_arc", "radii": [1e-300, 1e300], "to": [1, 1]}), 1e-3),
        (
            _one({"type": "cubic", "control1": [1e300, 0], "control2": [0, 1e300], "to": [1, 1]}),
            1.0,
        ),
    ],
)
async def test_extreme_paths_are_answered_or_refused_never_a_500_nor_a_nan(
    client: httpx.AsyncClient, path: str | dict[str, Any], tolerance: float
) -> None:
    for endpoint in (URL, PREVIEW):
        response = await client.post(endpoint, json={"path": path, "tolerance": tolerance})
        assert response.status_code in (200, 422), response.text
        if response.status_code == 422:
            problem = problem_of(response, 422)
            strict_json(response)
            assert problem["errors"][0]["loc"][:2] in (["body", "path"], ["body", "tolerance"])
        elif endpoint == URL:
            result = strict_json(response)
            PathResponse.model_validate(result)
            assert result["stats"]["max_deviation"] <= tolerance
        else:
            drawing = response.text.split("<text")[0]
            assert not re.search(r"nan|inf", drawing, re.IGNORECASE)


@pytest.mark.parametrize("endpoint", [URL, BATCH])
async def test_a_path_too_large_for_gcode_is_refused_naming_a_field_of_the_request(
    client: httpx.AsyncClient, endpoint: str
) -> None:
    job = {"path": "M 0 0 L 3e6 0", "tolerance": 0.1, "gcode": {"feed_rate": 100}}
    if endpoint == URL:
        problem = problem_of(await client.post(URL, json=job), 422)
        prefix: list[str | int] = ["body"]
    else:
        response = await client.post(BATCH, json={"jobs": [job]})
        problem = strict_json(response)["results"][0]["error"]
        prefix = ["body", "jobs", 0]
    assert problem["type"].endswith(":gcode")
    assert "1e+06" in problem["detail"]
    (loc,) = locs(problem)
    assert loc[: len(prefix)] == prefix
    assert loc[len(prefix)] in ("path", "gcode"), loc
