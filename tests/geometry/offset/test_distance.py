"""segment_distance and chain_distance against dense sampling (an independent estimate:
the minimum over sample pairs bounds the exact distance from above, within the sampling
step)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from arcspline.geometry.curves.segments import CircularArc, Line
from arcspline.geometry.offset import chain_distance, segment_distance
from arcspline.geometry.spline import Point
from tests.geometry.offset import shapes
from tests.support import offset_oracle as oracle


def _samples(e: Line | CircularArc, n: int = 4001) -> np.ndarray:
    t = np.linspace(0.0, 1.0, n)
    if isinstance(e, Line):
        a, b = np.array(e.start), np.array(e.end)
        return a + t[:, None] * (b - a)
    angle = e.start_angle_rad + t * e.sweep_rad
    return np.column_stack([e.center[0] + e.radius * np.cos(angle),
                            e.center[1] + e.radius * np.sin(angle)])  # fmt: skip


def _brute(a: Line | CircularArc, b: Line | CircularArc) -> float:
    pa = _samples(a)
    # exact distance from each sample of a to b, by the oracle
    return float(oracle.distance_to(pa, oracle.from_core([b])).min())


elements = st.one_of(
    st.builds(
        lambda x0, y0, x1, y1: Line(Point(x0, y0), Point(x1, y1)),
        *(st.floats(-5, 5) for _ in range(4)),
    ),
    st.builds(
        lambda cx, cy, r, a0, sw: shapes.arc((cx, cy), r, a0, sw),
        st.floats(-5, 5), st.floats(-5, 5), st.floats(0.1, 5), st.floats(-4, 4),
        st.floats(0.05, 6.2).flatmap(lambda s: st.sampled_from([s, -s])),
    ),
)  # fmt: skip


@settings(max_examples=150, deadline=None)
@given(a=elements, b=elements)
def test_segment_distance_is_the_sampled_minimum(
    a: Line | CircularArc, b: Line | CircularArc
) -> None:
    if isinstance(a, Line) and a.start == a.end:
        return
    exact = segment_distance(a, b)
    sampled = _brute(a, b)
    size = max(1.0, math.dist(a.start, a.end), getattr(a, "radius", 0.0) * 6.3)
    # the exact minimum is at most any sample's and at least it less the sampling step
    assert exact <= sampled + 1e-12
    assert exact >= sampled - size * 6.3 / 4000
    assert segment_distance(b, a) == pytest.approx(exact, abs=1e-12), (repr(a), repr(b))


def test_tangent_and_crossing_elements() -> None:
    circle = shapes.arc((0.0, 0.0), 1.0, 0.0, math.pi)
    assert segment_distance(circle, Line(Point(-2.0, 1.0), Point(2.0, 1.0))) == 0.0
    assert segment_distance(circle, Line(Point(-2.0, 1.5), Point(2.0, 1.5))) == pytest.approx(0.5)
    assert segment_distance(circle, Line(Point(0.0, 0.0), Point(0.0, 3.0))) == 0.0
    # the lower half is not part of the arc: the nearest point is an end
    below = Line(Point(-0.5, -2.0), Point(0.5, -2.0))
    assert segment_distance(circle, below) == pytest.approx(math.hypot(0.5, 2.0))
    other = shapes.arc((3.0, 0.0), 1.0, math.pi / 2, math.pi)
    assert segment_distance(circle, other) == pytest.approx(1.0)


def test_chain_distance_against_the_oracle() -> None:
    star = shapes.star(5, 4.0, 2.0)
    rng = np.random.default_rng(7)
    points = rng.uniform(-6, 6, size=(200, 2))
    expected = oracle.distance_to(points, oracle.from_core(star))
    got = [chain_distance(Point(*p), star) for p in points.tolist()]
    assert got == pytest.approx(expected.tolist(), abs=1e-12)
