"""INPUT to request (``arcspline.cli.inputs``): every kind of input, by file suffix, by
content and typed inline, against the golden cases of ``data/inputs.json``; stdin; documents
sent as their exact bytes."""

from __future__ import annotations

import base64
import io
import json
from pathlib import Path
from typing import Any

import ezdxf
import pytest

from arcspline.cli.errors import CommandError
from arcspline.cli.inputs import Source, resolve, sniff
from tests.cli.conftest import DATA, DRAWING_DXF, DRAWING_SVG

GOLDEN = json.loads((DATA / "inputs.json").read_text())
NO_STDIN = io.BytesIO(b"")


def _argument(case: dict[str, Any]) -> str:
    return str(DATA / case["file"]) if "file" in case else case["argument"]


def _id(case: dict[str, Any]) -> str:
    return case.get("file") or case["argument"][:30]


@pytest.mark.parametrize("case", GOLDEN["cases"], ids=_id)
def test_each_kind_of_input_gives_its_request(case: dict[str, Any]) -> None:
    source = resolve(_argument(case), NO_STDIN)
    assert source.kind == case["kind"]
    assert source.output == case.get("output")
    if "request" in case:
        assert source.request == case["request"]
    for name, value in case.get("fields", {}).items():
        assert source.request[name] == value, name
    assert "output" not in source.request


@pytest.mark.parametrize("case", GOLDEN["errors"], ids=_id)
def test_what_is_not_an_input_is_one_clear_reason(case: dict[str, Any]) -> None:
    with pytest.raises(CommandError) as refused:
        resolve(_argument(case), NO_STDIN)
    assert case["reason"] in str(refused.value)
    assert "\n" not in str(refused.value)


def test_a_folder_is_not_an_input() -> None:
    with pytest.raises(CommandError, match="is not a file"):
        resolve(str(DATA), NO_STDIN)


def test_path_data_too_long_for_a_file_name_is_still_path_data() -> None:
    data = "M 0 0" + " L 1 1 L 2 0" * 1000
    assert resolve(data, NO_STDIN) == Source("path data", "path", {"path": data})


@pytest.mark.parametrize(
    ("file", "kind", "fmt"),
    [
        (DRAWING_SVG, "drawing", "svg"),
        (DRAWING_DXF, "drawing", "dxf"),
        (DATA / "spiral.json", "spiral", None),
        (DATA / "path-data.txt", "path", None),
    ],
    ids=["svg", "dxf", "json", "path-data"],
)
def test_stdin_is_read_by_its_content(file: Path, kind: str, fmt: str | None) -> None:
    source = resolve("-", io.BytesIO(file.read_bytes()))
    assert (source.name, source.kind) == ("stdin", kind)
    assert source.request.get("format") == fmt


def test_a_document_goes_as_its_own_bytes(tmp_path: Path) -> None:
    """UTF-8 as text, anything else as base64: either way the service reads these bytes."""
    utf8 = DRAWING_SVG.read_bytes()
    assert resolve(str(DRAWING_SVG), NO_STDIN).request["document"].encode() == utf8
    latin1 = tmp_path / "latin1.svg"
    latin1.write_bytes(
        b'<?xml version="1.0" encoding="ISO-8859-1"?>\n<svg xmlns="http://www.w3.org/2000/svg">'
        b'<desc>\xe9t\xe9</desc><path d="M 0 0 L 10 0"/></svg>'
    )
    request = resolve(str(latin1), NO_STDIN).request
    assert request["encoding"] == "base64"
    assert base64.b64decode(request["document"]) == latin1.read_bytes()


def test_a_binary_dxf_is_found_by_its_sentinel_and_sent_as_base64(tmp_path: Path) -> None:
    doc = ezdxf.new("R2000")
    doc.modelspace().add_line((0, 0), (10, 0))
    binary = tmp_path / "part.bin"
    doc.saveas(binary, fmt="bin")
    assert sniff(binary.read_bytes()) == "dxf"
    request = resolve(str(binary), NO_STDIN).request
    assert (request["format"], request["encoding"]) == ("dxf", "base64")
    assert base64.b64decode(request["document"]) == binary.read_bytes()


@pytest.mark.parametrize(
    ("content", "found"),
    [
        (b"\xef\xbb\xbf<svg/>", "svg"),
        (b"\xff\xfe<\x00s\x00", "svg"),
        (b"  \n<?xml version='1.0'?><svg/>", "svg"),
        (b"999\ncomment\n  0\nSECTION\n", "dxf"),
        (b"  0\r\nSECTION\r\n", "dxf"),
        (b'\n{"path": "M 0 0"}', "json"),
        (b"M10,10", "path-data"),
        (b"", None),
        (b"G0 X0", None),
        (b"Makefile", None),
    ],
)
def test_sniffing(content: bytes, found: str | None) -> None:
    assert sniff(content) == found


def test_a_json_request_may_start_with_a_byte_order_mark(tmp_path: Path) -> None:
    request = tmp_path / "bom.json"
    request.write_bytes(b'\xef\xbb\xbf{"path": "M 0 0 L 1 1", "tolerance": 0.1}')
    source = resolve(str(request), NO_STDIN)
    assert (source.kind, source.request["path"]) == ("path", "M 0 0 L 1 1")
