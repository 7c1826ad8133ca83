"""An SVG element's geometric attributes read into numbers and maps, each error a
:class:`DocumentError` naming the element (docs/drawings.md §3).

Lengths are SVG 2 §8.9 "Units" (through :mod:`.svg_units`): a percentage is of the
viewport's width (x, width, cx, rx), height (y, height, cy, ry) or normalised diagonal
``sqrt((w² + h²) / 2)`` (r). ``transform`` is :mod:`.svg_transform`'s grammar; ``points`` is
SVG 2 §10.7's list of numbers; ``viewBox`` and ``preserveAspectRatio`` are SVG 2 §8.5–8.6.
"""

from __future__ import annotations

import math
import re
from typing import Final

from .affine import Affine
from .model import DocumentError
from .svg_parse import Node
from .svg_transform import TransformSyntaxError, parse_transform
from .svg_units import (
    AspectRatio,
    UnitSyntaxError,
    ViewBox,
    parse_aspect_ratio,
    parse_length,
    parse_view_box,
    user_units,
)

__all__ = ["Viewport", "aspect_ratio", "length", "lengths", "number_list", "transform", "view_box"]

#: A viewport's width and height in user units; ``None`` where the document gives none.
Viewport = tuple[float, float] | None

_NUMBER: Final = re.compile(r"[+-]?(?:[0-9]+(?:\.[0-9]*)?|\.[0-9]+)(?:[eE][+-]?[0-9]+)?")
_FINITE: Final = "a finite number"
_AFTER: Final = "a number after ','"
#: The axis each length attribute's percentage refers to: 0 width, 1 height, 2 diagonal.
_AXES: Final = {"x": 0, "cx": 0, "width": 0, "rx": 0, "y": 1, "cy": 1, "height": 1, "ry": 1,
                "r": 2}  # fmt: skip


def length(
    node: Node,
    name: str,
    viewport: Viewport,
    default: str = "0",
    fallback: Node | None = None,
) -> float:
    """Attribute ``name`` in user units: ``fallback``'s when ``node`` has none, ``default``
    when neither has one or it is ``auto``; a percentage of ``viewport`` (module docstring)."""
    text = node.attrib.get(name)
    if text is None and fallback is not None:
        text = fallback.attrib.get(name)
    if text is None or text.strip() == "auto":
        text = default
    reference: float | None = None
    if viewport is not None:
        w, h = viewport
        reference = (w, h, math.sqrt((w * w + h * h) / 2.0))[_AXES[name.rstrip("12")]]
    try:
        return user_units(parse_length(text), reference)
    except UnitSyntaxError as error:
        raise DocumentError(node.source, f"{name}: {error}") from None


def lengths(node: Node, viewport: Viewport, names: str) -> list[float]:
    """The attributes ``names`` (separated by spaces) in user units, absent ones 0."""
    return [length(node, name, viewport) for name in names.split()]


def transform(node: Node) -> Affine:
    """The element's ``transform`` (identity when it has none)."""
    text = node.attrib.get("transform")
    if text is None:
        return Affine()
    try:
        return parse_transform(text)
    except TransformSyntaxError as error:
        raise DocumentError(node.source, f"transform {text!r}: {error}") from None


def view_box(node: Node) -> ViewBox | None:
    text = node.attrib.get("viewBox")
    try:
        return parse_view_box(text) if text is not None else None
    except UnitSyntaxError as error:
        raise DocumentError(node.source, str(error)) from None


def aspect_ratio(node: Node) -> AspectRatio:
    try:
        return parse_aspect_ratio(node.attrib.get("preserveAspectRatio"))
    except UnitSyntaxError as error:
        raise DocumentError(node.source, str(error)) from None


def number_list(node: Node, name: str) -> list[float]:
    """Attribute ``name`` as numbers separated by whitespace and/or one comma (``points``,
    SVG 2 §10.7), strictly; as in path data, a sign or a dot may start the next number
    without a separator."""
    text = node.attrib.get(name, "")
    numbers: list[float] = []
    pos = _skip_wsp(text, 0)
    while pos < len(text):
        match = _NUMBER.match(text, pos)
        if match is None or not math.isfinite(value := float(match.group())):
            raise DocumentError(node.source, f"{name}: at character {pos}: expected {_FINITE}")
        numbers.append(value)
        pos = _skip_wsp(text, match.end())
        if text.startswith(",", pos):
            pos = _skip_wsp(text, pos + 1)
            if pos == len(text):
                raise DocumentError(node.source, f"{name}: at character {pos}: expected {_AFTER}")
    return numbers


def _skip_wsp(text: str, pos: int) -> int:
    while pos < len(text) and text[pos] in " \t\n\r\f":
        pos += 1
    return pos
