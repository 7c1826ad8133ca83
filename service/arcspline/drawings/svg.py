"""SVG documents read into a :class:`Drawing`: every drawn element's subpaths in millimetres,
y up, with what was not drawn said in warnings (docs/drawings.md §3).

The document is parsed into a tree (:mod:`.svg_parse`), then walked without recursion,
composing each element's map (the document frame of :mod:`.svg_units`, every ``transform``,
nested ``svg`` viewports and ``use`` offsets, SVG 2 §8 and §5.6) into one :class:`Affine`
that is applied once to its subpaths (:mod:`.svg_shapes`), exactly
(:func:`transform_subpath`).

Accounting (``Drawing.elements_in == len(elements) + skipped``): each subpath drawn counts
one; each drawable element not drawn (a shape, ``text``, ``image``, ``foreignObject``, an
unknown SVG element, a ``use`` whose reference is missing) counts one in a warning. Not
drawn and said so: ``display:none`` (attribute or ``style``; every drawable element under
it), ``visibility:hidden``/``collapse`` (:mod:`.svg_style`), a transform that collapses the
plane, a shape of zero size, a zero-size nested viewport, and a shape with a number that is
not finite once computed (finite numbers written whose sum, product or map overflows: what
is drawn is always finite; a number written beyond the float range is a syntax error).

Limits (:class:`DocumentLimits`): elements and depth as ``use`` instances expand, and
segments (``max_segments``), counted before each shape's segments are mapped so a reference
bomb is refused before its memory is spent; a shape under a ``use`` is read once and its
subpaths (in its own numbers) reused by every instance. Not drawn and not counted, as they
are not the drawing (:mod:`.svg_elements`): the contents of ``defs``, ``symbol`` (unless
used), ``clipPath``, ``mask``, ``pattern``, ``marker``, gradients, filters, metadata, the
alternatives a ``switch`` does not choose and elements of other namespaces (Inkscape's
``sodipodi:namedview``). Warnings of ``occurrences=0`` are notes on decisions that lose
nothing (a size in %, a clip path not applied, stylesheets not read).
"""

from __future__ import annotations

import math
from collections.abc import Iterator
from typing import Final, NamedTuple

from arcspline.geometry.curves.segments import Subpath

from .affine import Affine, transform_subpath
from .model import DocumentError, DocumentLimits, Drawing, DrawingWarning, Element
from .svg_attributes import Viewport, aspect_ratio, length, transform, view_box
from .svg_elements import (
    NOT_RENDERED,
    SHAPES,
    descendants,
    drawable_count,
    switch_choice,
    unsupported_reason,
)
from .svg_parse import Node, parse_svg
from .svg_shapes import shape_subpaths
from .svg_style import STYLESHEET_NOTE, ignored_notes, is_display_none, is_visible
from .svg_units import DocumentFrame, UnitSyntaxError, document_frame, view_box_map

__all__ = ["read_svg"]

XLINK_HREF: Final = "{http://www.w3.org/1999/xlink}href"
_DISPLAY_NONE: Final = "display:none: not drawn"
_NON_FINITE: Final = "has a non-finite number (its coordinates or transform overflow): not drawn"


def read_svg(
    document: bytes | str,
    *,
    limits: DocumentLimits = DocumentLimits(),  # noqa: B008 - an immutable NamedTuple
    units: str | None = None,
) -> Drawing:
    """The drawing an SVG document holds (module docstring).

    ``units`` (a key of ``MM_PER_UNIT``) overrides the document's scale: one user unit is
    that unit. Raises :class:`DocumentError` naming the element (``path#id`` or
    ``rect (line 12)``) or ``"document"`` for anything that cannot be read.
    """
    root = parse_svg(document, limits)
    if not root.svg or root.tag != "svg":
        raise DocumentError("document", f"the root element is {root.name}, not an svg element")
    frame = _frame(root, units)
    if not _finite_map(frame.to_mm):
        raise DocumentError(root.source, "its size and viewBox give a scale that is not finite")
    walk = _Walk(root, limits)
    for note in frame.notes:
        walk.warnings.add(root.source, note, 0)
    walk.run(frame.to_mm, frame.viewport)
    return Drawing(tuple(walk.elements), walk.warnings.result(), frame.units, walk.elements_in)


def _frame(root: Node, units: str | None) -> DocumentFrame:
    """The outermost ``svg``'s frame; an error names it, or ``"units"`` for an override."""
    get = root.attrib.get
    try:
        return document_frame(
            get("width"), get("height"), get("viewBox"), get("preserveAspectRatio"), units
        )
    except UnitSyntaxError as error:
        raise DocumentError(root.source if units is None else "units", str(error)) from None


class _Warnings:
    """Warnings gathered by (tag, reason): ``element`` names the first occurrence."""

    def __init__(self) -> None:
        self.by_kind: dict[tuple[str, str], DrawingWarning] = {}

    def add(self, source: str, reason: str, occurrences: int = 1) -> None:
        key = (source.split("#")[0].split(" ")[0], reason)
        seen = self.by_kind.get(key)
        if seen is None:
            self.by_kind[key] = DrawingWarning(source, reason, occurrences)
        else:
            self.by_kind[key] = seen._replace(occurrences=seen.occurrences + occurrences)

    def result(self) -> tuple[DrawingWarning, ...]:
        return tuple(self.by_kind.values())


class _Item(NamedTuple):
    """An element to draw: its parent's map to millimetres, the viewport its percentages
    refer to (user units), the inherited visibility, depth, the ``use`` chain above it, and
    for a ``symbol`` or ``svg`` that a ``use`` draws, that ``use`` (it sizes the viewport)."""

    node: Node
    ctm: Affine
    viewport: Viewport
    visible: bool
    depth: int
    chain: tuple[int, ...]
    sizer: Node | None = None


class _Walk:
    """One pass over the tree: ``elements`` drawn, ``warnings`` and the counts of
    elements drawable (``elements_in``) and visited (``visited``, ``use`` expanded)."""

    def __init__(self, root: Node, limits: DocumentLimits) -> None:
        self.root, self.limits = root, limits
        self.elements: list[Element] = []
        self.warnings = _Warnings()
        self.elements_in = 0
        self.visited = 0
        self.segments = 0
        #: Each used shape's subpaths in its own numbers, by (node, viewport), and whether
        #: they are finite: every instance transforms them without reading the shape again.
        self.used_shapes: dict[tuple[int, Viewport], tuple[tuple[Subpath, ...], bool]] = {}
        self.ids: dict[str, Node] = {}
        for node in descendants(root):
            self.ids.setdefault(node.attrib.get("id", ""), node)
            if node.svg and node.tag == "style":
                self.warnings.add(node.source, STYLESHEET_NOTE, 0)

    def run(self, to_mm: Affine, viewport: Viewport) -> None:
        stack = [_Item(self.root, to_mm, viewport, True, 0, ())]
        while stack:
            item = stack.pop()
            self.visited += 1
            self.check_limits(item)
            stack.extend(reversed(list(self.visit(item))))

    def check_limits(self, item: _Item) -> None:
        """The document's limits hold once uses are expanded (a few uses of uses can make
        millions of elements of a small file)."""
        if self.visited > self.limits.max_elements:
            raise DocumentError(
                item.node.source,
                f"more than {self.limits.max_elements} elements once uses are expanded",
            )
        if item.depth > self.limits.max_depth:
            raise DocumentError(
                item.node.source,
                f"nested deeper than {self.limits.max_depth} once uses are expanded",
            )

    def visit(self, item: _Item) -> Iterator[_Item]:
        """Draws or warns about one element; yields its children to visit."""
        node, sizer = item.node, item.sizer
        if not node.svg or (node.tag in NOT_RENDERED and sizer is None):
            return
        if is_display_none(node):
            self.skip(node, _DISPLAY_NONE, instanced=sizer is not None)
            return
        visible = is_visible(node, item.visible)
        for note in ignored_notes(node):
            self.warnings.add(node.source, note, 0)
        inner = item._replace(visible=visible, depth=item.depth + 1, sizer=None)
        if sizer is not None:
            yield from self.viewport(node, sizer, inner)
            return
        reason = unsupported_reason(node)
        if reason is not None:
            self.warn(node, reason)
            return
        if node is self.root and "transform" in node.attrib:
            self.warnings.add(node.source, "the outermost svg's transform is applied inside "
                              "its viewBox (in user units)", 0)  # fmt: skip
        inner = inner._replace(ctm=item.ctm @ transform(node))
        yield from self.contents(node, inner)

    def contents(self, node: Node, item: _Item) -> Iterator[_Item]:
        """What a shape or container draws, ``item`` carrying its own map."""
        if node.tag in SHAPES:
            self.shape(node, item)
        elif node.tag == "use":
            yield from self.use(node, item)
        elif node.tag == "svg" and node is not self.root:
            yield from self.viewport(node, node, item)
        else:
            children = switch_choice(node) if node.tag == "switch" else node.children
            yield from (item._replace(node=c) for c in children)

    # ---- containers

    def use(self, node: Node, item: _Item) -> Iterator[_Item]:
        """The element a ``use`` refers to, moved by the use's x and y (SVG 2 §5.6); a
        ``symbol`` or ``svg`` it refers to is drawn in a viewport the ``use`` sizes."""
        href = node.attrib.get("href", node.attrib.get(XLINK_HREF, "")).strip()
        target = self.ids.get(href[1:]) if href.startswith("#") and len(href) > 1 else None
        if target is None:
            why = "not found" if href.startswith("#") else "not a reference within the document"
            self.warn(node, f"use: the reference {href!r} is {why}: not drawn")
            return
        if id(node) in item.chain:
            raise DocumentError(node.source, f"refers to itself through {href!r} (a cycle)")
        x, y = length(node, "x", item.viewport), length(node, "y", item.viewport)
        moved = item.ctm @ Affine.translate(x, y)
        sizer = node if target.svg and target.tag in ("symbol", "svg") else None
        yield item._replace(node=target, ctm=moved, chain=(*item.chain, id(node)), sizer=sizer)

    def viewport(self, owner: Node, sizer: Node, item: _Item) -> Iterator[_Item]:
        """The children of a nested ``svg`` or a used ``symbol`` in their own viewport
        (SVG 2 §8.2): ``sizer`` (the ``use``, or the ``svg`` itself) gives width and height,
        else ``owner`` does, else 100 %; an ``svg`` is placed at its x and y (a ``use`` has
        already moved by its own; a symbol's x and y are not read)."""
        ctm = item.ctm
        if owner.tag == "svg":
            x, y = length(owner, "x", item.viewport), length(owner, "y", item.viewport)
            ctm = ctm @ Affine.translate(x, y)
        width = length(sizer, "width", item.viewport, "100%", owner)
        height = length(sizer, "height", item.viewport, "100%", owner)
        if width < 0.0 or height < 0.0:
            raise DocumentError(sizer.source, "a viewport's width and height must be >= 0")
        if width == 0.0 or height == 0.0:
            self.skip(owner, "a viewport of zero size: not drawn", instanced=True)
            return
        box, ratio = view_box(owner), aspect_ratio(owner)
        viewport = (width, height)
        if box is not None:
            ctm = ctm @ view_box_map(box, width, height, ratio)
            viewport = (box.width, box.height)
        inner = item._replace(ctm=ctm, viewport=viewport)
        yield from (inner._replace(node=c) for c in owner.children)

    # ---- drawing and accounting

    def shape(self, node: Node, item: _Item) -> None:
        """Draws a shape, or warns about it: hidden, of zero size, with a number that is not
        finite (its own, its map's, or one that overflows once mapped), or collapsed."""
        if not item.visible:
            self.warn(node, "visibility:hidden: not drawn")
            return
        subpaths, finite = self.shape_subpaths(node, item)
        if not subpaths:
            self.warn(node, f"{node.tag} of zero size or without data: not drawn")
            return
        if not (finite and _finite_map(item.ctm)):
            self.warn(node, _NON_FINITE)
            return
        if item.ctm.is_singular():
            self.warn(node, "its transform collapses the plane (a zero scale): not drawn")
            return
        self.count_segments(node, subpaths)
        drawn = [transform_subpath(subpath, item.ctm) for subpath in subpaths]
        if not all(map(_finite_subpath, drawn)):
            self.warn(node, _NON_FINITE)
            return
        self.elements_in += len(drawn)
        self.elements.extend(Element(subpath, node.source) for subpath in drawn)

    def shape_subpaths(self, node: Node, item: _Item) -> tuple[tuple[Subpath, ...], bool]:
        """The shape's subpaths in its own numbers and whether they are all finite; read
        once for a shape under a ``use`` (a reference bomb draws one path many times)."""
        key = (id(node), item.viewport)
        known = self.used_shapes.get(key) if item.chain else None
        if known is None:
            subpaths = shape_subpaths(node, item.viewport)
            known = (subpaths, all(map(_finite_subpath, subpaths)))
            if item.chain:
                self.used_shapes[key] = known
        return known

    def count_segments(self, node: Node, subpaths: tuple[Subpath, ...]) -> None:
        """Refuses the document once its segments, every instance counted, cross the limit,
        before they are mapped (``DocumentLimits.max_segments``)."""
        self.segments += sum(len(subpath.segments) for subpath in subpaths)
        if self.segments > self.limits.max_segments:
            raise DocumentError(
                "document",
                f"more than {self.limits.max_segments} segments, every use of an element "
                f"counted (the limit is crossed at {node.source})",
            )

    def warn(self, node: Node, reason: str) -> None:
        """One drawable element not drawn, for ``reason``."""
        self.elements_in += 1
        self.warnings.add(node.source, reason)

    def skip(self, node: Node, reason: str, instanced: bool = False) -> None:
        """``node`` and everything drawable in it not drawn, for ``reason``; ``instanced``:
        ``node`` is a viewport (a nested or used ``svg``, a used ``symbol``) whose children
        are counted whatever its own kind."""
        count = drawable_count(node, instanced)
        self.visited += count
        if count:
            self.elements_in += count
            self.warnings.add(node.source, reason, count)


def _finite_map(m: Affine) -> bool:
    """The map's numbers and its determinant are finite (a map whose determinant overflows
    cannot be told from a singular one)."""
    return all(map(math.isfinite, m)) and math.isfinite(m.determinant)


def _finite_subpath(subpath: Subpath) -> bool:
    """Every number of every segment (points and arc parameters) is finite."""
    for segment in subpath.segments:
        for value in segment:
            if isinstance(value, tuple):
                if not (math.isfinite(value[0]) and math.isfinite(value[1])):
                    return False
            elif not math.isfinite(value):
                return False
    return True
