"""Presentation properties: the style attribute over the presentation attribute, inherited
visibility, and the notes on properties not applied (SVG 2 §6, styling)."""

from __future__ import annotations

from arcspline.drawings.svg_parse import Node
from arcspline.drawings.svg_style import ignored_notes, is_display_none, is_visible, presentation


def _node(**attrib: str) -> Node:
    return Node("rect", True, {k.replace("_", "-"): v for k, v in attrib.items()}, 1)


def test_the_style_attribute_wins_and_its_last_declaration() -> None:
    assert presentation(_node(display="inline"), "display") == "inline"
    assert presentation(_node(display="inline", style="display:NONE"), "display") == "none"
    node = _node(style=" Display : block ; fill:red; display: none !important ")
    assert presentation(node, "display") == "none"
    assert presentation(node, "visibility") is None
    assert presentation(_node(style="color"), "color") is None  # no colon: no declaration


def test_display_none() -> None:
    assert is_display_none(_node(style="display:none"))
    assert not is_display_none(_node(display="inline"))
    assert not is_display_none(_node())


def test_visibility_is_inherited_and_may_be_overridden() -> None:
    for value, parent, expected in [
        (None, True, True), (None, False, False), ("inherit", False, False),
        ("hidden", True, False), ("collapse", True, False), ("visible", False, True),
    ]:  # fmt: skip
        node = _node(visibility=value) if value is not None else _node()
        assert is_visible(node, parent) is expected, (value, parent)


def test_properties_not_applied_are_noted() -> None:
    node = _node(clip_path="url(#c)", mask="none", style="marker-end:url(#m)")
    assert ignored_notes(node) == [
        "clip-path: not applied, the geometry is drawn whole",
        "marker-end: markers are not drawn",
    ]
    assert ignored_notes(_node()) == []
