"""DXF documents in: the modelspace's curves as our segments, in millimetres (docs/drawings.md
§4).

The document is loaded and its units and layers taken (``dxf_load.py``); the modelspace is
walked here, through block references, each entity read natively (``dxf_entities.py``).
Every map — an entity's object coordinate system, each INSERT's placement
(``dxf_placement.py``), and the units — is one of our :class:`Affine` maps, composed and
applied once per entity by :func:`transform_subpath`, so arcs stay exact under mirror and
non-uniform scale.

Nothing is lost silently: every entity reached (through block references, and in paper
space) is an element or counted in a warning. Warnings that skip nothing (units assumed, a
projection taken, a clip ignored, a spline approximated) carry ``occurrences = 0`` and say
their count in words.
"""

from __future__ import annotations

import math
import sys
from collections import Counter
from collections.abc import Sequence
from typing import TYPE_CHECKING, Any, NamedTuple

from ezdxf.document import Drawing as EzDrawing
from ezdxf.xclip import XClip

from arcspline.geometry.curves.segments import Subpath

from .affine import Affine, SingularMapError, transform_subpath
from .dxf_entities import (
    NON_FINITE,
    NOT_DRAWN,
    Shape,
    SkipError,
    entity_shape,
    finite_entity,
    finite_numbers,
)
from .dxf_load import document_units, load, selected_layers
from .dxf_placement import Placement, array_offsets, insert_placement, stretch
from .model import DocumentError, DocumentLimits, Drawing, DrawingWarning, Element

if TYPE_CHECKING:
    from ezdxf.entities.dxfgfx import DXFGraphic
    from ezdxf.layouts.blocklayout import BlockLayout

#: Units in the last place allowed for the rounding of mapping approximating cubics to
#: millimetres, times their coordinate scale (added to the certified distance).
MAPPING_ULPS = 16.0


class _Context(NamedTuple):
    """Where an entity is reached: the map of its block's coordinates to millimetres, the
    chain of block names (outermost first), the layer a layer-0 entity inherits, and why the
    whole reference is hidden (a frozen layer), if it is."""

    matrix: Affine
    blocks: tuple[str, ...] = ()
    insert_layer: str | None = None
    hidden: str | None = None


class _Reference(NamedTuple):
    """A block reference ready to walk: its block, the context of its entities (their matrix
    set per array offset), its placement and its array offsets."""

    block: BlockLayout
    inner: _Context
    placement: Placement
    offsets: list[Affine]


def read_dxf(
    document: bytes,
    *,
    limits: DocumentLimits = DocumentLimits(),  # noqa: B008 - an immutable NamedTuple
    units: str | None = None,
    layers: Sequence[str] | None = None,
    curve_tolerance_mm: float | None = None,
) -> Drawing:
    """The modelspace of a DXF ``document`` as elements in millimetres, y up (module
    docstring). ``units`` (a key of ``MM_PER_UNIT``) overrides the document's ``$INSUNITS``;
    ``layers`` keeps only entities on those layers; ``curve_tolerance_mm`` lets a rational
    cubic spline be approximated by cubics within that distance (certified, reported in
    ``Drawing.approximated_mm``), else it is skipped. Raises :class:`DocumentError` for a
    document that is not DXF, too large, too many elements, blocks nested too deep or
    referring to themselves, an unknown unit or layer, a tolerance that is not > 0."""
    if len(document) > limits.max_bytes:
        raise DocumentError(
            "document", f"is {len(document)} bytes, more than the limit of {limits.max_bytes}"
        )
    if curve_tolerance_mm is not None and not (
        math.isfinite(curve_tolerance_mm) and curve_tolerance_mm > 0.0
    ):
        raise DocumentError(
            "curve_tolerance_mm", f"{curve_tolerance_mm!r} is not a number of mm > 0"
        )
    doc, has_header = load(document)
    taken = document_units(doc, has_header, units)
    reader = _Reader(doc, limits, selected_layers(doc, layers), curve_tolerance_mm)
    if taken.note is not None:
        reader.note("document", taken.note)
    reader.modelspace(Affine.scale(taken.mm_per_unit))
    reader.paperspace()
    return Drawing(
        tuple(reader.elements), reader.warnings(), taken.name, reader.count, reader.approximated_mm
    )


def _entities(count: int) -> str:
    return f"{count} entity" if count == 1 else f"{count} entities"


def _up(value: float) -> str:
    """``value`` to 3 significant digits, rounded up (a bound must not be shown smaller)."""
    if value <= 0.0:
        return "0"
    step = 10.0 ** (math.floor(math.log10(value)) - 2)
    return f"{math.ceil(value / step) * step:.3g}"


class _Reader:
    """Walks the modelspace through block references, gathering elements and warnings."""

    def __init__(
        self,
        doc: EzDrawing,
        limits: DocumentLimits,
        layers: frozenset[str] | None,
        curve_tolerance_mm: float | None,
    ) -> None:
        self.doc, self.limits, self.layers = doc, limits, layers
        self.curve_tolerance_mm = curve_tolerance_mm
        self.elements: list[Element] = []
        self.skipped: Counter[tuple[str, str]] = Counter()
        self.notes: Counter[tuple[str, str]] = Counter()
        self.count = 0
        self.segments = 0
        self.references = 0
        self.approximated_mm = 0.0

    def note(self, element: str, reason: str) -> None:
        self.notes[(element, reason)] += 1

    def skip(self, element: str, reason: str) -> None:
        self.skipped[(element, reason)] += 1

    def warnings(self) -> tuple[DrawingWarning, ...]:
        skipped = [DrawingWarning(e, r, n) for (e, r), n in self.skipped.items()]
        noted = [
            DrawingWarning(e, r if e == "document" else f"{r} ({_entities(n)})", 0)
            for (e, r), n in self.notes.items()
        ]
        return (*skipped, *noted)

    def modelspace(self, units: Affine) -> None:
        context = _Context(units)
        for entity in self.doc.modelspace():
            self.visit(entity, context)

    def paperspace(self) -> None:
        for layout in self.doc.layouts:
            if layout.is_any_paperspace:
                for _entity in layout:
                    self.reach()
                    self.skip("paper space", "paper space layouts are not read")

    def reach(self) -> None:
        self.count += 1
        if self.count > self.limits.max_elements:
            raise DocumentError("document", f"has more than {self.limits.max_elements} elements")

    def layer_hides(self, entity: DXFGraphic, context: _Context) -> tuple[str | None, str]:
        """Why the entity's layer hides it (frozen, off, not selected), and that layer."""
        layer = str(entity.dxf.layer)
        if context.blocks and layer == "0" and context.insert_layer is not None:
            layer = context.insert_layer
        entry = self.doc.layers.get(layer) if self.doc.layers.has_entry(layer) else None
        if entry is not None and entry.is_frozen():
            return "on a frozen layer", layer
        if entry is not None and entry.is_off():
            return "on a layer turned off", layer
        return None, layer

    def visit(self, entity: DXFGraphic, context: _Context) -> None:
        """One entity reached: drawn, or counted in a warning, whatever it holds. An
        exception from ezdxf or from our reading of it becomes a warning for that entity
        alone (its class and message, briefly), so that the accounting stays exact."""
        if entity.dxftype() == "INSERT":
            self.insert(entity, context)
            return
        self.reach()
        kind = entity.dxftype()
        try:
            self.entity(entity, kind, context)
        except SkipError as why:
            self.skip(kind, str(why))
        except (MemoryError, DocumentError):  # the whole document's limits, not this entity's
            raise
        except Exception as exc:  # hostile input: any failure is this entity's
            self.skip(kind, _unexpected(exc))

    def entity(self, entity: DXFGraphic, kind: str, context: _Context) -> None:
        """A drawable entity (not a block reference), or :class:`SkipError` saying why not."""
        hidden, layer = self.layer_hides(entity, context)
        hidden = context.hidden or hidden
        if hidden is not None:
            raise SkipError(hidden)
        if self.layers is not None and layer.upper() not in self.layers:
            raise SkipError("not on a selected layer")
        if entity.dxf.get("invisible", 0):
            raise SkipError("is invisible")
        if kind in NOT_DRAWN:
            raise SkipError(NOT_DRAWN[kind])
        self.draw(entity, kind, context)

    def draw(self, entity: Any, kind: str, context: _Context) -> None:
        """The entity as an element in millimetres; a rational cubic spline is approximated
        within the tolerance taken back to its own units by the map's largest stretch, so
        that the mapped distance is within it in millimetres."""
        mm_per_own = stretch(context.matrix)
        tolerance = self.curve_tolerance_mm
        if tolerance is not None and mm_per_own > 0.0:
            tolerance /= mm_per_own
        shape = entity_shape(entity, kind, tolerance)
        # Counted before mapping, every block instance again: a block of a long polyline
        # inserted many times is refused before it is drawn.
        self.segments += len(shape.subpath.segments)
        if self.segments > self.limits.max_segments:
            raise DocumentError(
                "document",
                f"has more than {self.limits.max_segments} segments, every block reference "
                f"counted (the limit is crossed at {self.source(entity, kind, context)})",
            )
        for note in shape.notes:
            self.note(kind, note)
        try:
            mapped = transform_subpath(shape.subpath, context.matrix @ shape.plane)
        except SingularMapError as exc:
            raise SkipError("collapses to a line or a point in the XY plane") from exc
        if not finite_numbers(mapped.segments):
            raise SkipError(f"{NON_FINITE} once placed and scaled (beyond double precision)")
        if shape.tilted:
            self.note(kind, "is not in a plane parallel to XY: its projection onto XY was drawn")
        if shape.approximated > 0.0 or shape.approximating:
            self.approximated(shape, mapped, mm_per_own)
        self.elements.append(Element(mapped, self.source(entity, kind, context)))

    def approximated(self, shape: Shape, mapped: Subpath, mm_per_own: float) -> None:
        """Notes a spline approximated by cubics, or closed by moving its end onto its start,
        with its certified distance in millimetres: the distance in its own units stretched
        by the map, plus the rounding of the map."""
        points = [v for s in mapped.segments for v in s if isinstance(v, tuple)]
        size_mm = max(abs(c) for point in points for c in point)
        rounding = MAPPING_ULPS * sys.float_info.epsilon * size_mm
        bound_mm = shape.approximated * mm_per_own + rounding
        self.approximated_mm = max(self.approximated_mm, bound_mm)
        if shape.approximating:
            self.note(
                "SPLINE",
                f"rational cubic approximated by {shape.approximating} cubics within "
                f"{_up(bound_mm)} mm (certified)",
            )
        else:
            # no number in the reason: the splines closed alike are counted in one note
            self.note(
                "SPLINE",
                "closed by moving its end onto its start (counted in the approximation bound)",
            )

    def source(self, entity: DXFGraphic, kind: str, context: _Context) -> str:
        handle = entity.dxf.get("handle")
        name = f"{kind} #{handle}" if handle else kind
        return name + "".join(f" in block {b}" for b in reversed(context.blocks))

    def insert(self, entity: Any, context: _Context) -> None:
        """A block reference (INSERT, or MINSERT: an array of them): the block's entities,
        each mapped by its placement (``dxf_placement.py``). A reference that cannot be
        placed counts as one entity skipped, with the reason (as :meth:`visit`)."""
        try:
            reference = self.reference(entity, context)
        except (DocumentError, MemoryError):
            raise
        except SkipError as why:
            self.reach()
            self.skip("INSERT", str(why))
            return
        except Exception as exc:  # hostile input: any failure is this entity's
            self.reach()
            self.skip("INSERT", _unexpected(exc))
            return
        block, inner, placement, offsets = reference
        for offset in offsets:
            matrix = placement.placed @ offset @ placement.shape
            for child in block:
                self.visit(child, inner._replace(matrix=matrix))

    def reference(self, entity: Any, context: _Context) -> _Reference:
        """What a block reference places: its block, the context of the block's entities
        (without their matrix), the placement and the array offsets; raises
        :class:`SkipError` for a reference not drawn, :class:`DocumentError` for one that
        makes the document unreadable (a cycle, too deep, too many)."""
        hidden, layer = self.layer_hides(entity, context)
        hidden = context.hidden or hidden
        name = str(entity.dxf.name)
        where = self.source(entity, "INSERT", context)
        block = self.doc.blocks.get(name)
        for _attrib in entity.attribs:
            self.reach()
            self.skip("ATTRIB", hidden or NOT_DRAWN["ATTRIB"])
        if block is None:
            raise SkipError("refers to a block that is not defined")
        if name in context.blocks:
            raise DocumentError(where, f"block {name!r} refers to itself")
        if len(context.blocks) >= self.limits.max_depth:
            raise DocumentError(where, f"blocks are nested more than {self.limits.max_depth} deep")
        if not finite_entity(entity):
            raise SkipError(NON_FINITE)
        if float(entity.dxf.xscale) == 0.0 or float(entity.dxf.yscale) == 0.0:
            raise SkipError("has scale 0 along x or y: the block collapses")
        rows, columns = int(entity.dxf.row_count), int(entity.dxf.column_count)
        self.references += max(rows, 1) * max(columns, 1)
        if self.references > self.limits.max_elements:
            raise DocumentError(
                where, f"block references exceed the limit of {self.limits.max_elements}"
            )
        base = block.block.dxf.base_point if block.block is not None else (0.0, 0.0, 0.0)
        placement = insert_placement(entity, base, context.matrix)
        offsets = list(array_offsets(entity))
        if XClip(entity).has_clipping_path:
            self.note("INSERT", "is clipped (XCLIP): its block was drawn unclipped")
        if placement.tilted:
            self.note("INSERT", "is not in a plane parallel to XY: its projection was drawn")
        inner = context._replace(blocks=(*context.blocks, name), insert_layer=layer, hidden=hidden)
        return _Reference(block, inner, placement, offsets)


def _unexpected(exc: Exception) -> str:
    """The reason for an entity whose reading raised ``exc``: its class and message, short."""
    message = " ".join(str(exc).split())
    if len(message) > 80:
        message = message[:77] + "..."
    return (
        f"could not be read ({type(exc).__name__}: {message})"
        if message
        else (f"could not be read ({type(exc).__name__})")
    )


__all__ = ["read_dxf"]
