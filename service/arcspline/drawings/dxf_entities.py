"""Each DXF entity type as one of our subpaths, natively, never flattened (docs/drawings.md
§4): LINE, ARC and CIRCLE, ELLIPSE, LWPOLYLINE and 2D POLYLINE with their bulges (a bulge
``β`` is an arc of sweep ``4·atan β``), 3D POLYLINE projected, SPLINE (``dxf_spline.py``).

A subpath is in the entity's own coordinates: its OCS plane (``plane``, to be applied by the
caller with the block and unit maps) or the WCS. Angles that are multiples of 90° give exact
points.

An entity holding a number that is not finite (a NaN or an infinity in a point, radius,
angle, scale, spacing, bulge, weight or knot: any number it has) is not drawn, whatever its
type: such a number has no place in a drawing, and the arithmetic below would carry it on.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Iterable, Sequence
from typing import Any, NamedTuple

from arcspline.geometry.curves.segments import CircularArc, Line, Segment, Subpath
from arcspline.geometry.spline import Point

from .affine import Affine, SingularMapError, transform_subpath
from .dxf_placement import plane
from .dxf_spline import SplineRefusedError, spline_segments
from .dxf_spline_data import spline_data

#: Entity types that are not outlines, and why they are not drawn.
NOT_DRAWN = {
    **dict.fromkeys(("TEXT", "MTEXT", "ATTRIB", "ATTDEF"), "text is not drawn"),
    **dict.fromkeys(
        (
            "DIMENSION", "ARC_DIMENSION", "LARGE_RADIAL_DIMENSION", "LEADER", "MULTILEADER",
            "MLEADER", "TOLERANCE",
        ),
        "annotation is not drawn",
    ),
    **dict.fromkeys(
        ("HATCH", "MPOLYGON", "SOLID", "TRACE", "3DFACE", "MESH", "3DSOLID", "REGION", "BODY",
         "SURFACE", "EXTRUDEDSURFACE", "LOFTEDSURFACE", "REVOLVEDSURFACE", "SWEPTSURFACE",
         "PLANESURFACE", "NURBSURFACE"),
        "a filled area, face or solid is not an outline to cut",
    ),
    "POINT": "a point has no extent",
    "RAY": "infinite (a ray has no end)",
    "XLINE": "infinite (a construction line has no ends)",
}  # fmt: skip


#: Why an entity holding a NaN or an infinity is not drawn.
NON_FINITE = "has a non-finite number"


class SkipError(Exception):
    """An entity not drawn, and why."""


class Shape(NamedTuple):
    """An entity as a subpath in its own coordinates, the map of those onto the WCS XY plane,
    whether the entity is tilted to XY, notes on how it was read, and for a spline whose
    rational cubic pieces were approximated, the certified distance (in its own units) and
    the number of cubics (``dxf_spline.SplineSegments``)."""

    subpath: Subpath
    plane: Affine = Affine()
    tilted: bool = False
    notes: tuple[str, ...] = ()
    approximated: float = 0.0
    approximating: int = 0


def entity_shape(entity: Any, kind: str, curve_tolerance: float | None) -> Shape:
    """The entity of type ``kind`` as a :class:`Shape`; ``curve_tolerance`` (in the entity's
    own units, None to refuse) bounds the approximation of rational cubic splines. Raises
    :class:`SkipError` saying why for an entity that is not drawn."""
    if not finite_entity(entity):
        raise SkipError(NON_FINITE)
    match kind:
        case "LINE":
            start, end = _xy(entity.dxf.start), _xy(entity.dxf.end)
            if start == end:
                raise SkipError("has zero length")
            return Shape(
                Subpath((Line(start, end),)), tilted=entity.dxf.start.z != entity.dxf.end.z
            )
        case "ARC" | "CIRCLE":
            subpath = _arc(entity) if kind == "ARC" else _circle_entity(entity)
            return Shape(subpath, *plane(entity.dxf.extrusion, float(entity.dxf.center.z)))
        case "ELLIPSE":
            subpath, tilted = _ellipse(entity)
            return Shape(subpath, tilted=tilted)
        case "LWPOLYLINE":
            return Shape(
                _lwpolyline(entity), *plane(entity.dxf.extrusion, float(entity.dxf.elevation))
            )
        case "POLYLINE":
            subpath, tilted = _polyline_entity(entity)
            if entity.is_3d_polyline:
                return Shape(subpath, tilted=tilted)
            return Shape(subpath, *plane(entity.dxf.extrusion, float(entity.dxf.elevation.z)))
        case "SPLINE":
            return _spline(entity, curve_tolerance)
        case _:
            raise SkipError("this entity type is not read")


def finite_entity(entity: Any) -> bool:
    """Whether every number of the entity is finite: its DXF attributes, and the points,
    bulges, vertices, knots and weights held outside them."""
    values: list[object] = list(entity.dxf.all_existing_dxf_attribs().values())
    match entity.dxftype():
        case "LWPOLYLINE":
            values.extend(entity.get_points("xyseb"))
        case "POLYLINE":
            values.extend(v.dxf.all_existing_dxf_attribs().values() for v in entity.vertices)
        case "SPLINE":
            values.extend((entity.control_points, entity.fit_points, entity.knots))
            values.append(entity.weights)
    return finite_numbers(values)


def finite_numbers(values: Iterable[object]) -> bool:
    """Whether every float in ``values``, and in the tuples, vectors and lists nested in them,
    is finite (text is passed over)."""
    for value in values:
        if isinstance(value, float):
            if not math.isfinite(value):
                return False
        elif (
            isinstance(value, Iterable)
            and not isinstance(value, str | bytes)
            and not finite_numbers(value)
        ):
            return False
    return True


# --- exact values --------------------------------------------------------------------------


def _cos_sin_deg(angle_deg: float) -> tuple[float, float]:
    """cos and sin of an angle in degrees, exact at multiples of 90° (an ARC from 0° to 90°
    ends at (cx, cy + r), not at (cx + 1e-16·r, cy + r))."""
    quarter, rest = divmod(angle_deg, 90.0)
    if rest == 0.0:
        return ((1.0, 0.0), (0.0, 1.0), (-1.0, 0.0), (0.0, -1.0))[int(quarter) % 4]
    angle_rad = math.radians(angle_deg)
    return math.cos(angle_rad), math.sin(angle_rad)


def _on_circle(center: Point, radius: float, angle_deg: float) -> Point:
    cos, sin = _cos_sin_deg(angle_deg)
    return Point(center[0] + radius * cos, center[1] + radius * sin)


def _circle(center: Point, radius: float) -> Subpath:
    """A full circle as two half arcs, anticlockwise from angle 0 (a segment sweeps < 2π)."""
    east, west = _on_circle(center, radius, 0.0), _on_circle(center, radius, 180.0)
    return Subpath(
        (
            CircularArc(east, west, center, radius, 0.0, math.pi),
            CircularArc(west, east, center, radius, -math.pi, math.pi),
        ),
        closed=True,
    )


def _bulge_segment(p0: Point, p1: Point, bulge: float) -> Segment:
    """The polyline step from ``p0`` to ``p1``: a line, or the arc of sweep ``4·atan(bulge)``
    (anticlockwise for ``bulge > 0``). With chord ``d = p1 − p0`` the centre is
    ``M + perp(d)·(1 − β²)/(4β)`` (``perp`` turning anticlockwise) and the radius
    ``|d|·(1 + β²)/(4|β|)``."""
    if bulge == 0.0:
        return Line(p0, p1)
    dx, dy = p1[0] - p0[0], p1[1] - p0[1]
    k = (1.0 - bulge * bulge) / (4.0 * bulge)
    center = Point((p0[0] + p1[0]) / 2.0 - dy * k, (p0[1] + p1[1]) / 2.0 + dx * k)
    radius = math.hypot(dx, dy) * (1.0 + bulge * bulge) / (4.0 * abs(bulge))
    start_rad = math.atan2(p0[1] - center[1], p0[0] - center[0])
    return CircularArc(p0, p1, center, radius, start_rad, 4.0 * math.atan(bulge))


def _polyline(vertices: Sequence[tuple[Point, float]], closed: bool) -> Subpath:
    """Vertices with the bulge of the step after each, as one subpath; repeated vertices
    (zero-length steps) are passed over."""
    steps = list(itertools.pairwise(vertices))
    if closed and len(vertices) > 1:
        steps.append((vertices[-1], vertices[0]))
    segments = [_bulge_segment(p0, p1, bulge) for (p0, bulge), (p1, _) in steps if p0 != p1]
    if not segments:
        raise SkipError("has no length (all its vertices coincide)")
    return Subpath(tuple(segments), closed=segments[-1].end == segments[0].start)


# --- entities ------------------------------------------------------------------------------


def _xy(vector: Any) -> Point:
    return Point(float(vector[0]), float(vector[1]))


def _arc(entity: Any) -> Subpath:
    center, radius = _xy(entity.dxf.center), float(entity.dxf.radius)
    if not radius > 0.0:
        raise SkipError("has zero radius")
    start_deg, end_deg = float(entity.dxf.start_angle), float(entity.dxf.end_angle)
    sweep_deg = (end_deg - start_deg) % 360.0
    if sweep_deg == 0.0:  # 0° to 360° (or equal angles): the whole circle
        return _circle(center, radius)._replace(closed=True)
    arc = CircularArc(
        _on_circle(center, radius, start_deg), _on_circle(center, radius, end_deg), center,
        radius, math.remainder(math.radians(start_deg), math.tau), math.radians(sweep_deg),
    )  # fmt: skip
    return Subpath((arc,))


def _circle_entity(entity: Any) -> Subpath:
    radius = float(entity.dxf.radius)
    if not radius > 0.0:
        raise SkipError("has zero radius")
    return _circle(_xy(entity.dxf.center), radius)


def _ellipse(entity: Any) -> tuple[Subpath, bool]:
    """An ELLIPSE (centre and major axis in WCS, the minor axis ``ratio·|major|`` along
    ``extrusion × major``) as the unit circle's arc mapped by the affine map with columns
    major and minor (their projections onto XY)."""
    major = entity.dxf.major_axis
    normal = entity.dxf.extrusion
    across = normal.cross(major)
    if (
        across.magnitude == 0.0
    ):  # a zero major axis, or one along the extrusion: no plane to draw in
        raise SkipError("has a zero axis (or lies edge-on to the XY plane)")
    minor = across.normalize(major.magnitude * float(entity.dxf.ratio))
    center = entity.dxf.center
    m = Affine(major.x, major.y, minor.x, minor.y, center.x, center.y)
    start, end = float(entity.dxf.start_param), float(entity.dxf.end_param)
    sweep = (end - start) % math.tau
    if sweep == 0.0 or math.isclose(sweep, math.tau, rel_tol=0.0, abs_tol=1e-12):
        unit = _circle(Point(0.0, 0.0), 1.0)
    else:
        unit = Subpath(
            (
                CircularArc(
                    Point(math.cos(start), math.sin(start)), Point(math.cos(end), math.sin(end)),
                    Point(0.0, 0.0), 1.0, math.remainder(start, math.tau), sweep,
                ),
            )
        )  # fmt: skip
    try:
        return transform_subpath(unit, m), not (normal.x == 0.0 and normal.y == 0.0)
    except SingularMapError as exc:
        raise SkipError("has a zero axis (or lies edge-on to the XY plane)") from exc


def _lwpolyline(entity: Any) -> Subpath:
    vertices = [(Point(float(x), float(y)), float(b)) for x, y, b in entity.get_points("xyb")]
    return _polyline(vertices, bool(entity.closed))


def _polyline_entity(entity: Any) -> tuple[Subpath, bool]:
    if entity.is_poly_face_mesh or entity.is_polygon_mesh:
        raise SkipError("a polyface or polygon mesh is not an outline to cut")
    # Spline-frame control points (flag 16) are the frame, not the drawn curve.
    vertices = [v for v in entity.vertices if not v.dxf.flags & 16]
    if entity.is_3d_polyline:
        points = [(_xy(v.dxf.location), 0.0) for v in vertices]
        flat = all(v.dxf.location.z == vertices[0].dxf.location.z for v in vertices)
        return _polyline(points, entity.is_closed), not flat
    points = [(_xy(v.dxf.location), float(v.dxf.bulge)) for v in vertices]
    return _polyline(points, entity.is_closed), False


def _spline(entity: Any, curve_tolerance: float | None) -> Shape:
    """A SPLINE (its points are WCS, so no plane), with the notes on how it was read; a
    refused one is skipped with the reason, and its notes are lost with it."""
    try:
        data, notes = spline_data(entity)
        pieces = spline_segments(data, curve_tolerance)
    except SplineRefusedError as exc:
        raise SkipError(str(exc)) from exc
    return Shape(
        Subpath(pieces.segments, pieces.closed),
        notes=notes,
        approximated=pieces.approximated,
        approximating=pieces.approximating,
    )
