"""Limits and bad input: the segment cap, the tolerance floor, bad tolerances and strategies,
and batches that hold a bad request among good ones. Every refusal is a GeometryError that
names the input and the limit; nothing hangs (each test here has a hard time limit)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from arcspline.geometry import (
    DEFAULT_LIMITS,
    STRATEGIES,
    ArcSpline,
    GeometryError,
    Limits,
    Spiral,
    approximate,
    approximate_many,
    min_tolerance,
)
from tests.support import oracle

pytestmark = pytest.mark.timeout(120)

EPS = 2.0**-52
PAPER = Spiral.from_parameters((1.5, 3.0), (1.0, 0.0), 51.34, 0.41574)


def assert_same(a: ArcSpline | GeometryError, b: ArcSpline | GeometryError) -> None:
    """The same refusal, or the same segments and statistics, bit for bit."""
    if isinstance(b, GeometryError):
        assert isinstance(a, GeometryError)
        assert (a.field, a.kind, a.limit) == (b.field, b.kind, b.limit)
        return
    assert isinstance(a, ArcSpline)
    np.testing.assert_array_equal(a.table, b.table)
    assert a.stats == b.stats
    assert a.tolerance == b.tolerance


# -- the segment cap ------------------------------------------------------------------------


def test_segment_cap_refuses_naming_the_limit() -> None:
    with pytest.raises(GeometryError) as info:
        approximate(PAPER, 1e-5, limits=Limits(max_segments=10))
    err = info.value
    assert err.kind == "segment_limit"
    assert err.field == "tolerance"
    assert err.limit == 10
    assert "10" in err.message
    assert "segment" in err.message


@pytest.mark.parametrize(
    "limits",
    [
        {"max_segments": 0},
        {"max_segments": -1},
        {"max_segments": 2**31},
        {"max_segments": 10.0},
        {"max_segments": True},
        {"min_relative_tolerance": 0.0},
        {"min_relative_tolerance": 1.0},
        {"min_relative_tolerance": float("nan")},
    ],
    ids=str,
)
def test_limits_the_kernels_cannot_take_are_refused(limits: dict[str, float]) -> None:
    with pytest.raises(ValueError, match=next(iter(limits))):
        Limits(**limits)  # type: ignore[arg-type]


def test_segment_cap_is_inclusive() -> None:
    # Table 1: 54 arcs at 1e-5. A cap of 54 admits it; 53 does not.
    spline = approximate(PAPER, 1e-5, limits=Limits(max_segments=54))
    assert len(spline) == 54
    with pytest.raises(GeometryError) as info:
        approximate(PAPER, 1e-5, limits=Limits(max_segments=53))
    assert info.value.kind == "segment_limit"
    assert info.value.limit == 53


@pytest.mark.parametrize("strategy", STRATEGIES)
def test_at_the_floor_a_quarter_turn_spiral_is_right_or_refused(strategy: str) -> None:
    # θ → 90° with |c| = 1e4 spans ~3e5 with curvature from 0 to 1e4: at the floor it needs
    # many segments of wildly different radii. The core may stop at the cap or at the limit
    # of precision, promptly; an answer it gives must meet every guarantee.
    spiral = Spiral.from_parameters((0.0, 0.0), (1.0, 0.0), 89.999, 1e4)
    tol = min_tolerance(spiral) * 1.0001
    outcome: ArcSpline | GeometryError
    try:
        outcome = approximate(spiral, tol, strategy=strategy)
    except GeometryError as err:
        outcome = err
    if isinstance(outcome, GeometryError):
        assert outcome.kind in ("segment_limit", "precision")
        assert outcome.field == "tolerance"
        return
    assert len(outcome) <= DEFAULT_LIMITS.max_segments
    verdict = oracle.check(spiral.control_points, outcome, tol, samples=20_000)
    assert not verdict.violations, verdict.describe()


# -- the tolerance floor --------------------------------------------------------------------


def test_min_tolerance_is_positive_and_bounds_the_relative_floor() -> None:
    floor = min_tolerance(PAPER)
    assert math.isfinite(floor)
    assert floor > 0
    assert floor >= DEFAULT_LIMITS.min_relative_tolerance * PAPER.chord * (1 - 1e-12)
    # Near the origin the floor leaves the advertised range (down to 1e-9 of the chord) open.
    assert floor <= 1e-9 * PAPER.chord
    assert min_tolerance(PAPER, Limits(min_relative_tolerance=1e-3)) >= 1e-3 * PAPER.chord


def test_min_tolerance_grows_with_the_coordinates() -> None:
    # Below one ulp of the coordinates no answer can be vouched for.
    far = Spiral.from_parameters((1e6, -1e6), (1.0, 0.0), 51.34, 0.41574)
    assert min_tolerance(far) >= EPS * far.coordinate_scale
    assert min_tolerance(far) > min_tolerance(PAPER)


@pytest.mark.parametrize(
    "spiral",
    [PAPER, Spiral.from_parameters((1e6, 1e6), (0.0, -1.0), 30.0, -2.0)],
    ids=["paper", "far-1e6"],
)
def test_just_below_the_floor_is_refused_just_above_works(spiral: Spiral) -> None:
    floor = min_tolerance(spiral)
    below = floor * (1 - 1e-6)
    with pytest.raises(GeometryError) as info:
        approximate(spiral, below)
    err = info.value
    assert err.kind == "tolerance_floor"
    assert err.field == "tolerance"
    assert err.limit == pytest.approx(floor, rel=1e-12)
    assert "tolerance" in str(err)
    above = floor * (1 + 1e-6)
    spline = approximate(spiral, above)
    verdict = oracle.check(spiral.control_points, spline, above, samples=10_000)
    assert not verdict.violations, verdict.describe()


def test_a_stricter_relative_floor_from_limits() -> None:
    limits = Limits(min_relative_tolerance=1e-3)
    with pytest.raises(GeometryError) as info:
        approximate(PAPER, 0.9e-3 * PAPER.chord, limits=limits)
    assert info.value.kind == "tolerance_floor"
    assert len(approximate(PAPER, 1.1e-3 * PAPER.chord, limits=limits)) > 0


# -- bad tolerance and strategy ---------------------------------------------------------------


@pytest.mark.parametrize(
    "tolerance",
    [float("nan"), float("inf"), float("-inf"), 0.0, -0.0, -1e-3, "0.01", None, np.float32(1e-3)],
    ids=["nan", "inf", "-inf", "zero", "-zero", "negative", "string", "none", "float32"],
)
def test_bad_tolerance_names_the_field(tolerance: object) -> None:
    with pytest.raises(GeometryError) as info:
        approximate(PAPER, tolerance)  # type: ignore[arg-type]
    assert info.value.field == "tolerance"
    assert info.value.kind == "invalid_input"


@pytest.mark.parametrize("strategy", ["", "SUBDIVIDE", "fewest_arcs", "bisect"])
def test_unknown_strategy_names_the_field(strategy: str) -> None:
    with pytest.raises(GeometryError) as info:
        approximate(PAPER, 1e-3, strategy=strategy)  # type: ignore[arg-type]
    assert info.value.field == "strategy"
    assert info.value.kind == "invalid_input"
    for known in STRATEGIES:
        assert known in info.value.message
    with pytest.raises(GeometryError) as info:
        approximate_many([PAPER], [1e-3], strategy=strategy)  # type: ignore[arg-type]
    assert info.value.field == "strategy"


# -- batches ------------------------------------------------------------------------------


def test_a_bad_request_in_a_batch_is_returned_in_place() -> None:
    right = Spiral.from_parameters((0.0, 0.0), (0.0, 1.0), 30.0, -2.0)
    spirals = [PAPER, right, PAPER, right, PAPER]
    tolerances = [1e-3, float("nan"), 1e-4, min_tolerance(right) / 2, 1e-5]
    results = approximate_many(spirals, tolerances)
    assert len(results) == 5
    assert isinstance(results[1], GeometryError)
    assert (results[1].field, results[1].kind) == ("tolerance", "invalid_input")
    assert isinstance(results[3], GeometryError)
    assert (results[3].field, results[3].kind) == ("tolerance", "tolerance_floor")
    for j in (0, 2, 4):
        assert_same(results[j], approximate(spirals[j], tolerances[j]))
    assert [len(r) for r in results if isinstance(r, ArcSpline)] == [12, 26, 54]


def test_a_tolerance_that_is_not_a_number_in_a_batch_is_returned_in_place() -> None:
    results = approximate_many([PAPER, PAPER, PAPER], [1e-3, "1e-3", 1e-2])  # type: ignore[list-item]
    assert isinstance(results[1], GeometryError)
    assert (results[1].field, results[1].kind) == ("tolerance", "invalid_input")
    assert "'1e-3'" in results[1].message
    assert_same(results[0], approximate(PAPER, 1e-3))
    assert_same(results[2], approximate(PAPER, 1e-2))


def test_a_capped_request_in_a_batch_is_returned_in_place() -> None:
    limits = Limits(max_segments=20)
    results = approximate_many([PAPER, PAPER, PAPER], [1e-2, 1e-5, 1e-3], limits=limits)
    assert isinstance(results[1], GeometryError)
    assert results[1].kind == "segment_limit"
    assert results[1].limit == 20
    assert [len(r) for r in (results[0], results[2])] == [8, 12]
    # The refused spiral has no rows: its neighbours' statistics are still their own.
    assert_same(results[0], approximate(PAPER, 1e-2, limits=limits))
    assert_same(results[2], approximate(PAPER, 1e-3, limits=limits))


@pytest.mark.parametrize("copies", [1, 12], ids=["small", "large: several row blocks"])
def test_every_kind_of_spiral_in_a_batch_is_as_alone(copies: int) -> None:
    # Each batch mixes flat arcs (lines), many pieces, the segment limit and a tolerance below
    # the floor; the large one fills more than the kernels' first block of rows.
    flat = Spiral.from_parameters((0.0, 0.0), (1.0, 1.0), 1e-9, 1e-4)
    limits = Limits(max_segments=200)
    cases = [
        (PAPER, 1e-3),
        (flat, 1e-6 * flat.chord),
        (PAPER, 1e-7 * PAPER.chord),  # hundreds of pieces
        (PAPER, 1e-9),  # beyond the segment limit
        (PAPER, min_tolerance(PAPER) / 2),
        (PAPER, 1e-5),
    ] * copies
    results = approximate_many([s for s, _ in cases], [t for _, t in cases], limits=limits)
    for (spiral, tolerance), got in zip(cases, results, strict=True):
        try:
            alone: ArcSpline | GeometryError = approximate(spiral, tolerance, limits=limits)
        except GeometryError as error:
            alone = error
        assert_same(got, alone)
    kinds = [r.kind if isinstance(r, GeometryError) else len(r) for r in results[:6]]
    assert (kinds[0], kinds[5]) == (12, 54)
    assert kinds[3:5] == ["segment_limit", "tolerance_floor"]
    line_count = results[1].stats.line_count  # type: ignore[union-attr]
    assert line_count > 0


def test_batch_edge_cases() -> None:
    assert approximate_many([], []) == []
    with pytest.raises(ValueError, match="length"):
        approximate_many([PAPER, PAPER], [1e-3])


@pytest.mark.parametrize(
    ("end_curvature", "turn_angle_deg"),
    # At 89.5° the denominator 54·|c|·cos θ itself underflows to 0 (found by schemathesis).
    [(5e-324, 50.0), (-1e-310, 50.0), (5e-324, 89.5)],
)
def test_a_curvature_so_small_the_size_overflows_says_so(
    end_curvature: float, turn_angle_deg: float
) -> None:
    # |c| is finite and non-zero; it is the size a ~ 1/c that leaves double precision.
    with pytest.raises(GeometryError, match=r"size a = -?inf, outside the supported") as caught:
        Spiral.from_parameters((0.0, 0.0), (1.0, 0.0), turn_angle_deg, end_curvature)
    assert caught.value.field == "end_curvature"
    assert caught.value.kind == "invalid_input"


@pytest.mark.parametrize(
    ("start", "turn_angle_deg", "end_curvature"),
    [
        ((-1.1959e16, -6.3419e16), 5.83e-307, -0.5),  # size a is subnormal (found by schemathesis)
        ((1e6, 1e6), 30.0, 1e8),  # a spiral of 3e-9 at coordinates of 1e6
        ((0.0, 0.0), 30.0, 1e-160),  # a spiral of 1e160
        ((1e200, 0.0), 30.0, 1.0),  # coordinates beyond 1e150
    ],
)
def test_spirals_double_precision_cannot_hold_are_refused(
    start: tuple[float, float], turn_angle_deg: float, end_curvature: float
) -> None:
    with pytest.raises(GeometryError) as caught:
        Spiral.from_parameters(start, (1.0, 0.0), turn_angle_deg, end_curvature)
    assert caught.value.field in {"start", "end_curvature"}
    assert caught.value.kind == "invalid_input"
