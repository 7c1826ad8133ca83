"""SVG's shapes as exact subpaths in the element's own numbers (docs/drawings.md §3).

Each is built as SVG 2 §9–10 says, y down, so a positive sweep is SVG's "positive angle
direction": ``path`` by the path-data parser (§9.3); ``line`` (§10.5) and ``polyline``/
``polygon`` (§10.6, §10.7) as lines, a polygon closed back to its first point; ``rect``
(§10.2) with ``rx``/``ry`` (``auto`` takes the other, each clamped to half its side) and its
corners as exact quarter arcs; ``circle`` (§10.3) and ``ellipse`` (§10.4) as two half arcs
from ``(cx + r, cy)``, since a segment sweeps less than a full turn. A shape of zero size or
without data gives no subpath; a negative size is an error naming the element.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Callable
from typing import Final

from arcspline.geometry.curves.segments import CircularArc, EllipticalArc, Line, Segment, Subpath
from arcspline.geometry.errors import GeometryError
from arcspline.geometry.spline import Point
from arcspline.paths.svg_data import parse_path_data

from .model import DocumentError
from .svg_attributes import Viewport, length, lengths, number_list
from .svg_parse import Node

__all__ = ["ellipse", "polyline", "rounded_rect", "shape_subpaths"]

_QUARTER: Final = math.pi / 2.0


def shape_subpaths(node: Node, viewport: Viewport) -> tuple[Subpath, ...]:
    """The subpaths of shape element ``node`` (a tag of ``SHAPES``), percentages being of
    ``viewport``; none for a shape of zero size or without data."""
    return _READERS[node.tag](node, viewport)


def _path(node: Node, viewport: Viewport) -> tuple[Subpath, ...]:
    d = node.attrib.get("d", "")
    if not d.strip(" \t\n\r\f"):
        return ()
    try:
        return parse_path_data(d).subpaths
    except GeometryError as error:
        raise DocumentError(node.source, f"path data {error.message}") from None


def _line(node: Node, viewport: Viewport) -> tuple[Subpath, ...]:
    x1, y1, x2, y2 = lengths(node, viewport, "x1 y1 x2 y2")
    if (x1, y1) == (x2, y2):
        return ()
    return (Subpath((Line(Point(x1, y1), Point(x2, y2)),)),)


def _poly(node: Node, viewport: Viewport) -> tuple[Subpath, ...]:
    numbers = number_list(node, "points")
    if len(numbers) % 2:
        raise DocumentError(node.source, f"points: an odd count of numbers ({len(numbers)})")
    points = [Point(numbers[i], numbers[i + 1]) for i in range(0, len(numbers), 2)]
    subpath = polyline(points, node.tag == "polygon")
    return (subpath,) if subpath is not None else ()


def _rect(node: Node, viewport: Viewport) -> tuple[Subpath, ...]:
    x, y, width, height = lengths(node, viewport, "x y width height")
    if width < 0.0 or height < 0.0:
        raise DocumentError(node.source, "width and height must be >= 0")
    if width == 0.0 or height == 0.0:
        return ()
    rx, ry = _radii(node, viewport)
    return (rounded_rect(x, y, width, height, min(rx, width / 2), min(ry, height / 2)),)


def _circle(node: Node, viewport: Viewport) -> tuple[Subpath, ...]:
    cx, cy, r = lengths(node, viewport, "cx cy r")
    if r < 0.0:
        raise DocumentError(node.source, "r must be >= 0")
    return (ellipse(cx, cy, r, r),) if r > 0.0 else ()


def _ellipse(node: Node, viewport: Viewport) -> tuple[Subpath, ...]:
    cx, cy = lengths(node, viewport, "cx cy")
    rx, ry = _radii(node, viewport)
    return (ellipse(cx, cy, rx, ry),) if rx > 0.0 and ry > 0.0 else ()


_READERS: Final[dict[str, Callable[[Node, Viewport], tuple[Subpath, ...]]]] = {
    "path": _path,
    "line": _line,
    "polyline": _poly,
    "polygon": _poly,
    "rect": _rect,
    "circle": _circle,
    "ellipse": _ellipse,
}


def _radii(node: Node, viewport: Viewport) -> tuple[float, float]:
    """``rx`` and ``ry`` (SVG 2 §10.2, §10.4): ``auto`` (or absent) takes the other's
    value, both ``auto`` give 0; a negative value is an error."""
    rx, ry = (_radius(node, name, viewport) for name in ("rx", "ry"))
    if rx is None:
        rx = ry if ry is not None else 0.0
    return rx, ry if ry is not None else rx


def _radius(node: Node, name: str, viewport: Viewport) -> float | None:
    if node.attrib.get(name, "auto").strip() == "auto":
        return None
    value = length(node, name, viewport)
    if value < 0.0:
        raise DocumentError(node.source, f"{name} must be >= 0, got {value:g}")
    return value


# --- shapes as segments, in the element's numbers ------------------------------------------


def polyline(points: list[Point], closed: bool) -> Subpath | None:
    """Lines through ``points`` (back to the first when ``closed``, SVG 2 §10.7); ``None``
    when they are fewer than two distinct points."""
    if len(set(points)) < 2:
        return None
    if closed and points[-1] != points[0]:
        points = [*points, points[0]]
    return Subpath(tuple(Line(a, b) for a, b in itertools.pairwise(points)), closed)


def rounded_rect(x: float, y: float, width: float, height: float, rx: float, ry: float) -> Subpath:
    """A rectangle from ``(x + rx, y)`` along +x, corners as quarter arcs of radii ``rx``,
    ``ry`` (SVG 2 §10.2's equivalent path); sharp corners when either radius is 0."""
    x3, y3 = x + width, y + height
    if rx == 0.0 or ry == 0.0:
        corners = [Point(x, y), Point(x3, y), Point(x3, y3), Point(x, y3)]
        edges = itertools.pairwise([*corners, corners[0]])
        return Subpath(tuple(Line(a, b) for a, b in edges), True)
    x1, y1 = x + rx, y + ry
    # A radius of half the side leaves no straight edge: the two arcs meet at one point.
    x2 = x1 if 2.0 * rx >= width else x3 - rx
    y2 = y1 if 2.0 * ry >= height else y3 - ry
    # Each side: its straight edge (if any) from where the last corner ends, then the corner
    # arc (start, end, centre, start angle), sweeping a quarter turn.
    sides = (
        (Point(x1, y), Point(x2, y), Point(x3, y1), Point(x2, y1), -_QUARTER),
        (Point(x3, y1), Point(x3, y2), Point(x2, y3), Point(x2, y2), 0.0),
        (Point(x2, y3), Point(x1, y3), Point(x, y2), Point(x1, y2), _QUARTER),
        (Point(x, y2), Point(x, y1), Point(x1, y), Point(x1, y1), math.pi),
    )
    segments: list[Segment] = []
    for edge_start, corner_start, corner_end, center, angle in sides:
        if edge_start != corner_start:
            segments.append(Line(edge_start, corner_start))
        segments.append(_arc(corner_start, corner_end, center, rx, ry, angle, _QUARTER))
    return Subpath(tuple(segments), True)


def ellipse(cx: float, cy: float, rx: float, ry: float) -> Subpath:
    """The ellipse (a circle when ``rx == ry``) as two half arcs from ``(cx + rx, cy)`` the
    positive way, through ``(cx - rx, cy)`` (SVG 2 §10.3, §10.4)."""
    right, left, center = Point(cx + rx, cy), Point(cx - rx, cy), Point(cx, cy)
    return Subpath(
        (
            _arc(right, left, center, rx, ry, 0.0, math.pi),
            _arc(left, right, center, rx, ry, math.pi, math.pi),
        ),
        True,
    )


def _arc(start: Point, end: Point, center: Point, rx: float, ry: float, angle_rad: float,
         sweep_rad: float) -> Segment:  # fmt: skip
    if rx == ry:
        return CircularArc(start, end, center, rx, angle_rad, sweep_rad)
    return EllipticalArc(start, end, center, rx, ry, 0.0, angle_rad, sweep_rad)
