"""Intersections of lines and arcs, including tangency and nearly flat arcs."""

from __future__ import annotations

import math

import numpy as np
import pytest

from arcspline.geometry.curves.segments import Line
from arcspline.geometry.offset.intersect import hits
from arcspline.geometry.offset.table import table_of
from arcspline.geometry.spline import Point
from tests.geometry.offset import shapes

TOL = 1e-12


def _hits(a, b):  # type: ignore[no-untyped-def]
    t = table_of([a, b])
    return hits(t.take(np.array([0])), t.take(np.array([1])), TOL)


def test_crossing_lines_and_parallel_overlap() -> None:
    found = _hits(Line(Point(0, 0), Point(2, 2)), Line(Point(0, 2), Point(2, 0)))
    assert found.point.tolist() == [[1.0, 1.0]]
    assert found.ta.tolist() == [0.5]
    assert found.tb.tolist() == [0.5]
    overlap = _hits(Line(Point(0, 0), Point(2, 0)), Line(Point(1, 0), Point(3, 0)))
    assert sorted(map(tuple, overlap.point.tolist())) == [(1.0, 0.0), (2.0, 0.0)]
    assert (
        len(_hits(Line(Point(0, 0), Point(2, 0)), Line(Point(0, 1e-6), Point(2, 1e-6))).pair) == 0
    )


def test_a_tangent_line_touches_once() -> None:
    arc = shapes.arc((0.0, 0.0), 1.0, 0.0, math.pi)
    found = _hits(Line(Point(-2, 1), Point(2, 1)), arc)
    assert found.point.tolist() == [[0.0, 1.0]]
    two = _hits(Line(Point(-2, 0.5), Point(2, 0.5)), arc)
    assert sorted(two.point[:, 0].tolist()) == pytest.approx([-math.sqrt(0.75), math.sqrt(0.75)])
    assert two.point[:, 1].tolist() == pytest.approx([0.5, 0.5])


def test_tangent_circles_touch_once() -> None:
    a = shapes.arc((0.0, 0.0), 1.0, -1.0, 2.0)
    b = shapes.arc((3.0, 0.0), 2.0, 2.0, 2.5)
    found = _hits(a, b)
    assert len(found.pair) == 1
    assert found.point[0].tolist() == pytest.approx([1.0, 0.0])


def test_a_nearly_flat_arc_crosses_a_small_circle_where_it_should() -> None:
    # a 1e5-radius arc through the origin, nearly the x axis, and a unit circle about (0, 0.3)
    radius = 1e5
    flat = shapes.arc((0.0, radius), radius, -math.pi / 2 - 1e-5, 2e-5)
    small = shapes.arc((0.0, 0.3), 1.0, -math.pi, math.pi)
    found = _hits(flat, small)
    # independently: y = R − sqrt(R² − x²) on the big circle, x² + (y − 0.3)² = 1 on the small
    for x, y in found.point.tolist():
        assert math.hypot(x, y - radius) == pytest.approx(radius, abs=1e-9)
        assert math.hypot(x, y - 0.3) == pytest.approx(1.0, abs=1e-12)
    assert len(found.pair) == 2
    assert found.point[0, 0] * found.point[1, 0] < 0  # one on each side
