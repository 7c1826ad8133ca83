"""Paths as a request gives them: small picklable values that build (and check) the
:class:`~arcspline.geometry.curves.segments.Path` where it is needed, in a worker.

* :class:`PathFromData`: SVG path data (``svg_data.py``);
* :class:`PathFromSegments`: the explicit JSON form, subpaths of typed segments each
  continuing from where the last ended. A circular ``arc`` turns about its centre from the
  current point; an ``elliptical_arc`` is SVG's endpoint form (radii, rotation, the
  large-arc and anticlockwise flags, the end point). A ``closed`` subpath gets a closing line
  where it does not end at its start.
"""

from __future__ import annotations

import math
from typing import NamedTuple

from arcspline.geometry import GeometryError
from arcspline.geometry.curves.segments import (
    CircularArc,
    Cubic,
    Line,
    Path,
    Quadratic,
    Segment,
    Subpath,
)
from arcspline.geometry.spline import Point

from .svg_data import UncomputableArcError, arc_from_endpoints, parse_path_data

XY = tuple[float, float]


class LineTo(NamedTuple):
    to: XY


class QuadraticTo(NamedTuple):
    control: XY
    to: XY


class CubicTo(NamedTuple):
    control1: XY
    control2: XY
    to: XY


class ArcAbout(NamedTuple):
    """A circular arc from the current point about ``center`` through ``sweep_deg``
    (anticlockwise positive)."""

    center: XY
    sweep_deg: float


class EllipticalArcTo(NamedTuple):
    """SVG's endpoint form (``anticlockwise`` is SVG's sweep flag in a y-up frame)."""

    radii: XY
    rotation_deg: float
    large_arc: bool
    anticlockwise: bool
    to: XY


SegmentForm = LineTo | QuadraticTo | CubicTo | ArcAbout | EllipticalArcTo


class SubpathForm(NamedTuple):
    start: XY
    segments: tuple[SegmentForm, ...]
    closed: bool = False


class PathFromData(NamedTuple):
    """SVG path data, parsed in the worker."""

    data: str
    max_segments: int | None = None

    def build(self) -> Path:
        path = parse_path_data(self.data, max_segments=self.max_segments)
        if not path.subpaths:
            raise GeometryError("path", "draws nothing (no segment of non-zero extent)")
        return path


class PathFromSegments(NamedTuple):
    """The explicit JSON form."""

    subpaths: tuple[SubpathForm, ...]
    max_segments: int | None = None

    def build(self) -> Path:
        count = sum(len(sub.segments) for sub in self.subpaths)
        if self.max_segments is not None and count > self.max_segments:
            raise GeometryError(
                "path",
                f"has {count} segments; at most {self.max_segments} are accepted",
                kind="segment_limit",
                limit=float(self.max_segments),
            )
        return Path(tuple(_subpath(i, sub) for i, sub in enumerate(self.subpaths)))


def _subpath(i: int, form: SubpathForm) -> Subpath:
    current = Point(*form.start)
    segments: list[Segment] = []
    for j, seg in enumerate(form.segments):
        made = _segment(current, seg, f"path.subpaths[{i}].segments[{j}]")
        if made is not None:  # an elliptical arc between equal points is omitted, as in SVG
            segments.append(made)
            current = made.end
    if form.closed and current != Point(*form.start):
        segments.append(Line(current, Point(*form.start)))
    if not segments:
        raise GeometryError(f"path.subpaths[{i}]", "draws nothing (no segment of non-zero extent)")
    return Subpath(tuple(segments), form.closed)


def _segment(current: Point, seg: SegmentForm, where: str) -> Segment | None:
    if isinstance(seg, LineTo):
        return Line(current, Point(*seg.to))
    if isinstance(seg, QuadraticTo):
        return Quadratic(current, Point(*seg.control), Point(*seg.to))
    if isinstance(seg, CubicTo):
        return Cubic(current, Point(*seg.control1), Point(*seg.control2), Point(*seg.to))
    if isinstance(seg, ArcAbout):
        cx, cy = seg.center
        radius = math.hypot(current.x - cx, current.y - cy)
        if not radius > 0.0:
            raise GeometryError(where, "the arc's centre is its start point (radius 0)")
        start = math.atan2(current.y - cy, current.x - cx)
        sweep = math.radians(seg.sweep_deg)
        end = Point(cx + radius * math.cos(start + sweep), cy + radius * math.sin(start + sweep))
        return CircularArc(current, end, Point(cx, cy), radius, start, sweep)
    try:
        return arc_from_endpoints(
            current, Point(*seg.to), *seg.radii, seg.rotation_deg, seg.large_arc, seg.anticlockwise
        )
    except UncomputableArcError:
        raise GeometryError(
            where, "the elliptical arc cannot be computed in double precision"
        ) from None
