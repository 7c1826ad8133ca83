"""INPUT to a request: a file (SVG or DXF document, JSON request; by its suffix, else by
its content), inline JSON, SVG path data, or ``-`` for stdin (by its content).

A document goes to the service as its bytes, unchanged: text when they are UTF-8 (the
service encodes it back to the same bytes), else base64 (binary DXF, Latin-1 SVG), so the
document's own encoding declaration is what the reader sees.
"""

from __future__ import annotations

import base64
import codecs
import re
from dataclasses import dataclass
from pathlib import Path
from typing import Any, BinaryIO, Literal

from .errors import CommandError
from .options import Format, Kind

Content = Literal["svg", "dxf", "json", "path-data"]

#: File suffixes that say what a file holds.
SUFFIXES: dict[str, Content] = {".svg": "svg", ".dxf": "dxf", ".json": "json"}
#: The request field that names each kind.
KIND_FIELDS: dict[str, Kind] = {"spiral": "spiral", "path": "path", "document": "drawing"}

_BINARY_DXF = b"AutoCAD Binary DXF"
_UTF16_BOMS = (codecs.BOM_UTF16_LE, codecs.BOM_UTF16_BE)
#: ASCII DXF opens with group code 0 and SECTION, or with a 999 comment.
_ASCII_DXF = re.compile(rb"(?:0[ \t]*\r?\n[ \t]*SECTION|999[ \t]*\r?\n)")
#: SVG path data opens with a moveto and its first number (or a separator).
_PATH_DATA = re.compile(r"[Mm][\s\d.,+-]")
_SNIFF_BYTES = 4096


@dataclass(frozen=True)
class Source:
    """An INPUT read: ``name`` for messages and tables, its ``kind``, the ``request`` (JSON,
    without the options of the command line), and the ``output`` a JSON request asked for."""

    name: str
    kind: Kind
    request: dict[str, Any]
    output: Format | None = None


def resolve(argument: str, stdin: BinaryIO) -> Source:
    """INPUT as the commands take it."""
    if argument == "-":
        return from_bytes(stdin.read(), "stdin", None)
    path = Path(argument)
    found = _found(path)
    if found == "file":
        return read_file(path)
    if argument.lstrip().startswith("{"):
        return from_bytes(argument.encode(), "inline JSON", "json")
    if _PATH_DATA.match(argument.lstrip()) and not _names_a_file(argument):
        return Source("path data", "path", {"path": argument})
    if found == "other":
        raise CommandError(f"{argument} is not a file")
    raise CommandError(f"no such file: {argument} (nor JSON, nor SVG path data)")


def read_file(path: Path) -> Source:
    """A file, by its suffix, else by its content."""
    return from_bytes(path.read_bytes(), str(path), SUFFIXES.get(path.suffix.lower()))


def from_bytes(content: bytes, name: str, given: Content | None) -> Source:
    """The request of ``content`` (which holds ``given``, or what :func:`sniff` finds)."""
    what = given or sniff(content)
    if what is None:
        raise CommandError(
            f"{name}: cannot tell what it holds (not SVG, DXF, JSON or SVG path data)"
        )
    if what == "json":
        return _json_request(content, name)
    if what == "path-data":
        return Source(name, "path", {"path": _text(content, name).strip()})
    return Source(name, "drawing", document_request(content, what))


def sniff(content: bytes) -> Content | None:
    """What ``content`` holds, from its first bytes."""
    if content.startswith(_BINARY_DXF):
        return "dxf"
    if content.startswith(_UTF16_BOMS):
        return "svg"  # of our inputs, only XML is written in UTF-16
    head = content[:_SNIFF_BYTES].removeprefix(codecs.BOM_UTF8).lstrip()
    if head.startswith(b"<"):
        return "svg"
    if head.startswith(b"{"):
        return "json"
    if _ASCII_DXF.match(head):
        return "dxf"
    if _PATH_DATA.match(head[:2].decode("latin-1")):
        return "path-data"
    return None


def document_request(content: bytes, fmt: Literal["svg", "dxf"]) -> dict[str, Any]:
    """A drawing request's document fields, the bytes unchanged."""
    try:
        return {"document": content.decode("utf-8"), "format": fmt}
    except UnicodeDecodeError:
        encoded = base64.b64encode(content).decode("ascii")
        return {"document": encoded, "format": fmt, "encoding": "base64"}


def _json_request(content: bytes, name: str) -> Source:
    import orjson

    try:
        request = orjson.loads(content.removeprefix(codecs.BOM_UTF8))
    except orjson.JSONDecodeError as error:
        raise CommandError(f"{name}: not valid JSON ({error})") from None
    if not isinstance(request, dict):
        raise CommandError(f"{name}: a request is a JSON object, not {type(request).__name__}")
    kinds = [kind for key, kind in KIND_FIELDS.items() if key in request]
    if len(kinds) != 1:
        raise CommandError(
            f"{name}: a request has one of the fields 'spiral', 'path' or 'document' "
            f"({'none' if not kinds else 'several'} here)"
        )
    output = request.pop("output", None)
    if output is not None and output not in ("json", "gcode", "dxf", "svg"):
        raise CommandError(f"{name}: output {output!r} is not json, gcode, dxf or svg")
    return Source(name, kinds[0], request, output)


def _text(content: bytes, name: str) -> str:
    try:
        return content.decode("utf-8-sig")
    except UnicodeDecodeError as error:
        raise CommandError(f"{name}: path data is not UTF-8 text ({error})") from None


def _names_a_file(argument: str) -> bool:
    """Path data has no slashes and no file suffix; a name with either is a file's."""
    return "/" in argument or "\\" in argument or Path(argument).suffix.lower() in SUFFIXES


def _found(path: Path) -> Literal["file", "other"] | None:
    """What is at ``path``: a file, something else (a folder), or nothing (also for an
    argument too long to be a file name: path data can be)."""
    try:
        if path.is_file():
            return "file"
        return "other" if path.exists() else None
    except OSError:
        return None
