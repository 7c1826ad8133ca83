"""Property tests over random valid spirals and tolerances, measured by the oracle.

Spirals: start anywhere in ±1e3, any non-zero start tangent, θ in (0.01°, 89.9°), |c| from
1e-3 to 1e3 of either sign; tolerances from 1e-7 to 1e-1 of the chord. For each: the ends
and end tangents match, the spline is G1, and the two-sided distance is within the
tolerance (and as reported). A batch equals the same requests one by one.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import HealthCheck, Phase, assume, given, settings
from hypothesis import strategies as st

from arcspline.geometry import (
    ArcSpline,
    GeometryError,
    Spiral,
    approximate,
    approximate_many,
    min_tolerance,
)
from tests.support import oracle

# Modest and deterministic: the suite must stay fast and reproducible in CI.
PROPERTY = settings(
    max_examples=40,
    deadline=None,
    derandomize=True,
    suppress_health_check=[HealthCheck.too_slow],
    phases=[Phase.explicit, Phase.reuse, Phase.generate, Phase.shrink],
)

coordinate = st.floats(-1e3, 1e3, allow_nan=False, allow_infinity=False)
exponent = st.floats(-3.0, 3.0)


@st.composite
def spirals(draw: st.DrawFn) -> Spiral:
    heading = draw(st.floats(0.0, 2 * math.pi, exclude_max=True))
    length = 10 ** draw(st.floats(-3.0, 3.0))
    sign = draw(st.sampled_from([1.0, -1.0]))
    return Spiral.from_parameters(
        start=(draw(coordinate), draw(coordinate)),
        start_tangent=(length * math.cos(heading), length * math.sin(heading)),
        turn_angle_deg=draw(st.floats(0.01, 89.9, exclude_min=True, exclude_max=True)),
        end_curvature=sign * 10 ** draw(exponent),
    )


relative_tolerances = st.floats(-7.0, -1.0).map(lambda e: 10**e)


@PROPERTY
@given(spiral=spirals(), relative=relative_tolerances)
def test_random_spirals_meet_the_guarantees(spiral: Spiral, relative: float) -> None:
    tol = relative * oracle.chord(spiral.control_points)
    # A spiral tiny beside its distance from the origin can put this tolerance below what
    # double precision resolves there; that case is the floor's (next test).
    assume(tol >= min_tolerance(spiral))
    spline = approximate(spiral, tol)
    cp = spiral.control_points
    cont = oracle.continuity(cp, spline.segments)
    dev = oracle.measure(cp, spline.segments, samples=8_000, pairs=100_000)
    problems = cont.violations() + oracle.deviation_violations(cp, spline, tol, dev)
    verdict = oracle.Verdict(tol, dev, cont, problems)
    assert not problems, f"{spiral!r}\n{verdict.describe()}"


@PROPERTY
@given(spiral=spirals(), relative=relative_tolerances)
def test_below_the_floor_is_refused_not_approximated(spiral: Spiral, relative: float) -> None:
    floor = min_tolerance(spiral)
    tol = min(relative * spiral.chord, floor * 0.5)
    with pytest.raises(GeometryError) as info:
        approximate(spiral, tol)
    assert info.value.kind == "tolerance_floor"
    assert info.value.field == "tolerance"


@PROPERTY
@given(
    requests=st.lists(st.tuples(spirals(), relative_tolerances), min_size=1, max_size=6),
)
def test_a_batch_equals_one_by_one(requests: list[tuple[Spiral, float]]) -> None:
    spirals_ = [s for s, _ in requests]
    tols = [r * s.chord for s, r in requests]
    batch = approximate_many(spirals_, tols)
    assert len(batch) == len(requests)
    for got, spiral, tol in zip(batch, spirals_, tols, strict=True):
        try:
            alone: ArcSpline | GeometryError = approximate(spiral, tol)
        except GeometryError as error:
            alone = error
        if isinstance(alone, GeometryError):
            assert isinstance(got, GeometryError)
            assert (got.field, got.kind, got.limit) == (alone.field, alone.kind, alone.limit)
            continue
        assert isinstance(got, ArcSpline)
        # Bit for bit: every number of every segment and of the statistics.
        np.testing.assert_array_equal(got.table, alone.table)
        assert got.stats == alone.stats
