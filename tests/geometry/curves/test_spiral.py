"""The spiral (docs/method.md §1): both input forms, evaluation, curvature, length and bad input.

Every expected value is computed here or by the oracle's own Bernstein code, never by the
class under test.
"""

from __future__ import annotations

import math
import pickle
import re

import numpy as np
import pytest

from arcspline.geometry import GeometryError, Spiral
from tests.support import oracle

EPS = float(np.finfo(np.float64).eps)

# (start, start_tangent, turn_angle_deg, end_curvature): both senses, tangents in every
# quadrant, θ from 0.001° to 89.9°, |c| over eight decades, coordinates up to 1e6.
SPIRALS = [
    ((1.5, 3.0), (1.0, 0.0), 51.34, 0.41574),
    ((1.5, 3.0), (1.0, 0.0), 51.34, -0.41574),
    ((-2.0, 7.0), (0.0, 3.0), 0.001, 1e-4),
    ((0.0, 0.0), (-1.0, -1.0), 89.9, -1e4),
    ((1e6, -1e6), (0.6, -0.8), 30.0, 1e-3),
    ((5.0, -4.0), (-2.0, 0.5), 10.0, 250.0),
    ((-3e5, 2e5), (1.0, 2.0), 75.0, -0.02),
]
IDS = [f"theta={s[2]}-c={s[3]}" for s in SPIRALS]


def expected_control_points(start, tangent, theta_deg, c) -> np.ndarray:
    """§1 by the oracle's exact arithmetic: a = 25 tanθ / (54 |c| cosθ), b = 5 tanθ / (9 |c|),
    T1 = T0 turned by ±θ (never the core's floating-point cos(radians θ))."""
    return oracle.paper_control_points(start, tangent, theta_deg, c)


def cross(a, b) -> float:
    """The scalar ``a×b = ax·by − ay·bx`` (docs/method.md notation)."""
    return float(a[0] * b[1] - a[1] * b[0])


def direction_tol(cp: np.ndarray) -> float:
    """Angle rounding of a leg direction: 64 ulps of the coordinates over the shorter leg."""
    legs = min(math.dist(cp[0], cp[1]), math.dist(cp[2], cp[3]))
    return 64 * EPS * (1 + float(np.max(np.abs(cp))) / legs)


def numbers_in(text: str) -> list[float]:
    return [float(x) for x in re.findall(r"[-+]?\d+(?:\.\d+)?(?:[eE][-+]?\d+)?", text)]


def plain(text: str) -> str:
    """The message with Unicode minus signs as ASCII and without spaces, for matching."""
    return text.replace("−", "-").replace(" ", "")


@pytest.mark.parametrize("params", SPIRALS, ids=IDS)
def test_from_parameters_builds_the_specs_control_points(params) -> None:
    sp = Spiral.from_parameters(*params)
    want = expected_control_points(*params)
    scale = float(np.max(np.abs(want)))
    np.testing.assert_allclose(sp.control_points, want, rtol=0, atol=16 * EPS * scale)
    assert sp.turn_angle_deg == pytest.approx(params[2], rel=1e-14)
    assert sp.turn_angle_rad == pytest.approx(math.radians(params[2]), rel=1e-14)
    assert sp.end_curvature == params[3]
    assert math.hypot(*sp.start_tangent) == pytest.approx(1.0, abs=2 * EPS)
    assert sp.chord == pytest.approx(oracle.chord(want), rel=1e-12)
    assert sp.coordinate_scale == pytest.approx(scale, rel=1e-15)


@pytest.mark.parametrize("params", SPIRALS, ids=IDS)
def test_control_points_round_trip(params) -> None:
    sp = Spiral.from_parameters(*params)
    back = Spiral.from_control_points(sp.control_points.tolist())
    th = sp.turn_angle_rad
    # θ comes back from the directions of B1 − B0 and B3 − B2, which rounding at the
    # coordinates' scale tilts by ~eps·scale/|leg|; c = 5·tan θ / (9b) then moves by
    # dθ/(sin θ·cos θ) relative.
    angle_tol = direction_tol(sp.control_points)
    assert back.turn_angle_rad == pytest.approx(th, abs=angle_tol)
    c_rtol = angle_tol / (math.sin(th) * math.cos(th)) + 1e-13
    assert back.end_curvature == pytest.approx(sp.end_curvature, rel=c_rtol)
    assert back.start == sp.start
    turned = math.atan2(
        abs(cross(back.start_tangent, sp.start_tangent)),
        float(np.dot(back.start_tangent, sp.start_tangent)),
    )
    assert turned <= angle_tol
    # The points are rebuilt from (θ, c): a ∝ b / cos θ moves by tan θ·dθ relative.
    atol = (64 * EPS + 4 * angle_tol * (1 + math.tan(th))) * sp.coordinate_scale
    np.testing.assert_allclose(back.control_points, sp.control_points, atol=atol, rtol=0)


def test_from_control_points_accepts_lists_of_the_papers_form() -> None:
    cp = expected_control_points((1.5, 3.0), (1.0, 0.0), 51.34, 0.41574)
    sp = Spiral.from_control_points([list(p) for p in cp])
    assert sp.turn_angle_deg == pytest.approx(51.34, rel=1e-12)
    assert sp.end_curvature == pytest.approx(0.41574, rel=1e-12)
    mirror = Spiral.from_control_points(expected_control_points((0, 0), (0, 1), 20.0, -3.0))
    assert mirror.end_curvature == pytest.approx(-3.0, rel=1e-12)
    assert mirror.turn_angle_deg == pytest.approx(20.0, rel=1e-12)


# -- rejection of control points not of the paper's form -----------------------------------

GOOD = expected_control_points((1.5, 3.0), (1.0, 0.0), 51.34, 0.41574)


def test_rejects_unequal_first_legs_naming_the_condition_and_the_amount() -> None:
    cp = GOOD.copy()
    a_len = math.dist(cp[0], cp[1])
    cp[2] += np.array([0.0, 2e-3 * a_len])  # B2 − B1 now differs from B1 − B0 by 2e-3·|B1−B0|
    cp[3] += np.array([0.0, 2e-3 * a_len])
    with pytest.raises(GeometryError) as info:
        Spiral.from_control_points(cp)
    err = info.value
    assert err.field == "control_points"
    assert err.kind == "invalid_input"
    assert "B2-B1" in plain(err.message)
    assert "B1-B0" in plain(err.message)
    assert any(math.isclose(x, 2e-3, rel_tol=1e-2) for x in numbers_in(err.message)), err.message


def test_rejects_a_wrong_leg_ratio_naming_1_2_cos_theta_and_the_amount() -> None:
    cp = GOOD.copy()
    cp[3] = cp[2] + 1.01 * (cp[3] - cp[2])  # ratio 1 % above 1.2·cos θ
    with pytest.raises(GeometryError) as info:
        Spiral.from_control_points(cp)
    err = info.value
    assert err.field == "control_points"
    assert "1.2·cosθ" in plain(err.message) or "1.2*cos" in plain(err.message), err.message
    found = numbers_in(err.message)
    expected = 1.2 * math.cos(math.radians(51.34))
    assert any(math.isclose(x, expected, rel_tol=1e-6) for x in found), err.message
    assert any(math.isclose(x, 1.01 * expected, rel_tol=1e-6) for x in found), err.message
    assert any(math.isclose(x, 0.01, rel_tol=1e-2) for x in found), err.message


@pytest.mark.parametrize("turn_deg", [100.0, 90.0, -135.0, 0.0, 180.0])
def test_rejects_a_turn_outside_0_to_90_degrees_naming_the_angle(turn_deg: float) -> None:
    th = math.radians(turn_deg)
    a = 1.0
    # A leg ratio of the paper's form where there is one, so that the angle is what fails.
    b = abs(1.2 * math.cos(th)) if abs(math.cos(th)) > 1e-3 else 1.0
    cp = np.array([[0, 0], [a, 0], [2 * a, 0], [2 * a + b * math.cos(th), b * math.sin(th)]])
    with pytest.raises(GeometryError) as info:
        Spiral.from_control_points(cp)
    err = info.value
    assert err.field == "control_points"
    assert "90" in err.message, err.message
    assert any(math.isclose(x, abs(turn_deg), abs_tol=1e-6) for x in numbers_in(err.message)), (
        err.message
    )


@pytest.mark.parametrize(
    ("points", "field"),
    [
        ([[0, 0], [1, 0], [2, 0]], "control_points"),
        ([[0, 0], [1, 0], [2, 0], [3, 1], [4, 4]], "control_points"),
        ([[0, 0], [0, 0], [0, 0], [1, 1]], "control_points"),
        ([[0, 0], [1, 0], [2, 0], [2, 0]], "control_points"),
        ([[0, 0], [1, 0], [float("nan"), 0], [3, 1]], "control_points[2]"),
        ([[0, 0], [1, 0], [2, 0], [float("inf"), 1]], "control_points[3]"),
        ([[0, 0, 0], [1, 0], [2, 0], [3, 1]], "control_points[0]"),
    ],
    ids=["three", "five", "coincident", "zero-last-leg", "nan", "inf", "three-coords"],
)
def test_rejects_malformed_control_points(points, field: str) -> None:
    with pytest.raises(GeometryError) as info:
        Spiral.from_control_points(points)
    assert info.value.field == field
    assert info.value.kind == "invalid_input"


# -- evaluation -----------------------------------------------------------------------------


@pytest.mark.parametrize("params", SPIRALS, ids=IDS)
def test_evaluation_matches_bernstein(params) -> None:
    sp = Spiral.from_parameters(*params)
    cp = sp.control_points
    u = np.linspace(0, 1, 1001)
    scale = sp.coordinate_scale
    np.testing.assert_allclose(sp.eval(u), oracle.bezier_point(cp, u), rtol=0, atol=8 * EPS * scale)
    speed = np.max(np.abs(oracle.bezier_deriv(cp, u)))
    np.testing.assert_allclose(
        sp.deriv(u), oracle.bezier_deriv(cp, u), rtol=0, atol=64 * EPS * (scale + speed)
    )
    accel = np.max(np.abs(oracle.bezier_deriv2(cp, u)))
    np.testing.assert_allclose(
        sp.deriv2(u), oracle.bezier_deriv2(cp, u), rtol=0, atol=64 * EPS * (scale + accel)
    )
    assert sp.eval(np.zeros((2, 3))).shape == (2, 3, 2)


@pytest.mark.parametrize("params", SPIRALS, ids=IDS)
def test_ends_and_end_tangents(params) -> None:
    sp = Spiral.from_parameters(*params)
    cp = expected_control_points(*params)
    tol = 16 * EPS * sp.coordinate_scale
    np.testing.assert_allclose(sp.eval(0.0), cp[0], atol=tol, rtol=0)
    np.testing.assert_allclose(sp.eval(1.0), cp[3], atol=tol, rtol=0)
    t0 = np.array(params[1]) / math.hypot(*params[1])
    d0, d1 = sp.deriv(0.0), sp.deriv(1.0)
    angle_tol = direction_tol(cp)
    assert abs(cross(d0, t0)) / math.hypot(*d0) < angle_tol
    assert float(np.dot(d0, t0)) > 0
    # The end tangent is T0 turned by θ: anticlockwise for c > 0, clockwise for c < 0.
    turned = math.atan2(float(cross(t0, d1)), float(np.dot(t0, d1)))
    assert turned == pytest.approx(math.copysign(math.radians(params[2]), params[3]), abs=angle_tol)
    end_t = np.array(sp.end_tangent)
    np.testing.assert_allclose(end_t, d1 / math.hypot(*d1), atol=angle_tol, rtol=0)


def test_derivatives_agree_with_finite_differences() -> None:
    sp = Spiral.from_parameters((1.5, 3.0), (1.0, 0.0), 51.34, 0.41574)
    u = np.linspace(0.05, 0.95, 19)
    h = 1e-5
    fd1 = (sp.eval(u + h) - sp.eval(u - h)) / (2 * h)
    fd2 = (sp.deriv(u + h) - sp.deriv(u - h)) / (2 * h)
    np.testing.assert_allclose(sp.deriv(u), fd1, rtol=1e-8, atol=1e-8)
    np.testing.assert_allclose(sp.deriv2(u), fd2, rtol=1e-8, atol=1e-8)


@pytest.mark.parametrize("params", SPIRALS, ids=IDS)
def test_curvature_zero_at_start_c_at_end_and_monotone(params) -> None:
    sp = Spiral.from_parameters(*params)
    c = params[3]
    u = np.linspace(0, 1, 2001)
    k = np.asarray(sp.curvature(u))
    assert abs(float(sp.curvature(0.0))) <= 1e-12 * abs(c)
    assert float(sp.curvature(1.0)) == pytest.approx(c, rel=1e-9)
    np.testing.assert_allclose(
        k, oracle.signed_curvature(sp.control_points, u), rtol=1e-9, atol=1e-12 * abs(c)
    )
    # One sign throughout (no inflection), and |κ| strictly increasing after u = 0.
    assert np.all(np.sign(k[1:]) == np.sign(c))
    assert np.all(np.diff(np.abs(k)) > 0)


def test_curvature_is_the_turning_rate_of_the_tangent() -> None:
    # κ = dφ/ds by finite differences on a dense polyline, independent of any formula.
    sp = Spiral.from_parameters((0.0, 0.0), (0.0, 1.0), 40.0, -2.5)
    u = np.linspace(0, 1, 200_001)
    p = oracle.bezier_point(sp.control_points, u)
    seg = np.diff(p, axis=0)
    phi = np.unwrap(np.arctan2(seg[:, 1], seg[:, 0]))
    ds = np.hypot(*seg.T)
    kappa_fd = np.diff(phi) / (0.5 * (ds[1:] + ds[:-1]))
    picks = np.array([1000, 50_000, 100_000, 150_000, 199_000])
    np.testing.assert_allclose(kappa_fd[picks - 1], sp.curvature(u[picks]), rtol=1e-5, atol=1e-9)


@pytest.mark.parametrize("params", SPIRALS, ids=IDS)
def test_arclen_matches_a_dense_polyline(params) -> None:
    sp = Spiral.from_parameters(*params)
    cp = sp.control_points
    assert sp.arclen() == pytest.approx(oracle.arc_length(cp), rel=1e-12)
    assert sp.arclen(0.2, 0.7) == pytest.approx(oracle.arc_length(cp, 0.2, 0.7), rel=1e-12)
    assert sp.arclen(0.0, 0.3) + sp.arclen(0.3, 1.0) == pytest.approx(sp.arclen(), rel=1e-14)


def test_mirror_image_turns_clockwise() -> None:
    left = Spiral.from_parameters((1.0, 2.0), (3.0, 1.0), 35.0, 0.8)
    right = Spiral.from_parameters((1.0, 2.0), (3.0, 1.0), 35.0, -0.8)
    # Reflect the left spiral's control points across the line through B0 along T0.
    t0 = np.array([3.0, 1.0]) / math.hypot(3.0, 1.0)
    rel = left.control_points - left.control_points[0]
    along = rel @ t0
    reflected = left.control_points[0] + 2 * along[:, None] * t0 - rel
    np.testing.assert_allclose(right.control_points, reflected, atol=1e-13, rtol=0)
    u = np.linspace(0.001, 1, 500)
    assert np.all(np.asarray(right.curvature(u)) < 0)
    d = right.deriv(u)
    headings = np.unwrap(np.arctan2(d[:, 1], d[:, 0]))
    assert np.all(np.diff(headings) < 0)  # clockwise
    t1 = np.array(right.end_tangent)
    assert float(cross(t0, t1)) == pytest.approx(-math.sin(math.radians(35.0)), abs=1e-14)
    np.testing.assert_allclose(right.curvature(u), -np.asarray(left.curvature(u)), rtol=1e-12)


# -- bad input -------------------------------------------------------------------------------

NAN, INF = float("nan"), float("inf")
BASE = {
    "start": (0.0, 0.0),
    "start_tangent": (1.0, 0.0),
    "turn_angle_deg": 30.0,
    "end_curvature": 1.0,
}


@pytest.mark.parametrize(
    ("change", "field"),
    [
        ({"start": (NAN, 0.0)}, "start"),
        ({"start": (0.0, INF)}, "start"),
        ({"start": (0.0, 0.0, 0.0)}, "start"),
        ({"start": (1.0,)}, "start"),
        ({"start_tangent": (0.0, 0.0)}, "start_tangent"),
        ({"start_tangent": (NAN, 1.0)}, "start_tangent"),
        ({"start_tangent": (-INF, 1.0)}, "start_tangent"),
        ({"start_tangent": (1.0, 0.0, 0.0)}, "start_tangent"),
        ({"turn_angle_deg": 0.0}, "turn_angle_deg"),
        ({"turn_angle_deg": -5.0}, "turn_angle_deg"),
        ({"turn_angle_deg": 90.0}, "turn_angle_deg"),
        ({"turn_angle_deg": 135.0}, "turn_angle_deg"),
        ({"turn_angle_deg": NAN}, "turn_angle_deg"),
        ({"turn_angle_deg": INF}, "turn_angle_deg"),
        ({"end_curvature": 0.0}, "end_curvature"),
        ({"end_curvature": -0.0}, "end_curvature"),
        ({"end_curvature": NAN}, "end_curvature"),
        ({"end_curvature": INF}, "end_curvature"),
        ({"end_curvature": -INF}, "end_curvature"),
        ({"end_curvature": 5e-324}, "end_curvature"),
    ],
)
def test_bad_parameters_raise_naming_the_field(change: dict, field: str) -> None:
    with pytest.raises(GeometryError) as info:
        Spiral.from_parameters(**{**BASE, **change})
    err = info.value
    assert err.field == field
    assert err.kind == "invalid_input"
    assert isinstance(err, ValueError)
    assert str(err).startswith(field)


def test_geometry_error_survives_pickling() -> None:
    err = GeometryError("tolerance", "below the floor", kind="tolerance_floor", limit=1e-9)
    back = pickle.loads(pickle.dumps(err))
    assert (back.field, back.message, back.kind, back.limit) == (
        "tolerance",
        "below the floor",
        "tolerance_floor",
        1e-9,
    )
    assert str(back) == str(err)
