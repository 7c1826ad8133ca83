"""SVG lengths, viewBox and preserveAspectRatio, and the map from a document's user units to
millimetres with y up (docs/drawings.md §3).

Lengths (CSS Values 3 "absolute lengths", as SVG uses them): ``mm``, ``cm``, ``in``, ``pt``,
``pc``, ``px`` (1/96 in) and unitless numbers (px, i.e. user units); a percentage is of a
reference length given by the caller (the viewport's width, height or normalised diagonal).
Font-relative units (``em``, ``ex``, ``rem``, ``ch``) are refused: with no fonts there is no
size to take them from, and a guess would scale a part silently.

The viewBox map is SVG 1.1 §7.8 / SVG 2 §8.2 "equivalent transform of an SVG viewport": scale
``width/vw``, ``height/vh`` (for an ``align`` other than ``none``, the smaller of the two for
``meet``, the larger for ``slice``), translate by ``-vx·s``, ``-vy·s`` and by the slack for
``xMid``/``xMax`` (half of it, all of it), likewise for y.

The document's map (:func:`document_frame`) takes the outermost ``svg``'s size and viewBox to
millimetres and flips SVG's y-down canvas so that the drawing reads right in a y-up frame,
its origin at the bottom-left corner of the viewport. Decisions where the document does not
say (each reported in :attr:`DocumentFrame.notes`):

- ``width``/``height`` missing, ``auto`` (100 %, SVG 2 §5.1.2) or in ``%`` (a share of a
  viewport the document does not have, as in vpype's ``percent_size_viewbox.svg``): with a
  viewBox, a size known on one side gives the other by the viewBox's ratio, as for an SVG
  image's intrinsic size (CSS Images 3 §4); with neither known the viewBox's size is taken
  in px (one user unit = 1 px = 1/96 in).
- No viewBox: one user unit is 1 px (SVG's initial user space); without a height as well,
  the flip is about the canvas's top edge (y = 0), the only line the document places.
- A ``units`` override (a key of ``MM_PER_UNIT``): one user unit is that unit, whatever the
  size and viewBox say (drawings' declared units can be wrong); the origin stays the
  viewport's bottom-left corner (the viewBox's, when there is one).
"""

from __future__ import annotations

import math
import re
from typing import Final, NamedTuple

from .affine import Affine
from .model import MM_PER_UNIT

__all__ = [
    "AspectRatio",
    "DocumentFrame",
    "Length",
    "UnitSyntaxError",
    "ViewBox",
    "document_frame",
    "parse_aspect_ratio",
    "parse_length",
    "parse_view_box",
    "user_units",
    "view_box_map",
]

PX_MM: Final = MM_PER_UNIT["px"]
_NUMBER: Final = r"[+-]?(?:[0-9]+(?:\.[0-9]*)?|\.[0-9]+)(?:[eE][+-]?[0-9]+)?"
_LENGTH: Final = re.compile(rf"[ \t\n\r\f]*({_NUMBER})([A-Za-z]*|%)[ \t\n\r\f]*")
_LIST_SEPARATOR: Final = re.compile(r"[ \t\n\r\f]*,[ \t\n\r\f]*|[ \t\n\r\f]+")
_ABSOLUTE: Final = frozenset({"px", "mm", "cm", "in", "pt", "pc"})
_FONT_RELATIVE: Final = frozenset({"em", "ex", "rem", "ch"})
_ALIGNS: Final = frozenset(
    {"none"} | {f"x{x}Y{y}" for x in ("Min", "Mid", "Max") for y in ("Min", "Mid", "Max")}
)


class UnitSyntaxError(ValueError):
    """A length, viewBox or preserveAspectRatio value that cannot be read, and why."""


class Length(NamedTuple):
    """A number and its unit: ``""`` (user units, i.e. px), an absolute unit, or ``"%"``."""

    value: float
    unit: str

    @property
    def is_percent(self) -> bool:
        return self.unit == "%"


_HUNDRED_PERCENT: Final = Length(100.0, "%")


def parse_length(text: str) -> Length:
    """``"10mm"`` → ``Length(10.0, "mm")``; units are case-insensitive as in CSS."""
    match = _LENGTH.fullmatch(text)
    if match is None:
        raise UnitSyntaxError(f"{text!r} is not a length (a number with an optional unit)")
    value, unit = float(match.group(1)), match.group(2).lower()
    if not math.isfinite(value):
        raise UnitSyntaxError(f"{text!r} is not a finite length")
    if unit in _FONT_RELATIVE:
        raise UnitSyntaxError(f"{text!r}: font-relative units ({unit}) are not supported")
    if unit not in _ABSOLUTE and unit not in ("", "%"):
        raise UnitSyntaxError(f"{text!r}: unknown unit {unit!r}")
    return Length(value, unit)


def user_units(length: Length, reference: float | None) -> float:
    """The length in user units (px): ``reference`` is what 100 % is, ``None`` if unknown."""
    if length.is_percent:
        if reference is None:
            raise UnitSyntaxError(
                f"{length.value:g}% of an unknown viewport (the document has no size or viewBox)"
            )
        return length.value / 100.0 * reference
    if length.unit in ("", "px"):
        return length.value
    return length.value * (MM_PER_UNIT[length.unit] / PX_MM)


def _millimetres(length: Length) -> float:
    return length.value * MM_PER_UNIT[length.unit or "px"]


class ViewBox(NamedTuple):
    x: float
    y: float
    width: float
    height: float


def parse_view_box(text: str) -> ViewBox:
    """Four numbers separated by whitespace and/or a comma; width and height must be > 0
    (SVG: zero disables rendering, negative is an error; either way nothing can be drawn)."""
    parts = _LIST_SEPARATOR.split(text.strip(" \t\n\r\f"))
    if len(parts) != 4 or not all(re.fullmatch(_NUMBER, p) for p in parts):
        raise UnitSyntaxError(f"viewBox {text!r} is not four numbers")
    x, y, width, height = (float(p) for p in parts)
    if not all(math.isfinite(v) for v in (x, y, width, height)):
        raise UnitSyntaxError(f"viewBox {text!r} has a number that is not finite")
    if not (width > 0.0 and height > 0.0):
        raise UnitSyntaxError(f"viewBox {text!r}: width and height must be > 0")
    return ViewBox(x, y, width, height)


class AspectRatio(NamedTuple):
    """``preserveAspectRatio``: ``align`` (``none`` or ``xMidYMid`` …) and ``slice``."""

    align: str = "xMidYMid"
    slice: bool = False


def parse_aspect_ratio(text: str | None) -> AspectRatio:
    """``"[defer] <align> [meet | slice]"`` (SVG 2 §8.4); ``None`` gives the default."""
    if text is None:
        return AspectRatio()
    words = text.split()
    if words[:1] == ["defer"]:  # only meaningful on images; ignored as SVG says
        words = words[1:]
    if not 1 <= len(words) <= 2 or words[0] not in _ALIGNS:
        raise UnitSyntaxError(f"preserveAspectRatio {text!r}: expected <align> [meet|slice]")
    if len(words) == 2 and words[1] not in ("meet", "slice"):
        raise UnitSyntaxError(f"preserveAspectRatio {text!r}: expected meet or slice")
    return AspectRatio(words[0], words[1:] == ["slice"])


def view_box_map(view_box: ViewBox, width: float, height: float, ratio: AspectRatio) -> Affine:
    """The map from viewBox coordinates to a viewport ``width`` × ``height`` whose top-left
    corner is the origin (module docstring; y down, as both are)."""
    sx, sy = width / view_box.width, height / view_box.height
    if ratio.align != "none":
        sx = sy = max(sx, sy) if ratio.slice else min(sx, sy)
    tx, ty = -view_box.x * sx, -view_box.y * sy
    slack_x, slack_y = width - view_box.width * sx, height - view_box.height * sy
    share = {"Min": 0.0, "Mid": 0.5, "Max": 1.0}
    if ratio.align != "none":
        tx += share[ratio.align[1:4]] * slack_x
        ty += share[ratio.align[5:8]] * slack_y
    return Affine(sx, 0.0, 0.0, sy, tx, ty)


class DocumentFrame(NamedTuple):
    """The outermost ``svg``'s frame: ``to_mm`` takes its user units to millimetres, y up;
    ``viewport`` is the viewport's size in user units (``None`` where unknown), what
    percentages of its children refer to; ``units`` the unit the document declares (or the
    override); ``notes`` the decisions taken where the document left room."""

    to_mm: Affine
    viewport: tuple[float, float] | None
    units: str
    notes: tuple[str, ...]


def _declared(width: Length | None, height: Length | None) -> str:
    for length in (width, height):
        if length is not None and not length.is_percent:
            return length.unit or "px"
    return "px"


def _size(text: str | None) -> Length | None:
    """The outermost ``svg``'s width or height; ``auto`` is 100 % there (SVG 2 §5.1.2)."""
    if text is None:
        return None
    return _HUNDRED_PERCENT if text.strip(" \t\n\r\f") == "auto" else parse_length(text)


def document_frame(
    width: str | None,
    height: str | None,
    view_box: str | None,
    aspect_ratio: str | None,
    units: str | None = None,
) -> DocumentFrame:
    """The frame of a document whose outermost ``svg`` has these attributes (module
    docstring). Raises :class:`UnitSyntaxError` for a value that cannot be read, or a size
    of zero or less (nothing would be drawn)."""
    w, h = _size(width), _size(height)
    for name, length in (("width", w), ("height", h)):
        if length is not None and not length.value > 0.0:
            raise UnitSyntaxError(f"{name} {length.value:g}{length.unit} must be > 0")
    box = parse_view_box(view_box) if view_box is not None else None
    ratio = parse_aspect_ratio(aspect_ratio)
    width_mm = _millimetres(w) if w is not None and not w.is_percent else None
    height_mm = _millimetres(h) if h is not None and not h.is_percent else None
    notes: list[str] = []
    unknown = [n for n, v in (("width", width_mm), ("height", height_mm)) if v is None]
    if box is not None:
        if width_mm is None and height_mm is None:
            width_mm, height_mm = box.width * PX_MM, box.height * PX_MM
            notes.append(
                f"{' and '.join(unknown)} missing or in % of an unknown viewport: "
                "the viewBox's size is taken in px (1/96 in)"
            )
        elif width_mm is None and height_mm is not None:
            width_mm = height_mm * box.width / box.height
            notes.append("width missing or in %: taken from the height by the viewBox's ratio")
        elif height_mm is None and width_mm is not None:
            height_mm = width_mm * box.height / box.width
            notes.append("height missing or in %: taken from the width by the viewBox's ratio")
    elif height_mm is None:
        notes.append("no viewBox and no height: y is flipped about the canvas's top edge (y = 0)")
    viewport = (box.width, box.height) if box is not None else None
    if box is None and width_mm is not None and height_mm is not None:
        viewport = (width_mm / PX_MM, height_mm / PX_MM)
    if units is not None:
        return _overridden(units, box, height_mm, viewport, notes)
    declared = _declared(w, h)
    if box is None or width_mm is None or height_mm is None:
        top_mm = height_mm if height_mm is not None else 0.0
        to_mm = Affine(PX_MM, 0.0, 0.0, -PX_MM, 0.0, top_mm)
        return DocumentFrame(to_mm, viewport, declared, tuple(notes))
    inner = view_box_map(box, width_mm, height_mm, ratio)
    to_mm = Affine(inner.a, 0.0, 0.0, -inner.d, inner.e, height_mm - inner.f)
    return DocumentFrame(to_mm, viewport, declared, tuple(notes))


def _overridden(
    units: str,
    box: ViewBox | None,
    height_mm: float | None,
    viewport: tuple[float, float] | None,
    notes: list[str],
) -> DocumentFrame:
    if units not in MM_PER_UNIT:
        raise UnitSyntaxError(f"units {units!r}: expected one of {', '.join(MM_PER_UNIT)}")
    k = MM_PER_UNIT[units]
    notes.append(f"units overridden: one user unit is 1 {units}")
    if box is not None:
        to_mm = Affine(k, 0.0, 0.0, -k, -box.x * k, (box.y + box.height) * k)
        return DocumentFrame(to_mm, viewport, units, tuple(notes))
    top = height_mm / PX_MM if height_mm is not None else 0.0  # the height in user units (px)
    return DocumentFrame(Affine(k, 0.0, 0.0, -k, 0.0, top * k), viewport, units, tuple(notes))
