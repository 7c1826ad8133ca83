"""The path read back from a program, measured against the spiral by the test oracle.

The reader's cut moves become segments the oracle (``tests.support.oracle``) measures: it
samples both the spiral (Bernstein form, from the control points) and the path densely, in
both directions, with exact point-to-arc distances. A controller given an arc whose start
and end radii differ cuts between the two; the oracle is given the mean radius and half
the difference is added to what it measures, which bounds the distance to any such path.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Literal

import numpy as np

from arcspline.geometry import ArcSpline, Point, Spiral
from tests.support import gcode_reader, oracle


@dataclass(frozen=True)
class PathSegment:
    """A read-back move in the fields the oracle reads (those of the core's segments)."""

    type: Literal["arc", "line"]
    start: Point
    end: Point
    center: Point
    radius: float
    direction: Literal["ccw", "cw"]
    u_start: float
    u_end: float


def path_segments(cuts: list[gcode_reader.Move], spline: ArcSpline) -> list[PathSegment]:
    """One segment per cut move; the ``u`` range is that of the spline segment it cuts
    (the oracle uses it only to pick which path segments to compare first)."""
    segments = []
    for move, seg in zip(cuts, spline.segments, strict=True):
        start, end = Point(*move.xy_start), Point(*move.xy_end)
        if move.motion in (2, 3):
            assert move.centre is not None
            assert move.r_start is not None
            assert move.r_end is not None
            segments.append(
                PathSegment(
                    "arc",
                    start,
                    end,
                    Point(*move.centre),
                    0.5 * (move.r_start + move.r_end),
                    "ccw" if move.motion == 3 else "cw",
                    seg.u_start,
                    seg.u_end,
                )
            )
        else:
            segments.append(
                PathSegment("line", start, end, start, math.inf, "ccw", seg.u_start, seg.u_end)
            )
    return segments


def radius_mismatch(cuts: list[gcode_reader.Move]) -> float:
    """The largest ``|r_end − r_start|`` of the program's arcs."""
    return max(
        (abs(m.r_end - m.r_start) for m in cuts if m.r_start is not None and m.r_end is not None),
        default=0.0,
    )


def deviation(spiral: Spiral, spline: ArcSpline, program: gcode_reader.Program) -> float:
    """Upper bound of the two-sided distance between the spiral and the read-back path."""
    cuts = program.cuts
    measured = oracle.measure(spiral.control_points, path_segments(cuts, spline), samples=20_000)
    return measured.max + 0.5 * radius_mismatch(cuts)


def chord_deviation_sampled(spiral: Spiral, u0: float, u1: float, a: Point, b: Point) -> float:
    """Largest distance from the spiral piece to the segment ``a``–``b``: dense sampling,
    then the cells either side of the largest sample sampled again as densely."""
    cp = np.asarray(spiral.control_points, dtype=np.float64)

    def dist(u: np.ndarray) -> np.ndarray:
        points = oracle.bezier_point(cp, u)
        return np.asarray(
            oracle.point_line_distance(points, np.array(a), np.array(b)), dtype=np.float64
        )

    u = np.linspace(u0, u1, 4001)
    d = dist(u)
    k = int(np.argmax(d))
    fine = np.linspace(u[max(k - 1, 0)], u[min(k + 1, len(u) - 1)], 4001)
    return float(max(d[k], dist(fine).max()))
