"""Geometric attributes read into user units and maps, errors naming the element (SVG 2 §8:
a percentage of the viewport's width, height or normalised diagonal)."""

from __future__ import annotations

import math

import pytest

from arcspline.drawings.model import DocumentError
from arcspline.drawings.svg_attributes import (
    aspect_ratio,
    length,
    lengths,
    number_list,
    transform,
    view_box,
)
from arcspline.drawings.svg_parse import Node
from arcspline.drawings.svg_units import AspectRatio, ViewBox


def _node(**attrib: str) -> Node:
    return Node("rect", True, attrib, 3)


def test_percentages_refer_to_their_axis() -> None:
    node = _node(x="10%", y="10%", r="10%", rx="1in", cy="auto")
    viewport = (300.0, 400.0)  # diagonal sqrt((300² + 400²) / 2) = 353.55…
    assert length(node, "x", viewport) == pytest.approx(30.0)
    assert length(node, "y", viewport) == pytest.approx(40.0)
    assert length(node, "r", viewport) == pytest.approx(0.1 * math.sqrt(125_000.0))
    assert lengths(node, viewport, "rx cy width") == [96.0, 0.0, 0.0]
    with pytest.raises(DocumentError) as caught:
        length(node, "x", None)
    assert (caught.value.where, "unknown viewport" in caught.value.reason) == (
        "rect (line 3)",
        True,
    )


def test_a_fallback_element_and_a_default() -> None:
    use, symbol = _node(width="5"), _node(width="7", height="8")
    assert length(use, "width", None, "100%", symbol) == 5.0
    assert length(use, "height", None, "100%", symbol) == 8.0
    assert length(_node(), "height", (10.0, 20.0), "100%", _node()) == 20.0


def test_transform_view_box_and_aspect_ratio() -> None:
    node = _node(transform="translate(1 2)", viewBox="0 0 4 5", preserveAspectRatio="none")
    assert transform(node).apply((0.0, 0.0)) == (1.0, 2.0)  # type: ignore[arg-type]
    assert transform(_node()).apply((3.0, 4.0)) == (3.0, 4.0)  # type: ignore[arg-type]
    assert view_box(node) == ViewBox(0.0, 0.0, 4.0, 5.0)
    assert view_box(_node()) is None
    assert aspect_ratio(node) == AspectRatio("none", False)
    for bad in (_node(id="b", transform="skewX()"), _node(id="b", viewBox="0 0 1"),
                _node(id="b", preserveAspectRatio="middle")):  # fmt: skip
        with pytest.raises(DocumentError) as caught:
            transform(bad), view_box(bad), aspect_ratio(bad)
        assert caught.value.where == "rect#b"


def test_number_list() -> None:
    assert number_list(_node(points=" 1,2 3-4e1 .5.5 "), "points") == [1, 2, 3, -40, 0.5, 0.5]
    assert number_list(_node(), "points") == []
    for text, offset in (("1,,2", 2), ("1 2,", 4), (",1", 0), ("1 1e999", 2)):
        with pytest.raises(DocumentError, match=f"points: at character {offset}:"):
            number_list(_node(points=text), "points")
