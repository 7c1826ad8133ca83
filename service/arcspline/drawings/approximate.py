"""A drawing approximated (docs/drawings.md §6): its elements in the output unit, tidied,
joined into toolpaths, put in cutting order, and approximated as one path, certified.

Three steps may move the drawing a little before it is fitted, each by a bounded amount:
the reader, where it approximates a curve the core cannot hold (a rational cubic spline,
certified); tidying, which puts control points that lie within a rounding of their end
point on it (``tidy.py``); and joining, which closes gaps up to the join tolerance
(``join.py``). The path is fitted to what is left of the tolerance (:class:`Budget`), so
every output segment stays within ``tolerance`` of the drawing *as given*.
"""

from __future__ import annotations

import math
import re
from collections.abc import Sequence
from typing import Literal, NamedTuple

import numpy as np

from arcspline.geometry import GeometryError, Limits, StrategyName
from arcspline.geometry.curves.segments import Path
from arcspline.geometry.path_spline import PathSpline
from arcspline.geometry.paths import approximate_path
from arcspline.geometry.segment_table import MAX_MAGNITUDE

from .affine import Affine, transform_subpath
from .join import Toolpath, join
from .model import DocumentError, Drawing, DrawingWarning, Element
from .order import order, rapid_length
from .tidy import tidy

OutputUnits = Literal["mm", "inch"]
#: Millimetres per output unit.
MM_PER_OUTPUT_UNIT: dict[str, float] = {"mm": 1.0, "inch": 25.4}
#: The join tolerance when a request gives none, as a fraction of the tolerance: small
#: enough that fitting to the rest costs little, large enough for the rounding of
#: coordinates that CAD programs write (1e-6 mm and less).
JOIN_FRACTION = 0.1
#: How near its end point a control point is put on it, as a fraction of the tolerance.
SNAP_FRACTION = 0.05
#: The share of the tolerance a reader may spend approximating curves it cannot hold.
CURVE_FRACTION = 0.1
#: Most element names a refusal lists for the toolpath it names.
_NAMED_SOURCES = 3
_SUBPATH_FIELD = re.compile(r"path\.subpaths\[(?P<i>\d+)\](?P<rest>.*)")
_SUBPATH_WORDS = re.compile(r"path\.subpaths\[(?P<i>\d+)\]")


class DrawingOptions(NamedTuple):
    """How to cut a drawing: lengths in ``units`` (the output's unit)."""

    tolerance: float
    strategy: StrategyName = "subdivide"
    units: OutputUnits = "mm"
    join_tolerance: float | None = None
    order: bool = True
    choose_start: bool = False

    @property
    def resolved_join_tolerance(self) -> float:
        return (
            self.tolerance * JOIN_FRACTION if self.join_tolerance is None else self.join_tolerance
        )

    @property
    def curve_tolerance_mm(self) -> float:
        """What a reader may spend approximating a curve it cannot hold, in millimetres."""
        return self.tolerance * CURVE_FRACTION * MM_PER_OUTPUT_UNIT[self.units]


class Budget(NamedTuple):
    """How the tolerance is spent: the reader's approximation of curves, the largest move of
    tidying, the largest gap joined, and what is left for the fit (all in the output unit)."""

    tolerance: float
    curve_approximation: float
    snap_move: float
    join_gap: float

    @property
    def fit(self) -> float:
        return self.tolerance - self.curve_approximation - self.snap_move - self.join_gap


class DrawingResult(NamedTuple):
    """A drawing's approximation: one subpath of ``spline`` per toolpath, in cutting order.

    ``warnings`` are the reader's and the pipeline's (elements left out for having no
    length); ``elements_read`` the elements cut. Rapid lengths are from the origin through
    every toolpath in order, in the input's order and as cut.
    """

    spline: PathSpline
    toolpaths: tuple[Toolpath, ...]
    drawing: Drawing
    warnings: tuple[DrawingWarning, ...]
    elements_read: int
    units: OutputUnits
    budget: Budget
    join_tolerance: float
    joins: int
    rapid_before: float
    rapid_after: float


def _in_units(elements: tuple[Element, ...], units: OutputUnits) -> list[Element]:
    if units == "mm":
        return list(elements)
    to_units = Affine.scale(1.0 / MM_PER_OUTPUT_UNIT[units])
    return [Element(transform_subpath(e.subpath, to_units), e.source) for e in elements]


def _nothing_to_cut(drawing: Drawing, warnings: Sequence[DrawingWarning]) -> DocumentError:
    skipped = "; ".join(f"{w.element} ×{w.occurrences}: {w.reason}" for w in warnings[:5])
    return DocumentError(
        "document",
        f"has nothing to cut: {drawing.elements_in} drawable elements, none read"
        + (f" ({skipped})" if skipped else ""),
    )


def _drawn_by(toolpath: Toolpath) -> str:
    sources = toolpath.sources
    names = ", ".join(sources[:_NAMED_SOURCES])
    return names + (" …" if len(sources) > _NAMED_SOURCES else "")


def _named(error: GeometryError, toolpaths: Sequence[Toolpath]) -> GeometryError:
    """The core's refusal of ``path.subpaths[i]…`` (in its field, or in its words) as one of
    toolpath ``i``, naming the elements it was joined from."""
    field, message = error.field, error.message
    match = _SUBPATH_FIELD.fullmatch(field)
    if match is not None:
        i = int(match["i"])
        field = f"toolpaths[{i}]{match['rest']}"
    else:
        found = _SUBPATH_WORDS.search(message)
        if found is None:
            return error
        i = int(found["i"])
        message = _SUBPATH_WORDS.sub(f"toolpaths[{i}]", message, count=1)
    return GeometryError(
        field, f"{message} (drawn by {_drawn_by(toolpaths[i])})", kind=error.kind,
        limit=error.limit,
    )  # fmt: skip


def _check_ends(elements: Sequence[Element]) -> None:
    """Every segment's end points finite and within the core's range (``MAX_MAGNITUDE``)
    before joining and ordering compute with them (their grids take no NaN): a
    :class:`DocumentError` naming the element and the segment. The core checks every other
    number of the joined toolpaths itself, once."""
    counts = [len(e.subpath.segments) for e in elements]
    ends = np.array(
        [(*s.start, *s.end) for e in elements for s in e.subpath.segments], dtype=np.float64
    )
    with np.errstate(invalid="ignore"):
        bad = ~np.all(np.abs(ends) < MAX_MAGNITUDE, axis=1)
    if bad.any():
        k = int(np.argmax(bad))
        i = int(np.searchsorted(np.cumsum(counts), k, side="right"))
        j = k - sum(counts[:i])
        raise DocumentError(
            elements[i].source,
            f"segment {j}: has a number that is not finite or beyond ±{MAX_MAGNITUDE:g}",
        )


def _check(options: DrawingOptions) -> None:
    tolerance, join_tolerance = options.tolerance, options.resolved_join_tolerance
    if not (math.isfinite(tolerance) and tolerance > 0.0):
        raise GeometryError("tolerance", f"must be a finite number > 0, got {tolerance!r}")
    if not (math.isfinite(join_tolerance) and 0.0 <= join_tolerance < tolerance / 2):
        raise GeometryError(
            "join_tolerance",
            f"must lie in [0, tolerance / 2) = [0, {tolerance / 2:g}), got {join_tolerance!r}",
        )


def approximate_drawing(drawing: Drawing, options: DrawingOptions, limits: Limits) -> DrawingResult:
    """The drawing's toolpaths approximated within ``options.tolerance`` of the drawing as
    given (module docstring).

    Raises :class:`DocumentError` for a drawing with nothing to cut or an element the core
    cannot take (a number beyond its range), and
    :class:`GeometryError` for a bad tolerance or join tolerance, and where the core refuses
    (naming ``toolpaths[i]…`` in cutting order and the elements it was joined from).
    """
    _check(options)
    tolerance, units = options.tolerance, options.units
    tidied = tidy(_in_units(drawing.elements, units), tolerance * SNAP_FRACTION)
    warnings = (*drawing.warnings, *tidied.warnings)
    if not tidied.elements:
        raise _nothing_to_cut(drawing, warnings)
    _check_ends(tidied.elements)
    joined = join(tidied.elements, options.resolved_join_tolerance)
    if options.order:
        ordered = order(joined.toolpaths, choose_start=options.choose_start)
        toolpaths = ordered.toolpaths
        before, after = ordered.rapid_before, ordered.rapid_after
    else:
        toolpaths = joined.toolpaths
        before = after = rapid_length(toolpaths)
    budget = Budget(
        tolerance,
        drawing.approximated_mm / MM_PER_OUTPUT_UNIT[units],
        tidied.largest_move,
        joined.largest_gap,
    )
    path = Path(tuple(t.subpath for t in toolpaths))
    try:
        spline = approximate_path(path, budget.fit, options.strategy, limits)
    except GeometryError as error:
        raise _named(error, toolpaths) from None
    return DrawingResult(
        spline, tuple(toolpaths), drawing, warnings, len(tidied.elements), units, budget,
        options.resolved_join_tolerance, joined.joins, before, after,
    )  # fmt: skip
