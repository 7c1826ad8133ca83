"""Every drawing of the shared corpus offset and machined through the API (read in place;
skipped, or failed in CI, without it), each tool-centre path checked against the contours by
the independent offset oracle (``tests/support/offset_oracle.py``): 1 mm outside every
closed contour (a drawing with an open contour is refused, naming it), and a 2 mm tool
cutting each contour on the side ``cut: auto`` gives it, in a program that LinuxCNC's
``rs274`` accepts at its strictest. Two drawings the same way through the command line."""

from __future__ import annotations

import base64
import json
import math
import re
from collections.abc import AsyncIterator
from pathlib import Path
from typing import Any

import httpx
import pytest
from asgi_lifespan import LifespanManager
from typer.testing import CliRunner

from arcspline.api.app import create_app
from arcspline.cli.app import app as cli_app
from arcspline.settings import Settings
from tests.support import offset_oracle as oracle
from tests.support.corpus import corpus_files
from tests.support.rs274 import Rs274

pytestmark = [pytest.mark.slow]

URL = "/v1/drawings/approximate"
TOLERANCE_MM = 0.01
#: The tool radius: the offset distance and half the machining tool's diameter.
RADIUS_MM = 1.0
OFFSET = {"distance": RADIUS_MM, "side": "outside"}
MACHINING = {"tool_diameter": 2 * RADIUS_MM}
GCODE = {"feed_rate": 600, "safe_z": 5, "cut_z": -1, "step_down": 0.5}
#: As in tests/api/test_drawing_corpus.py: CadQuery's rational spline says metres but means mm.
SOURCE_UNITS = {"CadQuery__cadquery__rational_spline.dxf": "mm"}
#: How far a tool-centre path may be from the exact offset of the contours it was made from
#: (the same fit, offset exactly), relative to the drawing's size: an arc's ends may sit 1e-9
#: (relative) off its circle (segment_table.check), and a few of those add up.
RTOL = 1e-8
#: Drawings run through the command line too (all contours closed; small).
#: Where a refusal or a note says a contour crosses itself.
CROSSING = re.compile(r"crosses itself at \(([-+\deE.]+), ([-+\deE.]+)\)")
#: The reasons a contour is refused a side or left out.
REASONS = ("crosses itself", "is open", "does not fit")
#: The offset notes of contours left out.
LEFT_OUT = ("open", "crossing")
CLI_FILES = ("domoszlai__juicy-gcode__testtransform.svg", "CadQuery__cadquery__MC_12x31.dxf")


def _files() -> list[Path]:
    return [*corpus_files("svg"), *corpus_files("dxf")]


def _body(file: Path, **extra: Any) -> dict[str, Any]:
    return {
        "document": base64.b64encode(file.read_bytes()).decode(),
        "encoding": "base64",
        "format": file.suffix.lower().lstrip("."),
        "tolerance": TOLERANCE_MM,
        "source_units": SOURCE_UNITS.get(file.name),
        **extra,
    }


@pytest.fixture(scope="module")
async def client() -> AsyncIterator[httpx.AsyncClient]:
    """The app in this process with its pool (two workers, as tests/api's), one per module."""
    app = create_app(Settings(pool_size=2, queue_capacity=16))
    async with (
        LifespanManager(app, startup_timeout=120, shutdown_timeout=60) as manager,
        httpx.AsyncClient(
            transport=httpx.ASGITransport(app=manager.app), base_url="http://testserver"
        ) as http,
    ):
        yield http


class Contours:
    """The drawing's contours as the service fits them without an offset: what the
    tool-centre paths are measured against."""

    def __init__(self, answer: dict[str, Any]) -> None:
        self.segments = [oracle.from_json(t["segments"]) for t in answer["toolpaths"]]
        self.closed = [bool(t["closed"]) for t in answer["toolpaths"]]
        ends = [c for seg in self.segments for s in seg for c in (*s.start, *s.end)]
        self.scale = max(1.0, *(abs(c) for c in ends))
        self.max_deviation = float(answer["stats"]["max_deviation"])

    @property
    def tolerance(self) -> float:
        return RTOL * self.scale

    def slack(self, block: dict[str, Any], notes: list[dict[str, Any]]) -> float:
        """The rounding tolerance, plus what the answer says the contours moved before the
        offset: a contour closed over itself by a hair has that loop cut out (a ``loop``
        note), and its bound grows by half the loop's length — only then, and below the
        tolerance."""
        moved = block["source_max_deviation"] - self.max_deviation
        assert moved >= 0.0
        if moved > 0.0:
            assert any("closes over itself by a loop" in n["message"] for n in notes), notes
            assert moved < TOLERANCE_MM
        return self.tolerance + moved


def _assert_ok(report: oracle.OffsetReport, slack: float, contours: Contours) -> None:
    """The report within ``slack``; where loops were cut out (``slack`` above the rounding
    tolerance) the tool touching a point of such a loop, whose normal turns all the way
    round, may have its centre well off the path, so there the side is checked more coarsely:
    the centre within half the radius of the path (a path on the wrong side is 2 mm off)."""
    if slack <= contours.tolerance:
        assert report.ok(RADIUS_MM, slack), report.describe()
        return
    assert report.ok(RADIUS_MM, slack, sided=False), report.describe()
    assert report.centre_gap_mm < 0.5 * RADIUS_MM, report.describe()


def _check_offset(contours: Contours, answer: dict[str, Any]) -> None:
    """Every closed contour offset 1 mm outside: each path made from contour ``k``
    (``offset.origin``) keeps the radius from it and reaches all of it a tool can reach
    from outside, with the tool's centre on the path. Contours are measured against their own
    paths only (offsets are per contour: a neighbour within 2 mm may be cut into)."""
    offset = answer["offset"]
    assert offset["paths_out"] == len(answer["toolpaths"]) == len(offset["origin"])
    paths = [oracle.from_json(t["segments"]) for t in answer["toolpaths"]]
    slack = contours.slack(offset, offset["notes"])
    left = {n["toolpath"]: n["message"] for n in offset["notes"] if n["kind"] in LEFT_OUT}
    for k, message in left.items():
        _assert_left_out_rightly(k, message, contours)
    # Every contour not left out is closed (an open one has no outside) and is offset.
    assert all(contours.closed[k] for k in range(len(contours.closed)) if k not in left)
    sides: list[oracle.Side | None] = [
        None if k in left else "outside" for k in range(len(contours.segments))
    ]
    report = oracle.check_each(
        contours.segments, paths, offset["origin"], RADIUS_MM, sides, reach_tolerance=slack
    )
    # An outside offset never vanishes: a contour without a path has its outside unreached.
    _assert_ok(report, slack, contours)
    assert offset["contours_in"] == len(contours.segments)


def _check_machining(contours: Contours, answer: dict[str, Any]) -> None:
    """``cut: auto``: closed contours outside at even depth, inside at odd, open ones on the
    line; each contour's tool-centre paths (leads included) checked on its side as above,
    and an open contour's path on the contour itself."""
    plan = answer["machining"]
    assert plan["tool_diameter"] == 2 * RADIUS_MM
    slack = contours.slack(plan, plan["warnings"])
    assert len(plan["contours"]) == len(answer["toolpaths"])
    uncut = {w["toolpath"]: w["message"] for w in plan["warnings"] if "left uncut" in w["message"]}
    for k, message in uncut.items():
        _assert_left_out_rightly(k, message, contours)
    assert sorted({c["toolpath"] for c in plan["contours"]}) == [
        k for k in range(len(contours.closed)) if k not in uncut
    ]
    assert 0 <= plan["rapid_length"] < math.inf
    sides: dict[int, oracle.Side] = {}
    for cut in plan["contours"]:
        k = cut["toolpath"]
        expected = ("inside" if cut["depth"] % 2 else "outside") if contours.closed[k] else "on"
        assert cut["cut"] == expected, cut
        if expected != "on":
            sides[k] = "inside" if expected == "inside" else "outside"
    paths = [oracle.from_json(t["segments"]) for t in answer["toolpaths"]]
    origin = [c["toolpath"] for c in plan["contours"]]
    for path, k in zip(paths, origin, strict=True):
        if k not in sides:
            gap = oracle.distance_to(_samples(path), contours.segments[k]).max()
            assert gap <= contours.tolerance, (k, gap)
    cut = [k for k in range(len(contours.segments)) if k in sides]
    if cut:
        mine = [(p, cut.index(k)) for p, k in zip(paths, origin, strict=True) if k in sides]
        report = oracle.check_each(
            [contours.segments[k] for k in cut],
            [p for p, _ in mine],
            [j for _, j in mine],
            RADIUS_MM,
            [sides[k] for k in cut],
            reach_tolerance=slack,
        )
        _assert_ok(report, slack, contours)


def _refused_rightly(response: httpx.Response, contours: Contours) -> bool:
    """A 422 for a good reason, checked independently (:func:`_assert_left_out_rightly`)."""
    if response.status_code != 422:
        return False
    detail = response.json()["detail"]
    named = re.search(r"toolpaths[.\[](\d+)", detail)
    if named is None or not any(why in detail for why in REASONS):
        return False
    _assert_left_out_rightly(int(named[1]), detail, contours)
    return True


def _assert_left_out_rightly(k: int, message: str, contours: Contours) -> None:
    """Contour ``k`` refused (or left out) for the reason ``message`` gives, checked
    independently: open (asked a side), crossing itself where it says, or with no point a
    tool of the radius reaches from inside."""
    if "crosses itself" in message:
        found = CROSSING.search(message)
        assert found is not None, message
        assert _crosses_at(k, float(found[1]), float(found[2]), contours), message
    elif "is open" in message:
        assert not contours.closed[k], message
        assert not oracle.is_closed(contours.segments[k]), message
    else:
        assert "does not fit" in message, message
        # Only an inside cut can vanish: no point of the contour is reachable from inside.
        assert contours.closed[k], message
        inside = oracle.check_offset([contours.segments[k]], [], RADIUS_MM, "inside")
        assert inside.reachable == 0, f"toolpaths[{k}] is reachable: {inside.describe()}"


def _crosses_at(k: int, x: float, y: float, contours: Contours) -> bool:
    """Whether ``(x, y)`` (written to six significant digits) is on contour ``k``, on two
    segments that are not neighbours (nor the first and last of a loop)."""
    segments = contours.segments[k]
    near = [
        j
        for j, s in enumerate(segments)
        if oracle.distance_to([[x, y]], [s])[0] <= 1e-5 * max(1.0, abs(x), abs(y))
    ]
    n = len(segments)
    apart = [
        (a, b)
        for a in near
        for b in near
        if a < b and b - a > 1 and not (contours.closed[k] and (a, b) == (0, n - 1))
    ]
    return bool(apart)


def _samples(path: list[oracle.OSeg]) -> list[tuple[float, float]]:
    """Each segment's ends and quarter points."""
    return [s.point(t) for s in path for t in (0.0, 0.25, 0.5, 0.75, 1.0)]


async def _contours(client: httpx.AsyncClient, file: Path) -> Contours:
    response = await client.post(URL, json=_body(file))
    assert response.status_code == 200, response.text
    return Contours(response.json())


@pytest.mark.anyio
@pytest.mark.parametrize("file", _files(), ids=lambda p: p.name)
async def test_every_closed_contour_offset_outside_keeps_and_reaches_the_tool_radius(
    client: httpx.AsyncClient, file: Path
) -> None:
    contours = await _contours(client, file)
    response = await client.post(URL, json=_body(file, offset=OFFSET))
    if _refused_rightly(response, contours):
        return
    assert response.status_code == 200, response.text
    _check_offset(contours, response.json())


@pytest.mark.anyio
@pytest.mark.parametrize("file", _files(), ids=lambda p: p.name)
async def test_every_contour_machined_on_its_side_in_a_program_rs274_accepts(
    client: httpx.AsyncClient, rs274: Rs274, file: Path
) -> None:
    contours = await _contours(client, file)
    response = await client.post(URL, json=_body(file, machining=MACHINING))
    if _refused_rightly(response, contours):
        return
    assert response.status_code == 200, response.text
    _check_machining(contours, response.json())
    program = await client.post(
        URL, json=_body(file, machining=MACHINING, output="gcode", gcode=GCODE)
    )
    assert program.status_code == 200, program.text
    verdict = rs274.run(program.text)
    assert verdict.accepted, verdict.describe()


def _cli(*args: str) -> Any:
    result = CliRunner(env={"COLUMNS": "200"}).invoke(cli_app, list(args))
    assert result.exit_code == 0, f"{result.exit_code}: {result.stderr}"
    return result


@pytest.mark.parametrize("name", CLI_FILES)
def test_the_command_line_offsets_and_machines(rs274: Rs274, tmp_path: Path, name: str) -> None:
    file = {p.name: p for p in _files()}[name]  # skips (fails in CI) without the corpus
    common = [str(file), "-t", str(TOLERANCE_MM), "-q"]
    contours = Contours(json.loads(_cli("approx", *common).stdout))
    assert all(contours.closed)
    offset = _cli("approx", *common, "--offset", str(RADIUS_MM), "--side", "outside")
    _check_offset(contours, json.loads(offset.stdout))
    tool = ["--tool-diameter", str(2 * RADIUS_MM)]
    _check_machining(contours, json.loads(_cli("approx", *common, *tool).stdout))
    out = tmp_path / "part.ngc"
    depths = ["--feed-rate", "600", "--safe-z", "5", "--cut-z", "-1", "--step-down", "0.5"]
    _cli("approx", *common, *tool, *depths, "-o", str(out))
    verdict = rs274.run(out.read_text())
    assert verdict.accepted, verdict.describe()
