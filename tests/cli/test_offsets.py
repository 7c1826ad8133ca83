"""The tool-radius options (``arcspline.cli.tooling``): what they set in a request's
``offset`` or ``machining`` block, the usage errors of options with nothing to apply to, the
options the service's field paths stand for, and the summary's offset and machining lines.
The option lists follow the service's own request models."""

from __future__ import annotations

import io
import json
import math
from collections import Counter
from pathlib import Path
from typing import Any, get_args

import numpy as np
import pytest
from rich.console import Console
from typer.testing import Result

from arcspline.api import offset_schemas
from arcspline.cli.errors import UsageError, option_of
from arcspline.cli.options import Kind, Overrides
from arcspline.cli.summary import MachiningFacts, OffsetFacts, Outcome, Summary, details, warnings
from arcspline.cli.tooling import (
    MACHINING_OPTIONS,
    OFFSET_OPTIONS,
    TABS_OPTIONS,
    Cut,
    Join,
    Side,
    Tooling,
)
from tests.cli.conftest import SPIRAL, Invoke
from tests.cli.geometry import svg_points
from tests.support import gcode_reader
from tests.support import offset_oracle as oracle
from tests.support.rs274 import Rs274

PATH: dict[str, Any] = {"path": "M 0 0 L 10 0 L 10 10 Z", "tolerance": 0.01}
DRAWING: dict[str, Any] = {"document": "<svg/>", "format": "svg", "tolerance": 0.01}


def _apply(request: dict[str, Any], kind: Kind = "path", **options: Any) -> dict[str, Any]:
    return Overrides.of(None, None, None, Tooling.of(**options)).apply(request, kind)


def _refused(request: dict[str, Any], kind: Kind = "path", **options: Any) -> UsageError:
    with pytest.raises(UsageError) as refused:
        _apply(request, kind, **options)
    return refused.value


def test_the_option_lists_are_the_services_fields() -> None:
    assert set(OFFSET_OPTIONS) == set(offset_schemas.OffsetRequest.model_fields)
    assert set(MACHINING_OPTIONS) | {"tabs"} == set(offset_schemas.MachiningRequest.model_fields)
    assert set(TABS_OPTIONS) == set(offset_schemas.TabsRequest.model_fields)
    assert get_args(Side) == get_args(offset_schemas.Side)
    assert get_args(Join) == get_args(offset_schemas.Join)
    assert get_args(Cut) == get_args(offset_schemas.Cut)


def test_an_offset_sets_the_offset_block() -> None:
    body = _apply(PATH, offset=3.0, side="outside", join="mitre", mitre_limit=1.5)
    assert body == {**PATH, "offset": {"distance": 3.0, "side": "outside", "join": "mitre",
                                       "mitre_limit": 1.5}}  # fmt: skip
    assert "offset" not in PATH, "the request itself is left alone"
    assert _apply(DRAWING, "drawing", offset=0.5, side="left")["offset"] == {
        "distance": 0.5,
        "side": "left",
    }


def test_the_tool_diameter_sets_the_machining_block() -> None:
    body = _apply(PATH, tool_diameter=6.0, cut="outside", direction="conventional",
                  lead_radius=0.0, ramp=True, tabs=4, tab_width=5.0, tab_height=1.5,
                  compensation="controller", tool_number=7, join="mitre")  # fmt: skip
    assert body["machining"] == {
        "tool_diameter": 6.0, "cut": "outside", "direction": "conventional",
        "lead_radius": 0.0, "entry": "ramp", "compensation": "controller", "tool_number": 7,
        "join": "mitre", "tabs": {"count": 4, "width": 5.0, "height": 1.5},
    }  # fmt: skip
    assert "offset" not in body
    assert _apply(PATH, tool_diameter=3.0, ramp=False)["machining"] == {
        "tool_diameter": 3.0,
        "entry": "plunge",
    }
    assert _apply(PATH, tool_diameter=3.0)["machining"] == {"tool_diameter": 3.0}


def test_given_options_replace_the_requests_block_fields_and_others_stay() -> None:
    tabs = {"count": 2, "width": 4.0, "height": 1.0}
    request = {**PATH, "machining": {"tool_diameter": 6.0, "cut": "inside", "tabs": tabs}}
    body = _apply(request, cut="on", tab_height=2.0)
    assert body["machining"] == {"tool_diameter": 6.0, "cut": "on",
                                 "tabs": {"count": 2, "width": 4.0, "height": 2.0}}  # fmt: skip
    request = {**PATH, "offset": {"distance": 1.0, "side": "left", "join": "mitre"}}
    assert _apply(request, side="right", mitre_limit=3.0)["offset"] == {
        "distance": 1.0, "side": "right", "join": "mitre", "mitre_limit": 3.0,
    }  # fmt: skip
    assert _apply(request) == request, "no option, no change"


@pytest.mark.parametrize(
    ("request_", "options", "option", "says"),
    [
        (PATH, {"offset": 3.0, "side": "left", "tool_diameter": 6.0}, "--offset, --tool-diameter",
         "one or the other"),
        (PATH, {"side": "left"}, "--side", "only with --offset"),
        (PATH, {"mitre_limit": 3.0, "tool_diameter": 6.0}, "--mitre-limit", "only with --offset"),
        (PATH, {"offset": 1.0, "side": "left", "mitre_limit": 3.0}, "--mitre-limit",
         "only with --join mitre"),
        (PATH, {"cut": "inside"}, "--cut", "only with --tool-diameter"),
        (PATH, {"offset": 1.0, "side": "left", "ramp": True, "tool_number": 1},
         "--ramp, --tool-number", "only with --tool-diameter"),
        (PATH, {"join": "mitre"}, "--join", "only with --offset or --tool-diameter"),
        (PATH, {"tool_diameter": 6.0, "tab_width": 5.0, "tab_height": 1.0},
         "--tab-width, --tab-height", "only with --tabs"),
        ({**PATH, "machining": {"tool_diameter": 6.0}}, {"offset": 1.0, "side": "left"},
         "--offset", "asks for machining already"),
        ({**PATH, "offset": {"distance": 1.0, "side": "left"}}, {"tool_diameter": 2.0},
         "--tool-diameter", "asks for offset already"),
    ],
    ids=["both", "side-alone", "mitre-machining", "mitre-round", "cut-alone", "machining-on-offset",
         "join-alone", "tab-sizes-alone", "offset-on-machining", "tool-on-offset"],
)  # fmt: skip
def test_an_option_with_nothing_to_apply_to_is_a_usage_error(
    request_: dict[str, Any], options: dict[str, Any], option: str, says: str
) -> None:
    refused = _refused(request_, **options)
    assert refused.option == option
    assert says in str(refused)


def test_a_spiral_takes_neither() -> None:
    spiral = {"spiral": {"control_points": [[0, 0], [1, 0], [2, 1]]}, "tolerance": 0.1}
    refused = _refused(spiral, "spiral", offset=1.0, side="left")
    assert refused.option == "--offset, --side"
    assert "a spiral" in str(refused)
    assert _refused(spiral, "spiral", tool_diameter=1.0).option == "--tool-diameter"


@pytest.mark.parametrize(
    ("path", "option"),
    [("body.offset.distance", "--offset"), ("body.offset.side", "--side"),
     ("body.offset.mitre_limit", "--mitre-limit"), ("body.offset", "--offset"),
     ("body.machining", "--tool-diameter"), ("body.machining.tool_diameter", "--tool-diameter"),
     ("body.machining.entry", "--ramp"), ("body.machining.join", "--join"),
     ("body.machining.tabs", "--tabs"), ("body.machining.tabs.count", "--tabs"),
     ("body.machining.tabs.width", "--tab-width"), ("body.machining.tool_number", "--tool-number"),
     ("body.gcode.cut_z", "--cut-z"), ("body.machining.nothing", None),
     ("body.offset.distance.x", None), ("body.path.subpaths.0", None)],
)  # fmt: skip
def test_the_services_fields_and_their_options(path: str, option: str | None) -> None:
    assert option_of(path) == option


@pytest.mark.parametrize(
    ("args", "says"),
    [
        (["--offset", "1", "--tool-diameter", "2", "--side", "left"], "--offset, --tool-diameter"),
        (["--side", "left"], "--side: only with --offset"),
        (["--cut", "inside"], "--cut: only with --tool-diameter"),
        (["--tool-diameter", "2", "--tab-width", "3"], "--tab-width: only with --tabs"),
        (["--plunge"], "--ramp: only with --tool-diameter"),
    ],
)
def test_usage_errors_exit_2_naming_the_option(cli: Invoke, args: list[str], says: str) -> None:
    for command in ("approx", "preview"):
        result = cli(command, "M 0 0 L 10 0 L 10 10 Z", "-t", "0.01", *args)
        assert result.exit_code == 2, result.output
        assert says in " ".join(result.stderr.replace("│", " ").split())


def test_a_spiral_input_refuses_them_on_the_command_line(cli: Invoke) -> None:
    result = cli("approx", str(SPIRAL), "--tool-diameter", "2")
    assert result.exit_code == 2
    assert "--tool-diameter: a spiral is one curve" in " ".join(
        result.stderr.replace("│", " ").split()
    )


def _text(renderable: object) -> str:
    console = Console(width=200, record=True, file=io.StringIO())
    console.print(renderable)
    return console.export_text()


def _row(text: str, heading: str) -> str:
    """The value of a line of the summary table."""
    line = next(line for line in text.splitlines() if line.strip().startswith(heading))
    return line.strip().removeprefix(heading).strip()


def test_the_summary_shows_the_offset_and_its_notes() -> None:
    facts = OffsetFacts(3.0, "outside", 2, 3, 1, 0.0098)
    note = "toolpaths[1] (drawn by path#b): split into 2 paths"
    summary = Summary("drawing", 3, 12, 8, 4, 1e-12, 0.0099, 0.01, "mm", (note,), offset=facts)
    text = _text(details(Outcome("part.svg", "out.svg", summary, 0.5), "approx"))
    assert _row(text, "offset") == (
        "3 mm outside: 2 contours → 3 paths, 1 note (within 0.0098 of the exact offset)"
    )
    assert "machining" not in text
    assert [t.plain for t in warnings(summary)] == [f"warning: {note}"]


def test_the_summary_shows_the_machining_plan() -> None:
    plan = MachiningFacts(6.0, (("inside", 1), ("outside", 1)), 0, 35.25)
    summary = Summary("path", 2, 14, 10, 4, 0.0, 0.01, 0.01, None, machining=plan)
    text = _text(details(Outcome("part.json", "part.ngc", summary, 0.5), "approx"))
    assert _row(text, "machining") == (
        "tool 6: 2 contours (1 inside, 1 outside), 0 warnings, rapids 35.25"
    )
    assert "offset " not in text


# -- end to end: a square part with a round hole, through the command line ---------------

#: A 60 mm square with a hole of radius 8 in its middle: far enough apart that a tool up to
#: 9 mm in radius reaches every side of each without meeting the other.
PART_SVG = """<svg xmlns="http://www.w3.org/2000/svg" width="60mm" height="60mm"
  viewBox="0 0 60 60">
  <path id="outline" d="M 0 0 H 60 V 60 H 0 Z"/>
  <circle id="hole" cx="30" cy="30" r="8"/>
</svg>
"""
DEPTHS = ["--feed-rate", "600", "--safe-z", "5", "--cut-z", "-2", "--plunge-feed-rate", "200"]


@pytest.fixture
def part(tmp_path: Path) -> Path:
    path = tmp_path / "part.svg"
    path.write_text(PART_SVG)
    return path


def _ok(result: Result) -> Result:
    assert result.exit_code == 0, f"{result.exit_code}: {result.stderr}"
    return result


def _answer(cli: Invoke, *args: str) -> dict[str, Any]:
    answer: dict[str, Any] = json.loads(_ok(cli("approx", *args, "-q")).stdout)
    return answer


def _contours(cli: Invoke, part: Path) -> list[list[oracle.OSeg]]:
    """The part's contours as the service reads them (lines and a circle: fitted exactly),
    without any offset: what the tool-centre paths are measured against."""
    answer = _answer(cli, str(part), "-t", "0.01")
    assert answer["stats"]["max_deviation"] <= 1e-9
    return [oracle.from_json(toolpath["segments"]) for toolpath in answer["toolpaths"]]


def _paths(answer: dict[str, Any]) -> list[list[oracle.OSeg]]:
    return [oracle.from_json(toolpath["segments"]) for toolpath in answer["toolpaths"]]


def _by_size(contours: list[list[oracle.OSeg]]) -> list[list[oracle.OSeg]]:
    """Largest enclosed area first: the outline, then the hole."""
    return sorted(contours, key=lambda c: -abs(oracle.signed_area(c)))


@pytest.mark.parametrize(("join", "outline_corners"), [("round", 0), ("mitre", 4)])
def test_an_outside_offset_to_json_and_svg(
    cli: Invoke, part: Path, tmp_path: Path, join: str, outline_corners: int
) -> None:
    args = [str(part), "-t", "0.01", "--offset", "3", "--side", "outside", "--join", join]
    result = _ok(cli("approx", *args, "-o", str(tmp_path / "out.json")))
    answer = json.loads((tmp_path / "out.json").read_text())
    contours, paths = _contours(cli, part), _paths(answer)
    report = oracle.check_offset(contours, paths, 3.0, "outside")
    assert report.ok(3.0, 1e-9), report.describe()
    outline, hole = _by_size(paths)
    assert len(oracle.corners(outline, closed=True)) == outline_corners
    assert oracle.corners(hole, closed=True) == []
    assert abs(oracle.signed_area(hole)) == pytest.approx(math.pi * 11**2, rel=1e-12)
    offset = answer["offset"]
    assert (offset["distance"], offset["side"], offset["contours_in"], offset["paths_out"]) == (
        3.0, "outside", 2, 2,
    )  # fmt: skip
    assert _row(result.stderr, "offset") == (
        f"3 mm outside: 2 contours → 2 paths, 0 notes (within "
        f"{offset['source_max_deviation']:.4g} of the exact offset)"
    )
    assert _row(result.stderr, "segments") == str(answer["stats"]["segment_count"])

    _ok(cli("approx", *args, "-o", str(tmp_path / "out.svg")))
    drawn = np.array(svg_points((tmp_path / "out.svg").read_text()))
    assert len(drawn) >= len(outline) + len(hole)
    # Every end point drawn is on a path of the JSON answer, 3 from the part (a mitre's tip
    # 3·√2 from its corner).
    from_part = oracle.distance_to(drawn, [s for c in contours for s in c])
    farthest = 3.0 if join == "round" else 3.0 * math.sqrt(2.0)
    assert 3.0 - 1e-9 <= from_part.min() <= from_part.max() <= farthest + 1e-9
    assert oracle.distance_to(drawn, [s for p in paths for s in p]).max() < 1e-9


def test_an_offset_that_loses_a_contour_says_so_as_a_warning(cli: Invoke, part: Path) -> None:
    result = _ok(cli("approx", str(part), "-t", "0.01", "--offset", "9", "--side", "inside"))
    answer = json.loads(result.stdout)
    notes = answer["offset"]["notes"]
    assert "vanished" in [note["kind"] for note in notes]
    assert (answer["offset"]["paths_out"], len(answer["toolpaths"])) == (1, 1)
    outline = _by_size(_contours(cli, part))[0]
    # The hole (radius 8) has no inside for a tool of radius 9; the outline's is a 42 mm square.
    report = oracle.check_offset([outline], _paths(answer), 9.0, "inside")
    assert report.ok(9.0, 1e-9), report.describe()
    assert abs(oracle.signed_area(_paths(answer)[0])) == pytest.approx(42.0**2, rel=1e-12)
    counted = f"{len(notes)} note{'' if len(notes) == 1 else 's'}"
    assert _row(result.stderr, "offset").startswith(f"9 mm inside: 2 contours → 1 path, {counted}")
    said = [line for line in result.stderr.splitlines() if line.startswith("warning: ")]
    assert said == [f"warning: {note['message']}" for note in notes]


def _cuts_at_depth(program: str, cut_z: float) -> list[oracle.OSeg]:
    """The program's feed moves in XY at the cutting depth, as the oracle's segments (arcs
    as the controller computes them: centre, radius, sweep)."""
    segments = []
    for move in gcode_reader.read(program).cuts:
        if move.start[2] != cut_z or move.end[2] != cut_z:
            continue
        if move.motion == 1:
            segments.append(oracle.line(move.xy_start, move.xy_end))
        else:
            assert move.centre is not None
            assert move.r_start is not None
            assert move.sweep_rad is not None
            start = math.atan2(move.start[1] - move.centre[1], move.start[0] - move.centre[0])
            segments.append(oracle.arc(move.centre, move.r_start, start, move.sweep_rad))
    return segments


def test_a_machining_program_cuts_the_part_outside_and_its_hole_inside(
    cli: Invoke, part: Path, tmp_path: Path, rs274: Rs274
) -> None:
    args = [str(part), "-t", "0.01", "--tool-diameter", "6", *DEPTHS]
    result = _ok(cli("approx", *args, "-o", str(tmp_path / "part.ngc")))
    program = (tmp_path / "part.ngc").read_text()
    verdict = rs274.run(program)
    assert verdict.accepted, verdict.describe()
    outline, hole = _by_size(_contours(cli, part))
    # At depth, the tool (radius 3) keeps 3 from the part and reaches all of the outline's
    # outside and all of the hole's inside: the program is written to 4 decimals.
    cuts = _cuts_at_depth(program, -2.0)
    report = oracle.check_offset([outline, hole], [cuts], 3.0, ["outside", "inside"])
    assert report.ok(3.0, 1e-4), report.describe()

    answer = _answer(cli, *args)
    assert answer["gcode"] == program
    machining = answer["machining"]
    assert sorted(c["cut"] for c in machining["contours"]) == ["inside", "outside"]
    assert {c["direction"] for c in machining["contours"]} == {"climb"}
    # Climb milling with a clockwise spindle: clockwise around the part, anticlockwise in
    # its hole (the tool-centre paths, their leads closed by a chord).
    around, within = _by_size(_paths(answer))
    assert oracle.signed_area(around) < 0 < oracle.signed_area(within)
    cuts_by_side = Counter(c["cut"] for c in machining["contours"])
    assert _row(result.stderr, "machining") == (
        f"tool 6 mm: 2 contours ({', '.join(f'{n} {cut}' for cut, n in cuts_by_side.items())}), "
        f"{len(machining['warnings'])} warnings, rapids {machining['rapid_length']:.4g} mm"
    )


def test_a_machining_program_needs_its_depths(cli: Invoke, part: Path, tmp_path: Path) -> None:
    result = cli("approx", str(part), "-t", "0.01", "--tool-diameter", "6", "--feed-rate", "600",
                 "-o", str(tmp_path / "part.ngc"))  # fmt: skip
    assert result.exit_code == 1
    assert len(result.stderr.splitlines()) == 1, result.stderr
    assert result.stderr.startswith("error: body.gcode.")
    assert result.stderr.rstrip().endswith("(option --cut-z, --safe-z)")
    assert not (tmp_path / "part.ngc").exists()


def test_a_tool_too_large_names_its_option(cli: Invoke, part: Path) -> None:
    result = cli("approx", str(part), "-t", "0.01", "--offset", "40", "--side", "inside")
    assert result.exit_code == 1
    assert result.stderr.startswith("error: body.offset.distance: ")
    assert result.stderr.rstrip().endswith("(option --offset)")


def test_a_preview_takes_the_options(cli: Invoke, part: Path, tmp_path: Path) -> None:
    out = tmp_path / "preview.svg"
    _ok(cli("preview", str(part), "-t", "0.01", "--tool-diameter", "6", "-o", str(out)))
    assert "</svg>" in out.read_text()


def test_a_batch_takes_the_options(cli: Invoke, part: Path, tmp_path: Path) -> None:
    result = cli("batch", str(part), "-t", "0.01", "--offset", "2", "--side", "outside",
                 "--out-dir", str(tmp_path / "out"), "-j", "1")  # fmt: skip
    assert result.exit_code == 0, result.stderr
    answer = json.loads((tmp_path / "out" / "part.arcs.json").read_text())
    assert (answer["offset"]["distance"], answer["offset"]["paths_out"]) == (2.0, 2)
    report = oracle.check_offset(_contours(cli, part), _paths(answer), 2.0, "outside")
    assert report.ok(2.0, 1e-9), report.describe()


def test_a_machining_plans_warnings_follow_the_table(cli: Invoke, tmp_path: Path) -> None:
    # 240 + 2π·3 ≈ 259 of tool path around the square; a tab takes its width and the tool's.
    square = "M 0 0 H 60 V 60 H 0 Z"
    tabs = ["--tabs", "30", "--tab-width", "5", "--tab-height", "1"]
    out = tmp_path / "a.json"
    result = _ok(cli("approx", square, "-t", "0.01", "--tool-diameter", "6", *tabs, "-o", str(out)))
    machining = json.loads(out.read_text())["machining"]
    assert len(machining["warnings"]) == 1
    assert "30 tabs" in machining["warnings"][0]["message"]
    assert "1 contour (1 outside), 1 warning" in _row(result.stderr, "machining")
    said = [line for line in result.stderr.splitlines() if line.startswith("warning: ")]
    assert said == [f"warning: {machining['warnings'][0]['message']}"]
