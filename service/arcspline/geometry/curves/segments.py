"""The segments of a path, as values: what a path is made of before it is approximated.

Every segment carries its own start and end point, exactly as given or as computed once; a
subpath chains them, segment ``i``'s ``end`` being segment ``i + 1``'s ``start`` bit for bit
(:class:`Subpath` checks it). Angles are radians, anticlockwise positive; each segment's
parameter ``t`` runs over ``[0, 1]`` (for the arcs, the fraction of the sweep).
"""

from __future__ import annotations

from typing import NamedTuple

from ..spline import Point


class Line(NamedTuple):
    """A straight segment."""

    start: Point
    end: Point


class Quadratic(NamedTuple):
    """A quadratic Bézier curve."""

    start: Point
    control: Point
    end: Point


class Cubic(NamedTuple):
    """A cubic Bézier curve (any four points)."""

    start: Point
    control1: Point
    control2: Point
    end: Point


class CircularArc(NamedTuple):
    """An arc of the circle about ``center`` through ``start``, turning ``sweep_rad``
    (``0 < |sweep_rad| < 2π``); ``end`` is its end point as computed once."""

    start: Point
    end: Point
    center: Point
    radius: float
    start_angle_rad: float
    sweep_rad: float


class EllipticalArc(NamedTuple):
    """An arc of the ellipse ``center + R(rotation)·(rx·cos φ, ry·sin φ)`` for ``φ`` from
    ``start_angle_rad`` through ``sweep_rad`` (``0 < |sweep_rad| < 2π``); ``start`` and ``end``
    are its end points (as given in SVG's endpoint form, or computed once)."""

    start: Point
    end: Point
    center: Point
    rx: float
    ry: float
    rotation_rad: float
    start_angle_rad: float
    sweep_rad: float


Segment = Line | Quadratic | Cubic | CircularArc | EllipticalArc


class Subpath(NamedTuple):
    """Segments end to end; ``closed`` when the path closes it (SVG ``Z``): its last segment
    then ends exactly where its first starts (a closing line is one of the segments)."""

    segments: tuple[Segment, ...]
    closed: bool = False


class Path(NamedTuple):
    """One or more subpaths: one toolpath each, approximated together."""

    subpaths: tuple[Subpath, ...]
