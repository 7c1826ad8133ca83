"""What the reader does with each kind of SVG element (docs/drawings.md §3): shapes are
drawn, containers are walked, unsupported graphics are warned about, and resources,
metadata and animation are not part of the drawing (SVG 2 §1.6 "Element categories")."""

from __future__ import annotations

from collections.abc import Iterator
from typing import Final

from .svg_parse import Node

__all__ = [
    "CONTAINERS",
    "NOT_RENDERED",
    "SHAPES",
    "descendants",
    "drawable_count",
    "switch_choice",
    "unsupported_reason",
]

#: Basic shapes (SVG 2 §10) and path (§9): each is drawn.
SHAPES: Final = frozenset({"path", "line", "polyline", "polygon", "rect", "circle", "ellipse"})
CONTAINERS: Final = frozenset({"g", "a", "switch", "svg", "use"})
#: Graphics that cannot be cut as drawn: each one is a warning.
UNSUPPORTED: Final = {
    "text": "text is not drawn (convert it to paths)",
    "image": "images are not drawn",
    "foreignObject": "foreign objects are not drawn",
    "video": "videos are not drawn",
    "audio": "audio is not drawn",
    "canvas": "canvases are not drawn",
    "iframe": "iframes are not drawn",
    "mesh": "meshes are not drawn",
}
#: Elements that are not part of the drawing as rendered (resources, metadata, animation).
NOT_RENDERED: Final = frozenset(
    {
        "defs", "symbol", "clipPath", "mask", "pattern", "marker", "linearGradient",
        "radialGradient", "meshgradient", "solidcolor", "stop", "filter", "style", "script",
        "title", "desc", "metadata", "view", "cursor", "font", "font-face", "glyph",
        "missing-glyph", "hkern", "vkern", "color-profile", "animate", "animateMotion",
        "animateTransform", "animateColor", "set", "mpath", "discard", "tref", "tspan",
        "textPath", "altGlyphDef",
    }
)  # fmt: skip
#: Conditional processing attributes (SVG 2 §5.8.1), false for every value here.
_CONDITIONS: Final = ("requiredExtensions", "requiredFeatures", "systemLanguage")


def unsupported_reason(node: Node) -> str | None:
    """Why an SVG element that is rendered (not in NOT_RENDERED) is not drawn, or ``None``
    for a shape or a container."""
    if node.tag in UNSUPPORTED:
        return UNSUPPORTED[node.tag]
    if node.tag in SHAPES or node.tag in CONTAINERS:
        return None
    return f"unknown element {node.tag}: not drawn"


def switch_choice(node: Node) -> list[Node]:
    """A ``switch`` draws its first child whose conditions hold (SVG 2 §5.8.2); ours hold
    for none of the conditional attributes (no extensions, features or languages are
    claimed)."""
    for child in node.children:
        if child.svg and not any(c in child.attrib for c in _CONDITIONS):
            return [child]
    return []


def descendants(node: Node) -> Iterator[Node]:
    """``node`` and every element under it, in document order."""
    stack = [node]
    while stack:
        n = stack.pop()
        yield n
        stack.extend(reversed(n.children))


def drawable_count(node: Node, instanced: bool = False) -> int:
    """How many elements under ``node`` (itself included) would have been drawn or warned
    about: shapes, unsupported graphics and uses, outside resources, other namespaces and
    the alternatives a ``switch`` does not choose. ``instanced``: ``node`` is a ``symbol``
    (or ``svg``) a ``use`` draws, so its own category does not hide its children."""
    count = 0
    stack = list(node.children) if instanced else [node]
    while stack:
        n = stack.pop()
        if not n.svg or n.tag in NOT_RENDERED:
            continue
        if n.tag in SHAPES or n.tag == "use" or n.tag not in CONTAINERS:
            count += 1
        else:
            stack.extend(switch_choice(n) if n.tag == "switch" else n.children)
    return count
