"""Lead arcs and start points, measured independently."""

from __future__ import annotations

import math

import pytest

from arcspline.geometry import Point
from arcspline.machining.chains import chain_length
from arcspline.machining.leads import lead_in, lead_out, nearest_start

from .shapes import circle, rectangle


@pytest.mark.parametrize("left", [True, False])
def test_leads_are_tangent_quarter_circles_on_the_chosen_side(left: bool) -> None:
    p, t, radius = Point(3.0, 4.0), (0.6, 0.8), 2.0
    into, out = lead_in(p, t, left, radius), lead_out(p, t, left, radius)
    assert into.end == p
    assert out.start == p
    for arc in (into, out):
        assert abs(arc.sweep_rad) == pytest.approx(math.pi / 2)
        assert math.dist(arc.center, p) == pytest.approx(radius)
        # The centre lies on the asked side of the travel direction.
        side = t[0] * (arc.center[1] - p[1]) - t[1] * (arc.center[0] - p[0])
        assert (side > 0) == left
        # Radius ⟂ tangent at P: the arc is tangent to the path there.
        assert (arc.center[0] - p[0]) * t[0] + (arc.center[1] - p[1]) * t[1] == pytest.approx(
            0.0, abs=1e-12
        )
    # The lead-in comes from behind P, the lead-out goes ahead of it.
    assert (into.start[0] - p[0]) * t[0] + (into.start[1] - p[1]) * t[1] == pytest.approx(-radius)
    assert (out.end[0] - p[0]) * t[0] + (out.end[1] - p[1]) * t[1] == pytest.approx(radius)


def test_nearest_start_splits_where_the_point_is_nearest() -> None:
    loop = circle(0.0, 0.0, 5.0)
    begun = nearest_start(loop, Point(10.0 * math.cos(1.0), 10.0 * math.sin(1.0)), 1e-9)
    assert math.dist(begun[0].start, (5.0 * math.cos(1.0), 5.0 * math.sin(1.0))) < 1e-12
    assert begun[-1].end == begun[0].start
    assert chain_length(begun) == pytest.approx(2 * math.pi * 5.0)


def test_nearest_start_uses_a_joint_it_falls_on() -> None:
    square = rectangle(0, 0, 10, 10)
    begun = nearest_start(square, Point(12.0, 12.0), 1e-9)
    assert begun[0].start == (10.0, 10.0)
    assert len(begun) == 4
