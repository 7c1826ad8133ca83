"""Where an output goes (``arcspline.cli.outputs``): the format by --format, else by the
suffix of -o; a file appears whole or not at all, an older one stays as it was."""

from __future__ import annotations

from pathlib import Path

import pytest

from arcspline.cli.errors import CommandError, UsageError
from arcspline.cli.outputs import STDOUT, check_writable, format_of, output_path, write


@pytest.mark.parametrize(
    ("name", "fmt"),
    [("part.ngc", "gcode"), ("part.GCODE", "gcode"), ("part.nc", "gcode"), ("a.b.dxf", "dxf"),
     ("part.svg", "svg"), ("part.json", "json")],
)  # fmt: skip
def test_the_suffix_names_the_format(name: str, fmt: str) -> None:
    assert format_of(Path(name), None, "json") == fmt


def test_format_beats_suffix_and_stdout_takes_the_default() -> None:
    assert format_of(Path("part.txt"), "gcode", "json") == "gcode"
    assert format_of(Path("part.ngc"), "json", "svg") == "json"
    assert format_of(None, None, "svg") == "svg"
    assert format_of(STDOUT, None, "json") == "json"
    with pytest.raises(UsageError, match=r"part\.txt: its suffix is none of") as refused:
        format_of(Path("part.txt"), None, "json")
    assert refused.value.option == "-o"


def test_a_file_appears_whole_and_replaces_the_old_one(tmp_path: Path) -> None:
    target = tmp_path / "part.ngc"
    target.write_bytes(b"old")
    write(b"G0 X0\nM2\n", target)
    assert target.read_bytes() == b"G0 X0\nM2\n"
    assert [p.name for p in tmp_path.iterdir()] == ["part.ngc"]


def test_a_failed_write_leaves_no_partial_file_and_the_old_one_alone(tmp_path: Path) -> None:
    target = tmp_path / "part.ngc"
    target.write_bytes(b"old")
    with pytest.raises(TypeError):
        write("not bytes", target)  # type: ignore[arg-type]  # fails inside the write
    assert target.read_bytes() == b"old"
    with pytest.raises(TypeError):
        write("not bytes", tmp_path / "new.ngc")  # type: ignore[arg-type]
    assert [p.name for p in tmp_path.iterdir()] == ["part.ngc"]


def test_an_unwritable_place_is_found_before_the_work(tmp_path: Path) -> None:
    check_writable(None)
    check_writable(tmp_path / "part.ngc")
    with pytest.raises(CommandError, match="no such folder"):
        check_writable(tmp_path / "missing" / "part.ngc")
    with pytest.raises(CommandError, match="is a folder"):
        check_writable(tmp_path)


def test_a_batch_output_is_named_by_its_input() -> None:
    assert output_path(Path("in/a.svg"), None, "gcode", False) == Path("in/a.ngc")
    assert output_path(Path("in/a.svg"), Path("out"), "dxf", False) == Path("out/a.arcs.dxf")
    assert output_path(Path("in/a.json"), None, "json", True) == Path("in/a.json.arcs.json")


def test_the_output_may_not_replace_the_input(tmp_path: Path) -> None:
    drawing = tmp_path / "part.svg"
    drawing.write_text("<svg/>")
    with pytest.raises(UsageError, match="is the input"):
        check_writable(tmp_path / "." / "part.svg", str(drawing))
    check_writable(tmp_path / "part.arcs.svg", str(drawing))
