"""The presentation properties the reader obeys or reports (docs/drawings.md §3).

A property's value is the element's ``style`` attribute declaration, else its presentation
attribute (SVG 2 §6.6 "Presentation attributes": the ``style`` attribute wins; the last of
several declarations wins). Stylesheets (``style`` elements) are not read.

- ``display:none`` (SVG 2 §6.4.1, not inherited) removes the element and all under it;
- ``visibility`` (SVG 2 §6.4.2) is inherited: ``hidden`` and ``collapse`` hide, ``visible``
  shows again beneath a hidden ancestor, ``inherit`` (or none) takes the parent's;
- ``clip-path``, ``mask`` and markers are not applied: the geometry is drawn whole and a
  note says so.
"""

from __future__ import annotations

from typing import Final

from .svg_parse import Node

__all__ = ["STYLESHEET_NOTE", "ignored_notes", "is_display_none", "is_visible", "presentation"]

HIDDEN_VISIBILITY: Final = frozenset({"hidden", "collapse"})
#: Properties whose effect is not drawn, said in a note (nothing of the element is lost).
_IGNORED: Final = {
    "clip-path": "not applied, the geometry is drawn whole",
    "mask": "not applied, the geometry is drawn whole",
    "marker-start": "markers are not drawn",
    "marker-mid": "markers are not drawn",
    "marker-end": "markers are not drawn",
}
STYLESHEET_NOTE: Final = (
    "stylesheets are not read: their rules (a class with display:none, …) are not applied"
)


def presentation(node: Node, name: str) -> str | None:
    """Property ``name`` as the element sets it (module docstring), lower case; ``None``
    when it does not."""
    value = node.attrib.get(name)
    for declaration in node.attrib.get("style", "").split(";"):
        key, colon, text = declaration.partition(":")
        if colon and key.strip().lower() == name:
            value = text.replace("!important", "")
    return value.strip().lower() if value is not None else None


def is_display_none(node: Node) -> bool:
    return presentation(node, "display") == "none"


def is_visible(node: Node, inherited: bool) -> bool:
    """Whether the element is visible, ``inherited`` being its parent's visibility."""
    value = presentation(node, "visibility")
    if value in (None, "inherit"):
        return inherited
    return value not in HIDDEN_VISIBILITY


def ignored_notes(node: Node) -> list[str]:
    """A note for each property the element sets whose effect is not drawn."""
    return [
        f"{prop}: {why}"
        for prop, why in _IGNORED.items()
        if presentation(node, prop) not in (None, "none")
    ]
