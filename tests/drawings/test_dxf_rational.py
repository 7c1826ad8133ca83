"""Rational cubic → cubics with a certified bound, checked by an independent dense sampling of
the rational Bernstein formula against the cubics (tests/support/nurbs_oracle.py)."""

from __future__ import annotations

import math

import pytest

from arcspline.drawings.dxf_rational import hermite_bound, rational_cubic_fit
from arcspline.geometry.curves.segments import Cubic
from arcspline.geometry.spline import Point
from tests.support.nurbs_oracle import cubic_chain, hausdorff, rational_bezier

# weights 1, 3, 0.5, 2: w·x/w is exact at the ends, so the end points can be compared exactly
POINTS = [(0.0, 0.0), (1.0, 2.0), (3.0, 2.0), (4.0, 0.0)]
WEIGHTS = [1.0, 3.0, 0.5, 2.0]


def homogeneous(points: list[tuple[float, float]], weights: list[float]):  # type: ignore[no-untyped-def]
    return [(w * x, w * y, w) for (x, y), w in zip(points, weights, strict=True)]


def cross(u: tuple[float, float], v: tuple[float, float]) -> float:
    return u[0] * v[1] - u[1] * v[0]


def direction(p: tuple[float, float], q: tuple[float, float]) -> tuple[float, float]:
    dx, dy = q[0] - p[0], q[1] - p[1]
    n = math.hypot(dx, dy)
    return dx / n, dy / n


def assert_same_direction(u: tuple[float, float], v: tuple[float, float]) -> None:
    assert abs(cross(u, v)) < 1e-9
    assert u[0] * v[0] + u[1] * v[1] > 0


@pytest.mark.parametrize(
    ("points", "weights", "tolerance"),
    [
        (POINTS, WEIGHTS, 1e-1),
        (POINTS, WEIGHTS, 1e-3),
        (POINTS, WEIGHTS, 1e-6),
        ([(10.0, -5.0), (40.0, 30.0), (-20.0, 60.0), (35.0, 12.0)], [4.0, 0.25, 7.0, 1.0], 1e-4),
        ([(0.0, 0.0), (0.0, 1.0), (1.0, 1.0), (1.0, 0.0)], [1.0, 20.0, 20.0, 1.0], 1e-5),
    ],
)
def test_cubics_are_within_the_certified_bound(
    points: list[tuple[float, float]], weights: list[float], tolerance: float
) -> None:
    fit = rational_cubic_fit(homogeneous(points, weights), Point(*points[0]), tolerance, 4096)
    assert fit is not None
    assert 0.0 < fit.bound <= tolerance
    measured = hausdorff(rational_bezier(points, weights), cubic_chain(fit.cubics))
    assert measured <= fit.bound
    assert measured >= fit.bound / 1000  # the bound is not absurdly loose
    # end points exact, chained bit for bit
    assert fit.cubics[0].start == points[0]
    assert fit.cubics[-1].end == points[-1]
    for a, b in zip(fit.cubics, fit.cubics[1:], strict=False):
        assert a.end == b.start
        # G1 at every join: the rational curve is smooth there
        assert_same_direction(direction(a.control2, a.end), direction(b.start, b.control1))
    # the end tangents are the rational curve's: R'(0) ∥ P1 − P0, R'(1) ∥ P3 − P2
    first, last = fit.cubics[0], fit.cubics[-1]
    assert_same_direction(direction(first.start, first.control1), direction(points[0], points[1]))
    assert_same_direction(direction(last.control2, last.end), direction(points[2], points[3]))


def test_one_cubic_when_the_tolerance_allows_and_the_bound_is_close() -> None:
    fit = rational_cubic_fit(homogeneous(POINTS, WEIGHTS), Point(*POINTS[0]), 20.0, 4096)
    assert fit is not None
    (cubic,) = fit.cubics
    # Hermite: C1 = P0 + (w1/w0)(P1 − P0) = (3, 6), C2 = P3 − (w2/w3)(P3 − P2) = (3.75, 0.5)
    assert cubic == Cubic((0.0, 0.0), (3.0, 6.0), (3.75, 0.5), (4.0, 0.0))
    measured = hausdorff(rational_bezier(POINTS, WEIGHTS), cubic_chain(fit.cubics))
    assert measured <= fit.bound <= 20.0
    assert measured >= fit.bound / 1000


def test_more_pieces_for_a_smaller_tolerance_and_the_budget_is_kept() -> None:
    pieces = homogeneous(POINTS, WEIGHTS)
    counts = []
    for tolerance in (1e-2, 1e-4, 1e-6):
        fit = rational_cubic_fit(pieces, Point(*POINTS[0]), tolerance, 4096)
        assert fit is not None
        counts.append(len(fit.cubics))
    assert counts == sorted(counts)
    assert counts[0] < counts[-1]
    # the error of a Hermite cubic falls as h⁴: 100 times smaller needs about 100^¼ ≈ 3×
    assert counts[-1] < 10 * counts[1]
    assert rational_cubic_fit(pieces, Point(*POINTS[0]), 1e-300, 64) is None


def test_equal_weights_give_the_cubic_itself() -> None:
    fit = hermite_bound(homogeneous(POINTS, [2.0] * 4), Point(*POINTS[0]))
    assert fit.cubic == Cubic(*(Point(*p) for p in POINTS))
    assert fit.bound < 1e-12  # rounding allowance only


def test_weights_must_be_positive() -> None:
    with pytest.raises(ValueError, match="weights > 0"):
        rational_cubic_fit(homogeneous(POINTS, [1.0, -1.0, 1.0, 1.0]), Point(0, 0), 1.0, 10)
