"""Exact input (docs/method.md §1): control points slightly off the paper's form are fitted as
given, and θ near 90° keeps the precision of its parameters.

Every expected value comes from the independent oracle (``tests/support/oracle.py``): the given
points' own Bézier, or the paper's control points in 50-digit decimal arithmetic, never the
core's floating-point formulas.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from arcspline.geometry import STRATEGIES, GeometryError, Spiral, approximate
from tests.support import oracle

PAPER = ((1.5, 3.0), (1.0, 0.0), 51.34, 0.41574)

#: Just inside the form's bound (``FORM_RTOL`` = 1e-6 relative), as coordinates printed with
#: seven digits are.
NEAR = 0.9e-6


def off_form(kind: str) -> np.ndarray:
    """The paper's spiral (Table 1) with its points moved by ``NEAR`` of a leg: the last leg
    longer (``ratio``), the middle leg turned (``middle``; ``B3`` moves with ``B2``), both."""
    cp = oracle.paper_control_points(*PAPER)
    a_leg, b_leg = cp[1] - cp[0], cp[3] - cp[2]
    if kind in ("ratio", "both"):
        cp[3] = cp[3] + NEAR * b_leg
    if kind in ("middle", "both"):
        shift = NEAR * np.array([-a_leg[1], a_leg[0]])
        cp[2] = cp[2] + shift
        cp[3] = cp[3] + shift
    return cp


@pytest.mark.parametrize("strategy", STRATEGIES)
@pytest.mark.parametrize("kind", ["ratio", "middle", "both"])
def test_points_just_off_the_form_are_fitted_as_given(kind: str, strategy: str) -> None:
    given = off_form(kind)
    tolerance = 1e-8  # ~2e-9 of the chord; the points are off the form by ~1e-6
    spline = approximate(Spiral.from_control_points(given.tolist()), tolerance, strategy)
    # The ends are the given points, to the bit; the measurement below checks the rest
    # (end tangents along the given legs, G1, deviation ≤ tolerance both ways).
    assert tuple(spline.segments[0].start) == tuple(given[0])
    assert tuple(spline.segments[-1].end) == tuple(given[3])
    verdict = oracle.check(given, spline, tolerance, samples=20_000)
    assert not verdict.violations, verdict.describe()


def test_points_beyond_the_form_are_still_refused_with_the_amount() -> None:
    cp = oracle.paper_control_points(*PAPER)
    cp[3] = cp[3] + 2e-6 * (cp[3] - cp[2])
    with pytest.raises(GeometryError) as info:
        Spiral.from_control_points(cp.tolist())
    assert info.value.field == "control_points"
    assert "1.2·cos θ" in info.value.message
    assert "2e-06 relative" in info.value.message, info.value.message


# -- θ near 90° -------------------------------------------------------------------------

NEAR_RIGHT_ANGLE = [89.99999, 89.9999999, 89.9999999999]
SHAPES = [((2.0, -1.0), (1.0, 0.0), 1.0), ((-5.0, 7.0), (0.6, -0.8), -3e-3)]


@pytest.mark.parametrize("turn_angle_deg", NEAR_RIGHT_ANGLE)
@pytest.mark.parametrize("shape", SHAPES, ids=["left", "right"])
def test_control_points_near_a_right_angle_are_the_exact_ones(
    shape: tuple[tuple[float, float], tuple[float, float], float], turn_angle_deg: float
) -> None:
    start, tangent, c = shape
    exact = oracle.paper_control_points(start, tangent, turn_angle_deg, c)
    spiral = Spiral.from_parameters(start, tangent, turn_angle_deg, c)
    # A few ulps of the coordinates: what rounding B0 + a·T0 + ... alone costs.
    bound = 8 * oracle.EPS * oracle.coordinate_scale(exact)
    assert np.max(np.abs(spiral.control_points - exact)) <= bound
    t1 = oracle.paper_end_tangent(tangent, turn_angle_deg, c)
    assert math.dist(spiral.end_tangent, t1) <= 4 * oracle.EPS


@pytest.mark.parametrize("strategy", STRATEGIES)
@pytest.mark.parametrize("turn_angle_deg", NEAR_RIGHT_ANGLE)
@pytest.mark.parametrize("shape", SHAPES, ids=["left", "right"])
def test_answers_near_a_right_angle_end_where_the_spiral_ends(
    shape: tuple[tuple[float, float], tuple[float, float], float],
    turn_angle_deg: float,
    strategy: str,
) -> None:
    start, tangent, c = shape
    exact = oracle.paper_control_points(start, tangent, turn_angle_deg, c)
    tolerance = 1e-7 * oracle.chord(exact)
    spiral = Spiral.from_parameters(start, tangent, turn_angle_deg, c)
    spline = approximate(spiral, tolerance, strategy)
    segments = spline.segments
    slack = oracle.rounding_slack(exact)
    assert math.dist(segments[-1].end, exact[3]) <= slack
    # End point, end tangent (against B3 − B2 of the exact points) and G1, with the oracle's
    # rounding bounds; then the two-sided distance to the exact curve. Its foot-point search
    # is an upper bound, so only the bound is asserted: at θ = 90° − 1e-10° the spiral's last
    # ~1e-4 of its parameter turns by 90°, where the oracle's own reading of the reported
    # per-segment maxima is not sharp enough to compare them.
    continuity = oracle.continuity(exact, segments)
    assert not continuity.violations(), continuity.violations()
    assert oracle.arc_violations(segments) == []
    t1 = np.array(oracle.paper_end_tangent(tangent, turn_angle_deg, c))
    last = segments[-1]
    if last.type == "arc":
        radial = np.array(last.end) - np.array(last.center)
        sense = 1.0 if last.direction == "ccw" else -1.0
        along = sense * np.array([-radial[1], radial[0]]) / np.hypot(*radial)
    else:
        along = (np.array(last.end) - np.array(last.start)) / last.length
    cross = along[0] * t1[1] - along[1] * t1[0]
    assert math.atan2(abs(cross), along @ t1) <= continuity.end_angle_bound
    deviation = oracle.measure(exact, segments, samples=20_000)
    assert deviation.max <= tolerance * (1 + 1e-9) + slack, deviation


@pytest.mark.parametrize("size", [1e200, 1.7e308])
def test_control_points_near_the_float_range_are_refused_not_overflowed(size: float) -> None:
    # Differences of such coordinates overflow to inf (a RuntimeWarning, an error under
    # the tests' warning filter) unless their size is refused first.
    points = [[-size, 0.0], [0.0, 0.0], [size, 0.0], [size, size]]
    with pytest.raises(GeometryError, match="must not exceed") as caught:
        Spiral.from_control_points(points)
    assert caught.value.field == "control_points"
