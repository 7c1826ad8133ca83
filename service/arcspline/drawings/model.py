"""What a drawing reader gives: the drawn elements as subpaths in millimetres, with what it
could not take said in warnings (docs/drawings.md §1).

Nothing is lost silently: every element of the document is either in ``elements`` or
counted in a warning (``Drawing.elements_in == len(elements) + skipped``).
"""

from __future__ import annotations

from typing import NamedTuple

from arcspline.geometry.curves.segments import Subpath

#: Millimetres per unit of length, for the units a drawing or a request may name.
MM_PER_UNIT: dict[str, float] = {
    "mm": 1.0,
    "cm": 10.0,
    "m": 1000.0,
    "in": 25.4,
    "ft": 304.8,
    "pt": 25.4 / 72.0,
    "pc": 25.4 / 6.0,
    "px": 25.4 / 96.0,
}


class Element(NamedTuple):
    """One drawn subpath and where it came from (``path#outline``, ``LINE #1F``, ``line 12``)."""

    subpath: Subpath
    source: str


class DrawingWarning(NamedTuple):
    """Something of the document not drawn, and why (``occurrences`` elements alike)."""

    element: str
    reason: str
    occurrences: int = 1


class Drawing(NamedTuple):
    """A document read: its elements in millimetres (y up), and what was left out.

    ``units`` is the unit the document's own numbers were taken to be in (declared, or
    overridden by the request); ``elements_in`` counts the drawable elements the document
    held, each one either read into ``elements`` or counted in ``warnings``.
    ``approximated_mm`` is the largest distance, certified, between an element and the
    document's own curve where the reader had to approximate one (a rational cubic spline);
    0 where every element is exact.
    """

    elements: tuple[Element, ...]
    warnings: tuple[DrawingWarning, ...]
    units: str
    elements_in: int
    approximated_mm: float = 0.0

    @property
    def skipped(self) -> int:
        return sum(w.occurrences for w in self.warnings)


class DocumentLimits(NamedTuple):
    """Bounds on what a reader accepts before it refuses a document.

    ``max_bytes``: the document's size; ``max_elements``: elements, each ``use`` or block
    instance counted again; ``max_depth``: nesting of groups, uses and blocks;
    ``max_segments``: segments read, over all elements and every instance of a referenced
    one (a small file can draw one long path many times over: a reference bomb). A reader
    refuses a document as soon as it crosses one, before spending the memory.
    """

    max_bytes: int = 16 * 1024 * 1024
    max_elements: int = 100_000
    max_depth: int = 64
    max_segments: int = 1_000_000


class DocumentError(ValueError):
    """The document cannot be read: ``where`` names the element (its id, type or line) or
    ``"document"``, ``reason`` says why in words."""

    def __init__(self, where: str, reason: str) -> None:
        super().__init__(f"{where}: {reason}")
        self.where = where
        self.reason = reason

    def __reduce__(self) -> tuple[object, ...]:
        # Crosses the process-pool boundary: pickle the two fields, not the formatted text.
        return (DocumentError, (self.where, self.reason))
