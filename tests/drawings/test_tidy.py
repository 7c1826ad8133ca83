"""Tidying drawn elements: near-coincident control points put on their end points (moving
the curve by at most 4/9 of the distance, checked by sampling both curves), straight
Béziers as lines, elements with no length left out with a warning; and the near cusps of
real drawings (Inkscape's rounding) then fitted where the core refused them before."""

from __future__ import annotations

import math

import numpy as np
import pytest

from arcspline.drawings.model import Element
from arcspline.drawings.tidy import tidy
from arcspline.geometry import GeometryError, approximate_path
from arcspline.geometry.curves.segments import Cubic, Line, Path, Quadratic, Subpath


def _cubic_points(c: Cubic, t: np.ndarray) -> np.ndarray:
    p = np.array([c.start, c.control1, c.control2, c.end], dtype=float)
    s = 1 - t
    weights = np.stack([s**3, 3 * s * s * t, 3 * s * t * t, t**3], axis=1)
    return weights @ p


def _element(*segments: object, closed: bool = False) -> Element:
    return Element(Subpath(tuple(segments), closed), "path#p")  # type: ignore[arg-type]


def test_a_control_point_a_rounding_from_its_end_is_put_on_it() -> None:
    # From car.svg (path#path3153): the first control point 2.6e-6 above the start.
    cubic = Cubic(
        (21.130977, 70.80742389), (21.130977, 70.80742654), (30.95, 65.43), (40.03, 63.58)
    )
    done = tidy([_element(cubic)], snap=5e-4)
    (segment,) = done.elements[0].subpath.segments
    assert isinstance(segment, Cubic)
    assert segment.control1 == cubic.start
    assert segment.control2 == cubic.control2
    t = np.linspace(0, 1, 10_001)
    moved = float(
        np.max(np.linalg.norm(_cubic_points(segment, t) - _cubic_points(cubic, t), axis=1))
    )
    distance = math.dist(cubic.control1, cubic.start)
    assert done.largest_move == pytest.approx(4 / 9 * distance)
    assert moved <= done.largest_move * (1 + 1e-9)
    assert moved >= done.largest_move * 0.999  # the bound is the true largest move


def test_both_inner_control_points_moved_are_bounded_together() -> None:
    # (0,0) (0,d) (10,d) (10,0): both inner points snap; the curve moves by 3/4·d at t = ½,
    # more than either alone (4/9·d).
    d = 4e-4
    cubic = Cubic((0.0, 0.0), (0.0, d), (10.0, d), (10.0, 0.0))
    done = tidy([_element(cubic)], snap=5e-4)
    (segment,) = done.elements[0].subpath.segments
    assert segment == Line((0.0, 0.0), (10.0, 0.0))  # both inner points on the ends: straight
    t = np.linspace(0, 1, 10_001)
    moved = float(np.max(np.abs(_cubic_points(cubic, t)[:, 1])))  # distance to the line y = 0
    assert moved == pytest.approx(0.75 * d, rel=1e-6)
    assert done.largest_move >= moved


def test_a_quadratic_control_point_moves_to_its_nearer_end_only() -> None:
    # A short quadratic whose control point is within snap of both ends.
    quad = Quadratic((0.0, 0.0), (0.6e-4, 0.3e-4), (1e-4, 0.0))
    done = tidy([_element(quad)], snap=5e-4)
    (segment,) = done.elements[0].subpath.segments
    assert segment == Line((0.0, 0.0), (1e-4, 0.0))
    t = np.linspace(0, 1, 10_001)
    s = 1 - t
    p = np.outer(s * s, quad.start) + np.outer(2 * s * t, quad.control) + np.outer(t * t, quad.end)
    moved = float(np.max(np.abs(p[:, 1])))  # the line is y = 0
    assert moved <= done.largest_move


def test_a_control_point_further_than_snap_stays() -> None:
    cubic = Cubic((0.0, 0.0), (0.0, 1e-3), (1.0, 1.0), (2.0, 0.0))
    done = tidy([_element(cubic)], snap=1e-4)
    assert done.elements[0].subpath.segments == (cubic,)
    assert done.largest_move == 0


@pytest.mark.parametrize(
    "segment",
    [
        # zebra.svg: both control points on the end point (a straight segment, traced fast)
        Cubic((83.34375, 61.45831625), (83.0791666, 61.9874829), (83.0791666, 61.9874829),
              (83.0791666, 61.9874829)),
        Cubic((0.0, 0.0), (0.0, 0.0), (3.0, 4.0), (3.0, 4.0)),
        Quadratic((0.0, 0.0), (0.0, 0.0), (3.0, 4.0)),
    ],
)  # fmt: skip
def test_straight_beziers_become_their_line(segment: Cubic | Quadratic) -> None:
    done = tidy([_element(segment)], snap=0.0)
    assert done.elements[0].subpath.segments == (Line(segment.start, segment.end),)
    assert done.largest_move == 0


def test_elements_without_length_are_left_out_and_counted() -> None:
    point = (5.0, 5.0)
    dot = _element(Line(point, point))
    blob = _element(Cubic(point, point, point, point))
    line = _element(Line((0.0, 0.0), (1.0, 0.0)))
    done = tidy([dot, line, blob], snap=0.0)
    assert [e.subpath for e in done.elements] == [line.subpath]
    (warning,) = done.warnings
    assert warning.occurrences == 2
    assert "no length" in warning.reason


def test_a_near_cusp_the_core_refuses_is_fitted_once_tidied() -> None:
    # zebra.svg, path at line 9: a cubic straight but for its doubled end point.
    end = (83.07916666666667, 61.98748291666669)
    cusp = Cubic((83.34375, 61.458316249999996), end, end, end)
    lead = Line((80.0, 60.0), cusp.start)
    with pytest.raises(GeometryError):
        approximate_path(Path((Subpath((lead, cusp)),)), 0.01)
    done = tidy([_element(lead, cusp)], snap=5e-4)
    result = approximate_path(Path((done.elements[0].subpath,)), 0.01)
    assert result.stats.max_deviation <= 0.01
