"""Many files (``arcspline.cli.batch``): which files, where each output goes, and a batch
with a bad file among good ones, computed by a local pool of worker processes: exit 1, the
others written (their programs accepted by ``rs274``), the bad one named with its reason."""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import pytest

from arcspline.cli.batch import expand, plan
from arcspline.cli.errors import CommandError, UsageError
from tests.cli.conftest import DATA, DRAWING_DXF, DRAWING_SVG, SPIRAL, Invoke
from tests.support.rs274 import Rs274

BROKEN_SVG = b'<svg xmlns="http://www.w3.org/2000/svg"><path d="M 0 0 L 1 1"></svg>'


def _parts(folder: Path) -> Path:
    """Three good inputs of three kinds, and a broken SVG."""
    folder.mkdir()
    for source in (SPIRAL, DRAWING_SVG, DRAWING_DXF):
        shutil.copy(source, folder)
    (folder / "broken.svg").write_bytes(BROKEN_SVG)
    (folder / "notes.txt").write_text("not an input")
    return folder


def test_folders_globs_and_files(tmp_path: Path) -> None:
    parts = _parts(tmp_path / "parts")
    names = [p.name for p in expand([str(parts)])]
    assert names == ["broken.svg", "bulge_lwpolyline.dxf", "rounded_rect.svg", "spiral.json"]
    assert expand([f"{tmp_path}/**/*.svg", str(parts / "broken.svg")]) == [
        parts / "broken.svg", parts / "rounded_rect.svg"
    ]  # fmt: skip
    assert expand([str(parts / "notes.txt")]) == [parts / "notes.txt"]  # named: taken
    with pytest.raises(CommandError, match=r"no files in .*\*\.step"):
        expand([str(parts / "*.step")])


def test_outputs_never_meet_nor_replace_an_input(tmp_path: Path) -> None:
    a_svg, a_dxf, b_json = Path("in/a.svg"), Path("in/a.dxf"), Path("in/b.json")
    outputs = plan([a_svg, a_dxf, b_json], None, "json").outputs
    assert outputs == {
        a_svg: Path("in/a.svg.arcs.json"),
        a_dxf: Path("in/a.dxf.arcs.json"),
        b_json: Path("in/b.arcs.json"),
    }
    assert plan([a_svg], None, "svg").outputs == {a_svg: Path("in/a.arcs.svg")}
    assert plan([a_svg, b_json], tmp_path, "gcode").outputs == {
        a_svg: tmp_path / "a.ngc",
        b_json: tmp_path / "b.ngc",
    }
    with pytest.raises(UsageError, match="would write the same output"):
        plan([Path("x/a.svg"), Path("y/a.svg")], tmp_path, "dxf")


def test_one_bad_file_is_reported_and_the_others_finish(
    cli: Invoke, tmp_path: Path, rs274: Rs274, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.chdir(tmp_path)  # short names: the table's lines stay whole
    _parts(tmp_path / "parts")
    out = Path("programs")
    result = cli("batch", "parts", "-t", "0.01", "--feed-rate", "600", "-j", "2",
                 "--out-dir", str(out))  # fmt: skip
    assert result.exit_code == 1, result.stderr
    written = sorted(p.name for p in out.iterdir())
    assert written == ["bulge_lwpolyline.ngc", "rounded_rect.ngc", "spiral.ngc"]
    for program in out.iterdir():
        verdict = rs274.run(program.read_text())
        assert verdict.accepted, f"{program.name}: {verdict.describe()}"
    lines = result.stderr.splitlines()
    assert "arcspline batch: 3 written, 1 failed" in lines
    broken = next(line for line in lines if "broken.svg" in line)
    assert "failed: body.document: not well-formed XML" in broken
    for name in written:
        assert any(str(out / name) in line for line in lines)


def test_json_beside_each_input_without_gcode_options(cli: Invoke, tmp_path: Path) -> None:
    shutil.copy(DRAWING_SVG, tmp_path)
    shutil.copy(DATA / "path.json", tmp_path)
    result = cli("batch", str(tmp_path / "*.*"), "-t", "0.01", "-j", "1")
    assert result.exit_code == 0, result.stderr
    drawing = json.loads((tmp_path / "rounded_rect.arcs.json").read_text())
    assert drawing["stats"]["toolpath_count"] == 2
    path = json.loads((tmp_path / "path.arcs.json").read_text())
    assert path["stats"]["tolerance"] == 0.01
    assert "arcspline batch: 2 written, 0 failed" in result.stderr


def test_a_second_batch_beside_its_inputs_takes_only_the_inputs(
    cli: Invoke, tmp_path: Path
) -> None:
    shutil.copy(DRAWING_SVG, tmp_path)
    shutil.copy(DATA / "path.json", tmp_path)
    for fmt in ("json", "svg", "json"):
        result = cli("batch", str(tmp_path), "-t", "0.01", "-f", fmt, "-j", "1")
        assert result.exit_code == 0, result.stderr
        assert "arcspline batch: 2 written, 0 failed" in result.stderr
    assert sorted(p.name for p in tmp_path.iterdir()) == [
        "path.arcs.json", "path.arcs.svg", "path.json",
        "rounded_rect.arcs.json", "rounded_rect.arcs.svg", "rounded_rect.svg",
    ]  # fmt: skip
