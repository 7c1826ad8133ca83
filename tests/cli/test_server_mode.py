"""``--server URL``: the same work sent to a running service (``python -m arcspline`` in a
subprocess) gives the same bytes as computing it here — for a spiral, a path and a
drawing (SVG and DXF), in every format, the preview, and a batch; an unreachable server is
one line naming it."""

from __future__ import annotations

import re
import shutil
import socket
from collections.abc import Iterator
from pathlib import Path

import pytest

from tests.cli.conftest import DRAWING_DXF, DRAWING_SVG, PATH, SPIRAL, Invoke
from tests.support.server import Server, running_server

pytestmark = [pytest.mark.integration, pytest.mark.xdist_group("cli-server")]

PATH_DATA = "M 0 0 C 10 0 20 10 30 30 L 40 30 A 5 5 0 0 1 50 30 Z"
GCODE = ["--feed-rate", "600", "--safe-z", "5", "--cut-z", "-1", "--comments"]
TABS = ["--tool-diameter", "4", "--tabs", "2", "--tab-width", "3", "--tab-height", "0.5"]


@pytest.fixture(scope="module")
def server(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Server]:
    """A server with a pool of two workers, shared by this module's tests."""
    with running_server(tmp_path_factory.mktemp("server"), pool_size=2) as server:
        yield server


def _summary(stderr: str) -> list[str]:
    """The summary table's words, but its time."""
    lines = (line.split() for line in stderr.splitlines())
    return [" ".join(words) for words in lines if words and words[0] != "time"]


CASES = {
    "spiral.json": ["approx", str(SPIRAL), "-t", "1e-5"],
    "spiral.ngc": ["approx", str(SPIRAL), "-t", "1e-5", *GCODE, "--arc-format", "r"],
    "spiral.dxf": ["approx", str(SPIRAL)],
    "path.json": ["approx", PATH_DATA, "-t", "0.01", "--strategy", "fewest-arcs"],
    "path.svg": ["approx", str(PATH)],
    "path-preview.svg": ["preview", str(PATH)],
    "svg-drawing.ngc": ["approx", str(DRAWING_SVG), "-t", "0.01", *GCODE, "--step-down", "0.4"],
    "svg-drawing.svg": ["approx", str(DRAWING_SVG), "-t", "0.01", "--units", "inch"],
    "svg-drawing.json": ["approx", str(DRAWING_SVG), "-t", "0.001", "--choose-start"],
    "dxf-drawing.dxf": ["approx", str(DRAWING_DXF), "-t", "0.001"],
    "dxf-drawing-preview.svg": ["preview", str(DRAWING_DXF), "-t", "0.01"],
    "path-offset.json": ["approx", PATH_DATA, "-t", "0.01", "--offset", "1", "--side", "left"],
    "svg-drawing-machined.ngc": ["approx", str(DRAWING_SVG), "-t", "0.01", *GCODE, *TABS],
    "svg-drawing-machined-preview.svg": ["preview", str(DRAWING_SVG), "-t", "0.01", *TABS],
}


@pytest.mark.parametrize("name", CASES)
def test_the_server_gives_the_same_bytes(
    cli: Invoke, server: Server, tmp_path: Path, name: str
) -> None:
    here, there = tmp_path / "here", tmp_path / "there"
    here.mkdir()
    there.mkdir()
    local = cli(*CASES[name], "-o", str(here / name))
    remote = cli(*CASES[name], "-o", str(there / name), "--server", server.url)
    assert (local.exit_code, remote.exit_code) == (0, 0), local.stderr + remote.stderr
    assert (here / name).read_bytes() == (there / name).read_bytes()
    assert _summary(local.stderr.replace(str(here), "")) == _summary(
        remote.stderr.replace(str(there), "")
    )


def test_a_batch_through_the_server_writes_the_same_files(
    cli: Invoke, server: Server, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.chdir(tmp_path)
    parts = tmp_path / "parts"
    parts.mkdir()
    for source in (SPIRAL, DRAWING_SVG, DRAWING_DXF):
        shutil.copy(source, parts)
    (parts / "broken.dxf").write_text("0\nSECTION\n2\nENTITIES\n0\nLINE\n10\nx\n")
    args = ["batch", "parts", "-t", "0.01", *GCODE, "-j", "2"]
    local = cli(*args, "--out-dir", "here")
    remote = cli(*args, "--out-dir", "there", "--server", server.url)
    assert (local.exit_code, remote.exit_code) == (1, 1)
    names = sorted(p.name for p in (tmp_path / "here").iterdir())
    assert names == ["bulge_lwpolyline.ngc", "rounded_rect.ngc", "spiral.ngc"]
    assert names == sorted(p.name for p in (tmp_path / "there").iterdir())
    for name in names:
        assert (tmp_path / "here" / name).read_bytes() == (tmp_path / "there" / name).read_bytes()
    for result in (local, remote):
        assert re.search(r"parts/broken\.dxf .* failed: body\.document", result.stderr)


def test_an_unreachable_server_is_one_line_naming_it(cli: Invoke) -> None:
    with socket.socket() as s:  # a port nothing listens on
        s.bind(("127.0.0.1", 0))
        url = f"http://127.0.0.1:{s.getsockname()[1]}"
    for args in (["approx", str(SPIRAL)], ["batch", str(SPIRAL)]):
        result = cli(*args, "--server", url)
        assert result.exit_code == 1
        assert result.stderr.startswith(f"error: could not reach {url} (")
        assert len(result.stderr.splitlines()) == 1


def test_a_server_without_a_scheme_is_a_usage_error(cli: Invoke) -> None:
    result = cli("approx", str(SPIRAL), "--server", "localhost:8000")
    assert result.exit_code == 2
    assert "--server takes a URL such as http://localhost:8000" in result.stderr
