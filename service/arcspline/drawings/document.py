"""A document as a request gives it: a small picklable value that the worker reads into a
:class:`~.model.Drawing` (``read``), with the reader registered for its format."""

from __future__ import annotations

from collections.abc import Callable
from typing import Literal, NamedTuple

from .dxf import read_dxf
from .model import DocumentError, DocumentLimits, Drawing
from .svg import read_svg

DocumentFormat = Literal["svg", "dxf"]


def _svg(spec: DocumentSpec) -> Drawing:
    if spec.layers is not None:
        raise DocumentError("layers", "selects layers of DXF documents only")
    return read_svg(spec.content, limits=spec.limits, units=spec.source_units)


def _dxf(spec: DocumentSpec) -> Drawing:
    return read_dxf(
        spec.content,
        limits=spec.limits,
        units=spec.source_units,
        layers=spec.layers,
        curve_tolerance_mm=spec.curve_tolerance_mm,
    )


#: The reader of each format.
READERS: dict[str, Callable[[DocumentSpec], Drawing]] = {"svg": _svg, "dxf": _dxf}


class DocumentSpec(NamedTuple):
    """A document's bytes, its format, the unit its numbers are in when the request says so
    (else the document's own), the DXF layers to read (all when ``None``), the limits, and
    how far a reader may approximate a curve it cannot hold exactly (certified; ``None``:
    refuse such curves)."""

    content: bytes
    format: DocumentFormat
    source_units: str | None = None
    layers: tuple[str, ...] | None = None
    limits: DocumentLimits = DocumentLimits()
    curve_tolerance_mm: float | None = None

    def read(self) -> Drawing:
        return READERS[self.format](self)
