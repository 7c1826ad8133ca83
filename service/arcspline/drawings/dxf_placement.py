"""Where a DXF entity lies: its object coordinate system (OCS) and the block references
(INSERT, MINSERT) around it, as our :class:`Affine` maps (docs/drawings.md §4).

An entity's OCS plane is mapped onto the WCS XY plane by the arbitrary axis algorithm and
projected; a block reference places its block by ``OCS · translate(insert) · rotate ·
translate(column·spacing, row·spacing) · scale · translate(−base point)``.
"""

from __future__ import annotations

import math
from collections.abc import Iterator
from typing import Any, NamedTuple

from ezdxf.math import OCS

from .affine import Affine

#: Relative allowance for the rounding of :func:`stretch`, so that it bounds the map above.
STRETCH_RTOL = 1e-12


class Placement(NamedTuple):
    """A block reference's map, in two parts around its array offset: ``placed`` (the outer
    map, OCS, insertion point, rotation) after the offset, ``shape`` (scale, base point)
    before it;
    ``tilted`` when its OCS plane is not parallel to XY."""

    placed: Affine
    shape: Affine
    tilted: bool


def plane(extrusion: Any, elevation: float) -> tuple[Affine, bool]:
    """The map of an entity's OCS plane at ``elevation`` onto the WCS XY plane (the arbitrary
    axis algorithm, DXF reference "Object Coordinate Systems"), and whether that plane is
    tilted to XY. Extrusion (0, 0, −1) mirrors x exactly."""
    x, y, z = (float(c) for c in extrusion)
    if x == 0.0 and y == 0.0:
        if z > 0.0:
            return Affine(), False
        if z < 0.0:
            return Affine(-1.0, 0.0, 0.0, 1.0, 0.0, 0.0), False
    ocs = OCS((x, y, z))
    ux, uy, uz = ocs.ux, ocs.uy, ocs.uz
    return Affine(ux.x, ux.y, uy.x, uy.y, elevation * uz.x, elevation * uz.y), True


def insert_placement(entity: Any, base_point: Any, outer: Affine) -> Placement:
    """The map of an INSERT's block coordinates (module docstring) into the coordinates that
    ``outer`` maps to millimetres, composed with ``outer``, without its array offset; the
    caller has checked that neither scale is 0."""
    insert = entity.dxf.insert
    ocs, tilted = plane(entity.dxf.extrusion, float(insert.z))
    placed = (
        outer @ ocs @ Affine.translate(float(insert.x), float(insert.y))
        @ Affine.rotate_deg(float(entity.dxf.rotation))
    )  # fmt: skip
    shape = Affine.scale(float(entity.dxf.xscale), float(entity.dxf.yscale)) @ Affine.translate(
        -float(base_point[0]), -float(base_point[1])
    )
    return Placement(placed, shape, tilted)


def array_offsets(entity: Any) -> Iterator[Affine]:
    """The offsets of a MINSERT's instances, row by row (one, at 0, for an INSERT)."""
    rows, columns = int(entity.dxf.row_count), int(entity.dxf.column_count)
    spacing = float(entity.dxf.column_spacing), float(entity.dxf.row_spacing)
    for row in range(max(rows, 1)):
        for column in range(max(columns, 1)):
            yield Affine.translate(column * spacing[0], row * spacing[1])


def stretch(m: Affine) -> float:
    """The most the map ``m`` lengthens a vector, its largest singular value
    ``(√((a + d)² + (c − b)²) + √((a − d)² + (b + c)²)) / 2``, rounded up: a distance ``δ``
    in an entity's own units is at most ``stretch(m)·δ`` once mapped."""
    a, b, c, d = m.a, m.b, m.c, m.d
    sigma = (math.hypot(a + d, c - b) + math.hypot(a - d, b + c)) / 2.0
    return sigma * (1.0 + STRETCH_RTOL)
