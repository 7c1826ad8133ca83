"""An arc spline as an SVG drawing: the toolpaths as geometry, in real units.

Not the preview (``svg.py``, a picture for a person): this document is for other programs
(a laser cutter's software, Inkscape, a plotter, our own reader), so it holds nothing but the
toolpaths. Each part is one ``<path id="toolpath-k">`` (``k`` from 1, cutting order) of
``M``, ``L`` and ``A`` commands (and ``Z`` when the part ends exactly where it starts),
stroked, not filled.

* Units: ``width`` and ``height`` are in ``mm`` or ``in`` (``units``), and the ``viewBox`` has
  the same size in user units, so one user unit is one drawing unit.
* The y axis: SVG's points down, the drawing's up. The document's coordinates are
  ``(x, −y)`` — negation is exact in floating point, so nothing is lost — and the viewBox
  is placed around them; an arc's sweep flag is therefore 0 for an anticlockwise arc
  (SVG 1.1 §9.3.8: flag 1 is the direction of increasing angle in the path's numbers).
  No ``transform`` is used: programs that ignore transforms still read the right shape.
* Numbers are Python's ``repr`` of the doubles, so a reader gets the spline's own end points
  and radii back exactly, and the centre (which SVG does not carry: F.6.5 of SVG 1.1
  recomputes it from the end points and the radius) within a few ulps of the radius
  divided by ``|cos(sweep/2)|``. That factor is why an arc within
  :data:`HALF_CIRCLE_MARGIN` of a half circle is written as its two halves (split at its
  middle): the endpoint form cannot place the centre of a half circle to better than
  ``√ε`` of its radius.

See docs/drawings.md §7.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Literal, get_args

from arcspline.geometry import GeometryError
from arcspline.geometry.spline import ArcSpline

from .extents import check_finite, extents
from .part import Part

MEDIA_TYPE = "image/svg+xml"
Units = Literal["mm", "inch"]
UNITS: tuple[str, ...] = get_args(Units)
#: The SVG length unit of each drawing unit.
SVG_UNIT = {"mm": "mm", "inch": "in"}
#: Room around the drawing, as a fraction of its larger side.
MARGIN_FRACTION = 0.02
#: The stroke: 0.1 mm (the hairline laser cutters expect), or less on a tiny drawing.
STROKE_MM = 0.1
MM_PER_UNIT = {"mm": 1.0, "inch": 25.4}
#: ``|cos(sweep/2)|`` below which an arc is written as two halves (see the module docstring).
HALF_CIRCLE_MARGIN = 1e-6


@dataclass(frozen=True, slots=True)
class SvgDocumentOptions:
    """How to write the document; validated on construction (raises
    :class:`GeometryError` naming the option). The spline's coordinates are taken to be in
    ``units`` already."""

    units: Units = "mm"

    def __post_init__(self) -> None:
        if self.units not in UNITS:
            raise GeometryError("units", f"must be one of {', '.join(UNITS)}, got {self.units!r}")


def _flip(y: float) -> float:
    """The document's coordinate of the drawing's ``y``: ``−y`` exactly (``0.0 − y``, so
    that zero stays ``0.0`` rather than ``-0.0``)."""
    return 0.0 - y


def _arc(x: float, y: float, r: float, sweep_rad: float) -> str:
    """The ``A`` command to ``(x, y)`` (drawing coordinates) of an arc of radius ``r``."""
    large = 1 if abs(sweep_rad) > math.pi else 0
    flag = 0 if sweep_rad > 0.0 else 1  # the document's y is the drawing's −y
    return f"A{r!r} {r!r} 0 {large} {flag} {x!r} {_flip(y)!r}"


def path_data(spline: ArcSpline) -> str:
    """The part's path data, in the document's coordinates ``(x, −y)``."""
    c = spline.columns
    if len(c) == 0:
        return ""
    starts, ends, centres = c.start.tolist(), c.end.tolist(), c.center.tolist()
    x0, y0 = starts[0]
    out = [f"M{x0!r} {_flip(y0)!r}"]
    radii, sweeps, angles = c.radius.tolist(), c.sweep_rad.tolist(), c.start_angle_rad.tolist()
    is_arc = c.is_arc.tolist()
    for i, (x, y) in enumerate(ends):
        if not is_arc[i]:
            out.append(f"L{x!r} {_flip(y)!r}")
            continue
        r, sweep = radii[i], sweeps[i]
        if abs(math.cos(sweep / 2.0)) < HALF_CIRCLE_MARGIN:
            (cx, cy), middle_rad = centres[i], angles[i] + sweep / 2.0
            mx, my = cx + r * math.cos(middle_rad), cy + r * math.sin(middle_rad)
            out.append(_arc(mx, my, r, sweep / 2.0))
            sweep /= 2.0
        out.append(_arc(x, y, r, sweep))
    if starts[0] == ends[-1] and len(c) > 1:
        out.append("Z")
    return " ".join(out)


def write_svg_document(parts: Sequence[Part], options: SvgDocumentOptions) -> str:
    """The document described in the module docstring."""
    splines = [spline for spline, _ in parts]
    check_finite(splines, "SVG")
    low, high = extents(splines)
    size = float(max(high[0] - low[0], high[1] - low[1]))
    margin = MARGIN_FRACTION * size if size > 0.0 else 1.0
    x0, y0 = float(low[0]) - margin, -float(high[1]) - margin
    width, height = float(high[0] - low[0]) + 2 * margin, float(high[1] - low[1]) + 2 * margin
    if not all(map(math.isfinite, (x0, y0, width, height))):
        raise GeometryError(
            "parts", "the drawing is too large for its size to be written", kind="precision"
        )
    stroke = min(STROKE_MM / MM_PER_UNIT[options.units], max(size, margin) / 200.0)
    unit = SVG_UNIT[options.units]
    out = [
        '<?xml version="1.0" encoding="UTF-8"?>',
        f'<svg xmlns="http://www.w3.org/2000/svg" version="1.1" '
        f'width="{width!r}{unit}" height="{height!r}{unit}" '
        f'viewBox="{x0!r} {y0!r} {width!r} {height!r}">',
        f"<desc>arcspline: {len(splines)} toolpaths in {options.units}, cutting order; "
        "document y = drawing -y</desc>",
        f'<g fill="none" stroke="black" stroke-width="{stroke!r}" '
        'stroke-linecap="round" stroke-linejoin="round">',
    ]
    for k, spline in enumerate(splines, start=1):
        if len(spline):
            out.append(f'<path id="toolpath-{k}" d="{path_data(spline)}"/>')
    out.extend(["</g>", "</svg>", ""])
    return "\n".join(out)


class SvgDocumentWriter:
    """The SVG drawing as an output writer (options: :class:`SvgDocumentOptions`, or None
    for the defaults)."""

    name = "svg-document"
    media_type = MEDIA_TYPE

    def write(self, parts: Sequence[Part], options: SvgDocumentOptions | None = None) -> str:
        return write_svg_document(parts, options if options is not None else SvgDocumentOptions())


WRITER = SvgDocumentWriter()
