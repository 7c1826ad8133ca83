"""A DXF document's bytes into an ezdxf drawing, and the facts the reader takes from it
before the walk: the unit its numbers are in and the layers asked for (docs/drawings.md §4).

ezdxf reads the file (ASCII R12 and R2000+, or binary; a broken file goes through
``ezdxf.recover``); any exception it raises on hostile input becomes one
:class:`DocumentError`.
"""

from __future__ import annotations

import io
from collections.abc import Iterable, Iterator, Sequence
from typing import NamedTuple

import ezdxf.units
from ezdxf import recover
from ezdxf.document import Drawing as EzDrawing
from ezdxf.enums import InsertUnits
from ezdxf.lldxf.tagger import ascii_tags_loader, binary_tags_loader
from ezdxf.lldxf.types import DXFTag
from ezdxf.lldxf.validator import dxf_info

from .model import MM_PER_UNIT, DocumentError

#: The first bytes of a binary DXF file.
BINARY_SENTINEL = b"AutoCAD Binary DXF\r\n\x1a\x00"

#: ``$INSUNITS`` codes named in ``MM_PER_UNIT``; other codes go through ``ezdxf.units``.
INSUNITS_NAMES = {1: "in", 2: "ft", 4: "mm", 5: "cm", 6: "m"}
#: Millimetres per unit for the ``$INSUNITS`` codes ``ezdxf.units`` cannot convert.
INSUNITS_EXTRA_MM = {
    8: ("µin", 25.4e-6),
    9: ("mil", 0.0254),
    21: ("US survey ft", 1200.0 / 3937.0 * 1000.0),
    22: ("US survey in", 100.0 / 3937.0 * 1000.0),
    23: ("US survey yd", 3600.0 / 3937.0 * 1000.0),
    24: ("US survey mi", 6336000.0 / 3937.0 * 1000.0),
}


class Units(NamedTuple):
    """The unit a document's numbers are taken in, its millimetres, and a note when it was
    assumed rather than declared."""

    name: str
    mm_per_unit: float
    note: str | None


class _HeaderWatch:
    """Passes tags through, noting whether a HEADER section went by: ezdxf gives a file
    without one a default header (which claims metres), so its presence must be seen here."""

    def __init__(self) -> None:
        self.seen = False
        self.sections = 0

    def tags(self, tags: Iterable[DXFTag]) -> Iterator[DXFTag]:
        previous: DXFTag | None = None
        for tag in tags:
            if (
                previous is not None
                and previous.code == 0
                and previous.value in ("SECTION", b"SECTION")
                and tag.code == 2
            ):
                self.sections += 1
                self.seen = self.seen or tag.value in ("HEADER", b"HEADER")
            previous = tag
            yield tag


def load(document: bytes) -> tuple[EzDrawing, bool]:
    """The document read by ezdxf, and whether it has a HEADER section; a document without a
    single section is not DXF (ezdxf would give it an empty drawing)."""
    doc, watch = _parse(document)
    if not watch.sections:
        raise DocumentError("document", "is not a DXF file (it has no SECTION)")
    return doc, watch.seen


def _parse(document: bytes) -> tuple[EzDrawing, _HeaderWatch]:
    """ezdxf's reading of the document; ezdxf raises many kinds of exception on hostile
    input, and all of them mean the same thing here."""
    watch = _HeaderWatch()
    try:
        if document.startswith(BINARY_SENTINEL):
            return EzDrawing.load(watch.tags(binary_tags_loader(document))), watch
        # Bytes the declared encoding cannot decode become U+FFFD: ezdxf's default
        # (surrogateescape) would carry lone surrogates into element names and messages,
        # which no UTF-8 answer can hold (JSON, SVG, G-code).
        text = document.decode(_encoding(document), errors="replace")
        return EzDrawing.load(watch.tags(ascii_tags_loader(io.StringIO(text, newline=None)))), watch
    except Exception as first:
        watch = _HeaderWatch()
        try:
            for _ in watch.tags(recover.bytes_loader(io.BytesIO(document))):
                pass
            doc, _auditor = recover.read(io.BytesIO(document), errors="replace")
        except Exception as exc:
            why = str(first)[:200]
            raise DocumentError("document", f"is not a readable DXF file ({why})") from exc
        return doc, watch


def _encoding(document: bytes) -> str:
    """The text encoding the file declares (``$DWGCODEPAGE``; UTF-8 from R2007 on), as
    ``ezdxf.readfile`` finds it."""
    try:
        info = dxf_info(io.StringIO(document.decode("utf-8", errors="ignore")))
        encoding = "utf-8" if info.version >= "AC1021" else info.encoding
        "".encode(encoding)
    except Exception:  # an unreadable header: the loader says what is wrong
        return "utf-8"
    return encoding


def document_units(doc: EzDrawing, has_header: bool, override: str | None) -> Units:
    """The unit the document's numbers are taken in: the request's, else ``$INSUNITS``;
    millimetres, with a note, when the document declares none."""
    if override is not None:
        if override not in MM_PER_UNIT:
            raise DocumentError(
                "units", f"unknown unit {override!r}; known: {', '.join(MM_PER_UNIT)}"
            )
        return Units(override, MM_PER_UNIT[override], None)
    if not has_header:
        return Units("mm", 1.0, "has no HEADER section, so no units: millimetres were taken")
    code = doc.header.get("$INSUNITS", 0)
    if not isinstance(code, int) or code == 0:
        return Units("mm", 1.0, "declares no units ($INSUNITS unset or 0): millimetres taken")
    if code in INSUNITS_NAMES:
        name = INSUNITS_NAMES[code]
        return Units(name, MM_PER_UNIT[name], None)
    if code in INSUNITS_EXTRA_MM:
        return Units(*INSUNITS_EXTRA_MM[code], None)
    unknown = Units("mm", 1.0, f"declares unknown units ($INSUNITS {code}): millimetres taken")
    if code not in {unit.value for unit in InsertUnits}:
        return unknown  # ezdxf.units.decode indexes a list with the code: check it first
    try:
        return Units(
            ezdxf.units.decode(code) or str(code),
            ezdxf.units.conversion_factor(InsertUnits(code), InsertUnits.Millimeters),
            None,
        )
    except (ValueError, KeyError, TypeError, IndexError, ArithmeticError):
        return unknown


def selected_layers(doc: EzDrawing, layers: Sequence[str] | None) -> frozenset[str] | None:
    """The requested layers, matched without regard to case as DXF layer names are; unknown
    names are refused, listing the layers the document has."""
    if layers is None:
        return None
    known = {entry.dxf.name.upper(): entry.dxf.name for entry in doc.layers}
    for entity in doc.modelspace():
        # An entity ezdxf does not know has no layer attribute (it is skipped when read).
        if entity.dxf.is_supported("layer") and entity.dxf.hasattr("layer"):
            known.setdefault(entity.dxf.layer.upper(), entity.dxf.layer)
    unknown = [name for name in layers if name.upper() not in known]
    if unknown:
        raise DocumentError(
            "layers",
            f"no layer named {', '.join(map(repr, unknown))}; the document has "
            f"{', '.join(map(repr, sorted(known.values())))}",
        )
    return frozenset(name.upper() for name in layers)
