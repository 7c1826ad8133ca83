"""The core's guarantees, measured by the independent oracle (``tests/support/oracle.py``).

For the paper's spiral at Table 1's tolerances and for the golden cases in ``cases.json``
(both turning senses, θ from 1e-6° to 89.999°, |c| from 1e-4 to 1e4, coordinates up to 1e6,
tolerances from 1e-9 to 1 of the chord): the arc spline starts and ends on the spiral with
its end tangents, is G1, stays within the tolerance both ways, reports the deviation the
oracle measures, and its statistics match its segments. Cases below the tolerance floor
must be refused instead. Nothing here reads the core's internals.
"""

from __future__ import annotations

import json
from functools import cache
from pathlib import Path

import numpy as np
import pytest

from arcspline.geometry import (
    STRATEGIES,
    ArcSpline,
    GeometryError,
    Spiral,
    approximate,
    min_tolerance,
)
from tests.support import oracle

CASES = json.loads((Path(__file__).parent / "cases.json").read_text())["cases"]
SPIRAL_KEYS = ("start", "start_tangent", "turn_angle_deg", "end_curvature")
TABLE1_TOLERANCES = (0.1, 0.01, 0.001, 0.0001, 0.00001)
PAPER = {"start": (1.5, 3.0), "start_tangent": (1.0, 0.0), "turn_angle_deg": 51.34}
REFUSALS = ("tolerance_floor", "precision")


def spiral_of(case: dict) -> Spiral:
    return Spiral.from_parameters(**{k: case[k] for k in SPIRAL_KEYS})


def points_of(case: dict) -> np.ndarray:
    """The case's control points by the oracle's exact arithmetic (not the core's)."""
    return oracle.paper_control_points(*(case[k] for k in SPIRAL_KEYS))


def tolerance_of(case: dict) -> float:
    return float(case["relative_tolerance"] * oracle.chord(points_of(case)))


@cache
def golden(name: str, strategy: str) -> ArcSpline | GeometryError:
    """The core's answer for a golden case (computed once per test process)."""
    case = next(c for c in CASES if c["name"] == name)
    try:
        return approximate(spiral_of(case), tolerance_of(case), strategy=strategy)
    except GeometryError as error:
        return error


def expect_ok(name: str, strategy: str) -> ArcSpline:
    result = golden(name, strategy)
    if isinstance(result, GeometryError):
        pytest.fail(f"{name}: expected an arc spline, got {result.kind} error: {result}")
    return result


OK_CASES = [c["name"] for c in CASES if c["expect"] == "ok"]


# -- the paper's spiral ------------------------------------------------------------------


@pytest.mark.parametrize("strategy", STRATEGIES)
@pytest.mark.parametrize("end_curvature", [0.41574, -0.41574], ids=["left", "right"])
@pytest.mark.parametrize("tolerance", TABLE1_TOLERANCES, ids=lambda t: f"tol={t:g}")
def test_paper_spiral_meets_every_guarantee(
    tolerance: float, end_curvature: float, strategy: str
) -> None:
    spiral = Spiral.from_parameters(**PAPER, end_curvature=end_curvature)
    spline = approximate(spiral, tolerance, strategy=strategy)
    verdict = oracle.check(oracle.paper_control_points(**PAPER, c=end_curvature), spline, tolerance)
    assert not verdict.violations, verdict.describe()
    assert spline.strategy == strategy
    sense = "ccw" if end_curvature > 0 else "cw"
    assert all(s.direction == sense for s in spline.segments if s.type == "arc")


# -- golden cases: one guarantee per test, so a failure names what broke -------------------


@pytest.mark.parametrize("name", OK_CASES)
def test_golden_ends_end_tangents_and_g1(name: str) -> None:
    case = next(c for c in CASES if c["name"] == name)
    spline = expect_ok(name, "subdivide")
    cont = oracle.continuity(points_of(case), spline.segments)
    assert cont.violations() == []


@pytest.mark.parametrize("name", OK_CASES)
def test_golden_segments_are_self_consistent(name: str) -> None:
    assert oracle.arc_violations(expect_ok(name, "subdivide").segments) == []


@pytest.mark.parametrize("name", OK_CASES)
def test_golden_statistics_match_the_segments(name: str) -> None:
    case = next(c for c in CASES if c["name"] == name)
    spline = expect_ok(name, "subdivide")
    cp = points_of(case)
    assert oracle.stats_violations(cp, spline, tolerance_of(case)) == []


@pytest.mark.parametrize("strategy", STRATEGIES)
@pytest.mark.parametrize("name", OK_CASES)
def test_golden_deviation_within_tolerance_and_as_reported(name: str, strategy: str) -> None:
    case = next(c for c in CASES if c["name"] == name)
    spline = expect_ok(name, strategy)
    cp = points_of(case)
    tol = tolerance_of(case)
    dev = oracle.measure(cp, spline.segments)
    problems = oracle.deviation_violations(cp, spline, tol, dev)
    verdict = oracle.Verdict(tol, dev, oracle.continuity(cp, spline.segments), problems)
    assert not problems, verdict.describe()


@pytest.mark.parametrize("name", [c["name"] for c in CASES if c["expect"] == "tolerance_floor"])
def test_golden_cases_below_the_floor_are_refused(name: str) -> None:
    case = next(c for c in CASES if c["name"] == name)
    result = golden(name, "subdivide")
    assert isinstance(result, GeometryError), f"{name}: expected a refusal, got {result!r}"
    assert result.kind == "tolerance_floor"
    assert result.field == "tolerance"
    assert "tolerance" in str(result)
    floor = min_tolerance(spiral_of(case))
    assert result.limit == pytest.approx(floor, rel=1e-12)
    assert tolerance_of(case) < floor


@pytest.mark.parametrize("name", [c["name"] for c in CASES if c["expect"] == "ok_or_refused"])
def test_golden_cases_at_the_edge_are_right_or_refused(name: str) -> None:
    # Where double precision may not deliver the tolerance the core may refuse, naming the
    # tolerance; what it must never do is return an answer that breaks a guarantee.
    case = next(c for c in CASES if c["name"] == name)
    result = golden(name, "subdivide")
    if isinstance(result, GeometryError):
        assert result.field == "tolerance"
        assert result.kind in REFUSALS
        return
    verdict = oracle.check(points_of(case), result, tolerance_of(case))
    assert not verdict.violations, verdict.describe()


# -- the extremes, crossed ---------------------------------------------------------------


@pytest.mark.parametrize("relative_tolerance", [1e-9, 1e-5, 1.0], ids=lambda t: f"rtol={t:g}")
@pytest.mark.parametrize("end_curvature", [1e-4, -1e4], ids=["c=1e-4", "c=-1e4"])
@pytest.mark.parametrize("turn_angle_deg", [1e-6, 89.999], ids=["theta=1e-6", "theta=89.999"])
def test_extremes_are_right_or_refused(
    turn_angle_deg: float, end_curvature: float, relative_tolerance: float
) -> None:
    # Nearly straight and nearly quarter-turn spirals at the ends of the curvature and
    # tolerance ranges, placed a few chords from the origin (so every tolerance here is
    # representable). At 1e-5 of the chord or looser the core must deliver; tighter, it may
    # refuse naming the tolerance, but an answer it gives must meet every guarantee.
    shape = (turn_angle_deg, end_curvature)
    size = oracle.chord(oracle.paper_control_points((0.0, 0.0), (2.0, -1.0), *shape))
    spiral = Spiral.from_parameters((-3.0 * size, 2.0 * size), (2.0, -1.0), *shape)
    points = oracle.paper_control_points((-3.0 * size, 2.0 * size), (2.0, -1.0), *shape)
    tol = relative_tolerance * oracle.chord(points)
    outcome: ArcSpline | GeometryError
    try:
        outcome = approximate(spiral, tol)
    except GeometryError as error:
        outcome = error
    if isinstance(outcome, GeometryError):
        assert relative_tolerance < 1e-5, f"refused a reachable tolerance: {outcome}"
        assert outcome.field == "tolerance"
        assert outcome.kind in REFUSALS
        return
    verdict = oracle.check(points, outcome, tol, samples=30_000)
    assert not verdict.violations, verdict.describe()
