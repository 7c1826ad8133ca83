"""The commands (``arcspline.cli.app``) through typer's runner, computing locally: every kind
of INPUT to every format, each output read back independently (LinuxCNC's ``rs274`` for
programs, ezdxf for DXF, the SVG's own path data) and compared with the JSON answer; the
summary against that answer; errors as one line; usage errors; no partial file."""

from __future__ import annotations

import asyncio
import json
import math
import signal
from collections.abc import Iterator
from importlib.metadata import version
from pathlib import Path
from typing import Any

import pytest
import uvicorn

from arcspline.client import local_client
from arcspline.settings import get_settings
from tests.cli.conftest import DATA, DRAWING_DXF, DRAWING_SVG, PATH, SPIRAL, Invoke
from tests.cli.geometry import dxf_ends, json_ends, same_ends, svg_points
from tests.support.rs274 import Rs274

GCODE = ["--feed-rate", "600", "--safe-z", "5", "--cut-z", "-1", "--plunge-feed-rate", "200"]
TEXT_WARNING = Path(__file__).parents[1] / "data" / "svg" / "text_warning.svg"
FROZEN_LAYER = Path(__file__).parents[1] / "data" / "dxf" / "frozen_layer.dxf"


def _ok(result: Any) -> Any:
    assert result.exit_code == 0, f"{result.exit_code}: {result.stderr}"
    return result


def _answer(cli: Invoke, *args: str) -> dict[str, Any]:
    answer: dict[str, Any] = json.loads(_ok(cli("approx", *args, "-q")).stdout)
    return answer


def _row(stderr: str, heading: str) -> str:
    """The value of a line of the summary table."""
    line = next(line for line in stderr.splitlines() if line.strip().startswith(heading))
    return line.strip().removeprefix(heading).strip()


def test_a_spiral_to_json_on_stdout_with_its_summary(cli: Invoke) -> None:
    result = _ok(cli("approx", str(SPIRAL)))
    answer = json.loads(result.stdout)
    stats = answer["stats"]
    assert (stats["arc_count"], stats["tolerance"]) == (12, 0.001)  # Walton & Meek's Table 1
    assert answer["gcode"] is None
    assert _row(result.stderr, "kind") == "spiral"
    assert _row(result.stderr, "segments") == "12"
    assert _row(result.stderr, "arcs / lines") == "12 / 0"
    ratio = stats["max_deviation"] / stats["tolerance"]
    assert _row(result.stderr, "max deviation") == f"{stats['max_deviation']:.4g} ({ratio:.1%})"
    assert _row(result.stderr, "output") == "stdout"


def test_options_override_the_json_request(cli: Invoke) -> None:
    answer = _answer(cli, str(SPIRAL), "-t", "1e-5", "--strategy", "fewest-arcs")
    assert (answer["stats"]["tolerance"], answer["stats"]["strategy"]) == (1e-5, "fewest-arcs")
    assert answer["stats"]["max_deviation"] <= 1e-5


def test_a_drawings_program_is_accepted_by_rs274_and_is_the_services_own(
    cli: Invoke, tmp_path: Path, rs274: Rs274
) -> None:
    program = tmp_path / "part.ngc"
    result = _ok(cli("approx", str(DRAWING_SVG), "-t", "0.01", *GCODE, "-o", str(program)))
    text = program.read_text()
    verdict = rs274.run(text)
    assert verdict.accepted, verdict.describe()
    assert _row(result.stderr, "output") == str(program)
    assert _row(result.stderr, "kind") == "drawing, 2 toolpaths"
    # The program alone, as the service writes it for an Accept: text/x-gcode request.
    request = {"document": DRAWING_SVG.read_text(), "format": "svg", "tolerance": 0.01,
               "gcode": {"feed_rate": 600.0, "safe_z": 5.0, "cut_z": -1.0,
                         "plunge_feed_rate": 200.0}}  # fmt: skip

    async def alone() -> bytes:
        async with local_client() as client:
            return (await client.document(request, "gcode")).content

    assert asyncio.run(alone()) == program.read_bytes()


def test_a_dxf_drawing_to_dxf_reads_back_to_the_json_answers_segments(
    cli: Invoke, tmp_path: Path
) -> None:
    out = tmp_path / "part.dxf"
    result = _ok(cli("approx", str(DRAWING_DXF), "-t", "0.001", "-o", str(out)))
    answer = _answer(cli, str(DRAWING_DXF), "-t", "0.001")
    ends = dxf_ends(out)
    assert same_ends(ends, json_ends(answer), within=1e-9)
    assert (
        _row(result.stderr, "segments") == str(len(ends)) == str(answer["stats"]["segment_count"])
    )


def test_path_data_to_svg_draws_the_json_answers_end_points(cli: Invoke, tmp_path: Path) -> None:
    data = "M 0 0 C 10 0 20 10 30 30 L 40 30 A 5 5 0 0 1 50 30 Z"
    out = tmp_path / "path.svg"
    _ok(cli("approx", data, "-t", "0.01", "-o", str(out)))
    drawn = svg_points(out.read_text())
    for start, end in json_ends(_answer(cli, data, "-t", "0.01")):
        for point in (start, end):
            assert min(math.dist(point, p) for p in drawn) <= 1e-9


def test_stdin_and_a_json_requests_own_output(cli: Invoke) -> None:
    result = _ok(cli("approx", "-", "-t", "0.01", input=DRAWING_SVG.read_bytes()))
    assert json.loads(result.stdout)["stats"]["toolpath_count"] == 2
    assert "stdin" in result.stderr
    result = _ok(cli("approx", str(DATA / "drawing.json"), "-q"))  # "output": "svg"
    assert result.stdout.startswith("<?xml")
    assert "<svg" in result.stdout


def test_a_paths_program_to_stdout_by_format(cli: Invoke, rs274: Rs274) -> None:
    result = _ok(cli("approx", str(PATH), "--format", "gcode", "--line-numbers"))
    assert result.stdout.startswith("(arcspline")  # path.json asks for comments
    assert "N10 " in result.stdout
    verdict = rs274.run(result.stdout)
    assert verdict.accepted, verdict.describe()


def test_a_drawings_warnings_are_shown(cli: Invoke) -> None:
    result = _ok(cli("approx", str(TEXT_WARNING), "-t", "0.01"))
    assert any(line.startswith("warning: text") for line in result.stderr.splitlines())


def test_preview(cli: Invoke, tmp_path: Path) -> None:
    out = tmp_path / "preview.svg"
    _ok(cli("preview", str(DRAWING_DXF), "-t", "0.01", "-o", str(out)))
    assert out.read_text().lstrip().startswith("<svg")
    assert "</svg>" in out.read_text()
    assert _ok(cli("preview", str(SPIRAL))).stdout.lstrip().startswith("<svg")


@pytest.mark.parametrize(
    ("args", "says"),
    [
        (["approx", str(SPIRAL), "-t", "0"],
         "error: 1 invalid field(s): body.tolerance: Input should be greater than 0 "
         "(option --tolerance)"),
        (["approx", str(SPIRAL), "--feed-rate", "100", "--decimals", "9"],
         "error: 1 invalid field(s): body.gcode.decimals: Input should be less than or equal "
         "to 6 (option --decimals)"),
        (["approx", str(FROZEN_LAYER), "-t", "0.1", "--layers", "NOPE"], "(option --layers)"),
        (["approx", "missing.svg", "-t", "1"], "error: no such file: missing.svg"),
        (["approx", "M 0 0 L", "-t", "1"], "error: body.path: at character 7"),
        (["preview", str(DATA / "program.txt"), "-t", "1"], "cannot tell what it holds"),
    ],
    ids=["tolerance", "decimals", "layers", "missing-file", "path-data", "unknown-content"],
)  # fmt: skip
def test_a_failure_is_one_line_and_exit_1(cli: Invoke, args: list[str], says: str) -> None:
    result = cli(*args)
    assert result.exit_code == 1
    assert len(result.stderr.splitlines()) == 1, result.stderr
    assert says in result.stderr
    assert result.stdout == ""
    assert "Traceback" not in result.output


def test_debug_keeps_the_exception(cli: Invoke) -> None:
    result = cli("--debug", "approx", str(SPIRAL), "-t", "0")
    assert result.exit_code == 1
    assert type(result.exception).__name__ == "ServiceError"


@pytest.mark.parametrize(
    ("args", "says"),
    [
        (["approx", str(DRAWING_SVG)], "--tolerance"),
        (["approx", str(SPIRAL), "-o", "part.txt"], "its suffix is none of"),
        (["approx", str(SPIRAL), "--format", "gcode"], "--feed-rate"),
        (["approx", str(SPIRAL), "--layers", "A"], "only for drawings"),
        (["approx", str(SPIRAL), "--units", "inch"], "needs --feed-rate"),
        (["approx", str(SPIRAL), "--strategy", "fastest"], "fastest"),
        (["batch"], "Missing argument"),
    ],
)
def test_usage_errors_exit_2(cli: Invoke, args: list[str], says: str) -> None:
    result = cli(*args)
    assert result.exit_code == 2
    assert says in result.stderr


def test_no_partial_file_after_a_failure(cli: Invoke, tmp_path: Path) -> None:
    old, new = tmp_path / "old.ngc", tmp_path / "new.ngc"
    old.write_text("old program\n")
    for target in (old, new):
        result = cli("approx", str(SPIRAL), "-t", "1e-30", "--feed-rate", "100", "-o", str(target))
        assert result.exit_code == 1
        assert "tolerance" in result.stderr
    assert old.read_text() == "old program\n"
    assert [p.name for p in tmp_path.iterdir()] == ["old.ngc"]
    result = cli("approx", str(SPIRAL), "-o", str(tmp_path / "missing" / "x.json"))
    assert result.exit_code == 1
    assert "no such folder" in result.stderr


def test_version(cli: Invoke) -> None:
    result = _ok(cli("--version"))
    assert result.stdout == f"arcspline {version('arcspline')}\n"


@pytest.fixture
def _server_state() -> Iterator[None]:
    handler = signal.getsignal(signal.SIGTERM)
    get_settings.cache_clear()
    yield
    get_settings.cache_clear()
    signal.signal(signal.SIGTERM, handler)


@pytest.mark.usefixtures("_server_state")
def test_serve_is_the_server_with_the_environments_settings(
    cli: Invoke, monkeypatch: pytest.MonkeyPatch
) -> None:
    seen: list[dict[str, Any]] = []
    monkeypatch.setattr(uvicorn, "run", lambda app, **options: seen.append(options))
    monkeypatch.setenv("ARCSPLINE_PORT", "8123")
    _ok(cli("serve"))
    _ok(cli("serve", "--host", "0.0.0.0", "--port", "9000"))
    assert [(s["host"], s["port"]) for s in seen] == [("127.0.0.1", 8123), ("0.0.0.0", 9000)]
    monkeypatch.setenv("ARCSPLINE_PORT", "99999")
    get_settings.cache_clear()
    result = cli("serve")
    assert result.exit_code == 1
    assert result.stderr == (
        "error: invalid settings: ARCSPLINE_PORT: Input should be less than or equal to 65535\n"
    )
