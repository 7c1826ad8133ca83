"""Winding numbers and nesting, against a fine polygon of each contour."""

from __future__ import annotations

import numpy as np
import pytest

from arcspline.geometry import CircularArc, Line, Point
from arcspline.machining.chains import reversed_chain
from arcspline.machining.nesting import nesting, winding_number

from .shapes import circle, rectangle, stadium, star

Element = Line | CircularArc


def _polygon(chain: tuple[Element, ...], per_arc: int = 2000) -> np.ndarray:
    pts: list[tuple[float, float]] = []
    for e in chain:
        if isinstance(e, Line):
            pts.append(e.start)
        else:
            a = e.start_angle_rad + np.linspace(0.0, e.sweep_rad, per_arc, endpoint=False)
            pts += list(
                zip(
                    e.center[0] + e.radius * np.cos(a),
                    e.center[1] + e.radius * np.sin(a),
                    strict=True,
                )
            )
    return np.array(pts, dtype=np.float64)


def _polygon_winding(point: tuple[float, float], poly: np.ndarray) -> int:
    """Crossing-number winding (Sunday's algorithm) of a polygon."""
    x, y = point
    a, b = poly, np.roll(poly, -1, axis=0)
    cross = (b[:, 0] - a[:, 0]) * (y - a[:, 1]) - (x - a[:, 0]) * (b[:, 1] - a[:, 1])
    up = (a[:, 1] <= y) & (b[:, 1] > y) & (cross > 0)
    down = (a[:, 1] > y) & (b[:, 1] <= y) & (cross < 0)
    return int(up.sum() - down.sum())


SHAPES: dict[str, tuple[Element, ...]] = {
    "circle": circle(1.0, 2.0, 3.0),
    "clockwise circle": circle(1.0, 2.0, 3.0, ccw=False, parts=3),
    "stadium": stadium(0.0, 6.0, 1.0, 2.0),
    "reversed stadium": reversed_chain(stadium(0.0, 6.0, 1.0, 2.0)),
    "star": star(0.0, 0.0, 5.0, 2.0),
}


@pytest.mark.parametrize("name", SHAPES)
def test_winding_number_matches_a_fine_polygon(name: str) -> None:
    chain = SHAPES[name]
    poly = _polygon(chain)
    rng = np.random.default_rng(20)
    for x, y in rng.uniform(-7.0, 9.0, size=(400, 2)):
        # Points too near the boundary are where the fine polygon itself is unsure.
        if np.min(np.hypot(poly[:, 0] - x, poly[:, 1] - y)) < 0.05:
            continue
        assert winding_number(Point(x, y), chain) == _polygon_winding((x, y), poly)


def test_depth_and_parent_of_nested_contours() -> None:
    outline = rectangle(0, 0, 100, 60)
    hole = circle(30, 30, 20, ccw=False)
    island = rectangle(25, 25, 35, 35)
    other_hole = rectangle(70, 10, 90, 50)
    open_line = (Line(Point(72.0, 20.0), Point(88.0, 40.0)),)
    contours: list[tuple[Element, ...]] = [island, outline, open_line, hole, other_hole]
    found = nesting(contours, [True, True, False, True, True])
    assert found.depth == (2, 0, 2, 1, 1)
    assert found.parent == (3, None, 4, 1, 1)


def test_an_open_contour_encloses_nothing() -> None:
    around = circle(0, 0, 10)[:3]  # three quarters of a circle, open
    inner = circle(0, 0, 1)
    found = nesting([around, inner], [False, True])
    assert found.depth == (0, 0)
    assert found.parent == (None, None)
