"""Chains: elements of a fitted spline, signed area, self-crossings."""

from __future__ import annotations

import math

import pytest

from arcspline.geometry.curves.segments import CircularArc, Line, Path, Subpath
from arcspline.geometry.offset import crossings, elements_of, signed_area
from arcspline.geometry.paths import approximate_path
from arcspline.geometry.spline import Point
from tests.geometry.offset import shapes
from tests.support import offset_oracle as oracle


def test_elements_of_a_fitted_path_chain_exactly_and_keep_its_arcs() -> None:
    part = shapes.rounded_rectangle(10.0, 6.0, 2.0)
    spline = approximate_path(Path((Subpath(tuple(part), True),)), 0.01)
    elements = elements_of(spline.subpaths[0].spline)
    assert len(elements) == 8
    for a, b in zip(elements, (*elements[1:], elements[0]), strict=True):
        assert a.end == b.start
    assert [type(e) for e in elements] == [type(e) for e in part]
    arcs = [e for e in elements if isinstance(e, CircularArc)]
    assert all(a.radius == 2.0 for a in arcs)


@pytest.mark.parametrize(
    "contour",
    [
        shapes.star(7, 5.0, 2.0),
        shapes.circle((1.0, -2.0), 3.0),
        shapes.dumbbell(2.0, 6.0, 1.0),
        shapes.rounded_rectangle(4.0, 3.0, 1.0),
    ],
)
def test_signed_area_agrees_with_the_oracle_both_ways(contour: list[Line | CircularArc]) -> None:
    expected = oracle.signed_area(oracle.from_core(contour))
    assert signed_area(contour) == pytest.approx(expected, rel=1e-12)
    assert signed_area(shapes.reversed_chain(contour)) == pytest.approx(-expected, rel=1e-12)
    assert expected > 0


def test_a_circle_area() -> None:
    assert signed_area(shapes.circle((3.0, 4.0), 2.0)) == pytest.approx(4 * math.pi, rel=1e-14)


def test_crossings_of_a_figure_eight_and_of_simple_contours() -> None:
    eight = shapes.polygon([(0, 0), (4, 4), (4, 0), (0, 4)])
    assert crossings(eight, True) == (Point(2.0, 2.0),)
    assert crossings(shapes.star(5, 4.0, 2.0), True) == ()
    assert crossings(shapes.circle((0, 0), 1.0), True) == ()
    # an open chain touching itself
    touch = [Line(Point(0, 0), Point(4, 0)), Line(Point(4, 0), Point(2, 2)),
             Line(Point(2, 2), Point(2, 0))]  # fmt: skip
    assert crossings(touch, False) == (Point(2.0, 0.0),)
    assert crossings(touch[:2], False) == ()


def test_a_tiny_loop_is_ignored_when_asked() -> None:
    # a square whose closing corner overlaps itself by a hair
    loop = [Line(Point(-1e-4, 0), Point(4, 0)), Line(Point(4, 0), Point(4, 4)),
            Line(Point(4, 4), Point(0, 4)), Line(Point(0, 4), Point(0, -1e-4)),
            Line(Point(0, -1e-4), Point(-1e-4, 0))]  # fmt: skip
    assert crossings(loop, True) == (Point(0.0, 0.0),)
    assert crossings(loop, True, min_loop=1e-3) == ()
