"""A path's segments as one table, the compiled cutter's input (``curves/split.pyx``'s
``SEGMENT_FIELDS``), and the checks that keep every number within what the kernels can hold
(docs/method.md §11 "Limits")."""

from __future__ import annotations

import itertools
import math
from collections.abc import Sequence

import numpy as np

from .curves.segments import CircularArc, Cubic, EllipticalArc, Line, Quadratic, Segment
from .curves.split import SEGMENT_FIELDS, SEGMENT_KINDS
from .errors import GeometryError
from .spline import FloatArray

#: Coordinates and radii stay below this magnitude, so that squares and products of them stay
#: finite in double precision (as for spirals).
MAX_MAGNITUDE = 1e150
#: A segment smaller than this (but not a point) would underflow in the squares of its size.
MIN_SIZE = 1e-150
#: An arc's stored end points must lie this close (relative to its coordinates) to the points
#: its centre, radii and angles give: an arc is emitted as itself, or cut at its angles from
#: those ends, so they must agree (rounding of SVG's endpoint conversion is ~1e-15).
ARC_RTOL = 1e-9

_SEG = {name: j for j, name in enumerate(SEGMENT_FIELDS)}

#: ``SEGMENT_FIELDS`` in the order :func:`segment_row` writes them.
_ROW_ORDER = (
    "kind", "x0", "y0", "x1", "y1", "x2", "y2", "x3", "y3", "cx", "cy", "rx", "ry",
    "rotation_rad", "start_angle_rad", "sweep_rad", "coordinate_scale",
)  # fmt: skip
assert SEGMENT_FIELDS == _ROW_ORDER
_KIND = {
    Line: float(SEGMENT_KINDS["line"]),
    Quadratic: float(SEGMENT_KINDS["quadratic"]),
    Cubic: float(SEGMENT_KINDS["cubic"]),
    CircularArc: float(SEGMENT_KINDS["arc"]),
    EllipticalArc: float(SEGMENT_KINDS["elliptical_arc"]),
}


def segment_row(segment: Segment) -> tuple[float, ...]:
    """A segment as a row of ``SEGMENT_FIELDS`` (its kind, points and arc parameters; the
    coordinate scale is left 0 for :func:`segment_table`)."""
    (x0, y0), (x3, y3) = segment.start, segment.end
    kind = _KIND[type(segment)]
    if isinstance(segment, Line):
        return (kind, x0, y0, 0.0, 0.0, 0.0, 0.0, x3, y3, *_NO_ARC)
    if isinstance(segment, Quadratic):
        return (kind, x0, y0, *segment.control, 0.0, 0.0, x3, y3, *_NO_ARC)
    if isinstance(segment, Cubic):
        return (kind, x0, y0, *segment.control1, *segment.control2, x3, y3, *_NO_ARC)
    if isinstance(segment, CircularArc):
        rx = ry = segment.radius
        rotation = 0.0
    else:
        rx, ry, rotation = segment.rx, segment.ry, segment.rotation_rad
    return (
        kind, x0, y0, 0.0, 0.0, 0.0, 0.0, x3, y3, *segment.center, rx, ry, rotation,
        segment.start_angle_rad, segment.sweep_rad, 0.0,
    )  # fmt: skip


_NO_ARC = (0.0,) * 8


def segment_table(segments: Sequence[Segment]) -> FloatArray:
    """The segments as rows of ``SEGMENT_FIELDS``, with each one's coordinate scale: the
    largest magnitude of its points (and of its arc's centre plus radius)."""
    table = np.array([segment_row(s) for s in segments], dtype=np.float64)
    with np.errstate(invalid="ignore"):
        reach = np.maximum(table[:, _SEG["rx"]], table[:, _SEG["ry"]])
        table[:, _SEG["coordinate_scale"]] = np.maximum.reduce(
            [
                np.abs(table[:, _SEG["x0"] : _SEG["y3"] + 1]).max(axis=1),
                np.abs(table[:, _SEG["cx"]]) + reach,
                np.abs(table[:, _SEG["cy"]]) + reach,
            ]
        )
    return table


def check(table: FloatArray, owner: list[tuple[int, int]]) -> None:
    """Numbers the kernels can hold: finite, below ``MAX_MAGNITUDE``; radii > 0; sweeps
    within a full turn. Raises for the first segment that fails, naming it."""
    kind = table[:, _SEG["kind"]]
    arcs = kind >= SEGMENT_KINDS["arc"]
    sweep = np.abs(table[:, _SEG["sweep_rad"]])
    with np.errstate(invalid="ignore"):
        bad_number = ~np.all(np.abs(table) < MAX_MAGNITUDE, axis=1)
        bad_radius = arcs & ~((table[:, _SEG["rx"]] > 0.0) & (table[:, _SEG["ry"]] > 0.0))
        bad_sweep = arcs & ~((sweep > 0.0) & (sweep < 2.0 * math.pi))
    # Each segment starts where the one before it in its subpath ends, to the bit.
    starts, ends = table[1:, _SEG["x0"] : _SEG["y0"] + 1], table[:-1, _SEG["x3"] : _SEG["y3"] + 1]
    same_subpath = np.array([a[0] == b[0] for a, b in itertools.pairwise(owner)], dtype=bool)
    broken = np.concatenate([[False], same_subpath & np.any(starts != ends, axis=1)])
    size = _sizes(table)
    tiny = (size > 0.0) & (size < MIN_SIZE)
    off = _off_the_arc(table) > ARC_RTOL * table[:, _SEG["coordinate_scale"]]
    for bad, why in (
        (bad_number, f"has a number that is not finite or beyond ±{MAX_MAGNITUDE:g}"),
        (tiny, f"is smaller than {MIN_SIZE:g} across, too small for double precision"),
        (broken, "does not start where the segment before it ends"),
        (bad_radius, "an arc's radii must be > 0"),
        (bad_sweep, "an arc's sweep must be non-zero and less than a full turn"),
        (arcs & off, "an arc's end points are not where its centre, radii and angles put them"),
    ):
        if bad.any():
            i, j = owner[int(np.argmax(bad))]
            raise GeometryError(where(i, j), why)


def _off_the_arc(table: FloatArray) -> FloatArray:
    """How far an arc's stored start and end lie from the points its centre, radii, rotation
    and angles give (0 for other segments)."""
    t = {name: table[:, _SEG[name]] for name in _ROW_ORDER}
    cos_r, sin_r = np.cos(t["rotation_rad"]), np.sin(t["rotation_rad"])
    worst = np.zeros(len(table))
    with np.errstate(invalid="ignore", over="ignore"):
        for angle, (x, y) in (
            (t["start_angle_rad"], ("x0", "y0")),
            (t["start_angle_rad"] + t["sweep_rad"], ("x3", "y3")),
        ):
            ex, ey = t["rx"] * np.cos(angle), t["ry"] * np.sin(angle)
            px = t["cx"] + cos_r * ex - sin_r * ey
            py = t["cy"] + sin_r * ex + cos_r * ey
            worst = np.maximum(worst, np.hypot(px - t[x], py - t[y]))
    return np.where(table[:, _SEG["kind"]] >= SEGMENT_KINDS["arc"], worst, 0.0)


def _sizes(table: FloatArray) -> FloatArray:
    """Each segment's extent: its control points' largest offset from its start (a line's
    length), or an arc's larger radius."""
    kind = table[:, _SEG["kind"]]
    start = table[:, _SEG["x0"] : _SEG["y0"] + 1]
    used = {  # the control points each kind has, besides its start
        "x1": kind == SEGMENT_KINDS["quadratic"],
        "x2": kind == SEGMENT_KINDS["cubic"],
        "x3": kind < SEGMENT_KINDS["arc"],
    }
    used["x1"] = used["x1"] | used["x2"]
    size = np.where(
        kind >= SEGMENT_KINDS["arc"], np.maximum(table[:, _SEG["rx"]], table[:, _SEG["ry"]]), 0.0
    )
    with np.errstate(invalid="ignore", over="ignore"):
        for name, mask in used.items():
            j = _SEG[name]
            offset = np.abs(table[:, j : j + 2] - start).max(axis=1)
            size = np.where(mask, np.maximum(size, offset), size)
    return size


def where(subpath: int, segment: int) -> str:
    """A segment's name in errors: ``path.subpaths[i].segments[j]``."""
    return f"path.subpaths[{subpath}].segments[{segment}]"
