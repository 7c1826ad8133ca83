"""The oracle itself, on hand-built cases whose answers are known in closed form."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import pytest

from arcspline.geometry import ArcSegment, LineSegment, Point, SplineStats
from tests.support import oracle

# Straight "Bézier": equally spaced collinear control points give Q(u) = (3u, 0).
STRAIGHT = np.array([[0.0, 0.0], [1.0, 0.0], [2.0, 0.0], [3.0, 0.0]])


def paper_form(theta_deg: float, c: float) -> tuple[np.ndarray, float, float]:
    """The §1 control points (docs/method.md) from (1.5, 3), T0 = (1, 0): ``(cp, a, b)``."""
    th = math.radians(theta_deg)
    a = 25 * math.tan(th) / (54 * abs(c) * math.cos(th))
    b = 5 * math.tan(th) / (9 * abs(c))
    t1 = np.array([math.cos(th), math.copysign(math.sin(th), c)])
    b0 = np.array([1.5, 3.0])
    b1 = b0 + a * np.array([1.0, 0.0])
    b2 = b1 + a * np.array([1.0, 0.0])
    return np.array([b0, b1, b2, b2 + b * t1]), a, b


PAPER, PAPER_A, PAPER_B = paper_form(51.34, 0.41574)


def arc(center, radius, a0_deg, a1_deg, u=(0.0, 1.0), deviation=0.0) -> ArcSegment:
    """An arc about ``center`` from polar angle ``a0`` to ``a1`` (degrees, signed sweep)."""
    c = np.asarray(center, dtype=float)
    a0, a1 = math.radians(a0_deg), math.radians(a1_deg)
    start = c + radius * np.array([math.cos(a0), math.sin(a0)])
    end = c + radius * np.array([math.cos(a1), math.sin(a1)])
    return ArcSegment(
        start=Point(*start),
        end=Point(*end),
        center=Point(*c),
        radius=radius,
        direction="ccw" if a1 > a0 else "cw",
        start_angle_rad=math.atan2(*(start - c)[::-1]),
        sweep_rad=a1 - a0,
        length=radius * abs(a1 - a0),
        u_start=u[0],
        u_end=u[1],
        max_deviation=deviation,
        u_at_max_deviation=0.5 * (u[0] + u[1]),
    )


def line(start, end, u=(0.0, 1.0), deviation=0.0) -> LineSegment:
    return LineSegment(
        start=Point(*start),
        end=Point(*end),
        length=math.dist(start, end),
        u_start=u[0],
        u_end=u[1],
        max_deviation=deviation,
        u_at_max_deviation=0.5 * (u[0] + u[1]),
    )


def sagitta_arc(h: float) -> ArcSegment:
    """The arc through (0, 0) and (3, 0) bulging up by ``h``, centre below the chord."""
    r = (1.5**2 + h**2) / (2 * h)
    half_deg = math.degrees(math.asin(1.5 / r))
    return arc((1.5, h - r), r, 90 + half_deg, 90 - half_deg, deviation=h)


def exact_sagitta(r: float, h: float) -> tuple[np.ndarray, ArcSegment]:
    """A straight curve along y = 0 and the clockwise arc of radius ``r`` over it, sagitta h.

    With ``r`` and ``h`` powers of two the centre (0, h − r) is exact, and the end points
    (∓w, 0) are rounded only along the chord, which moves ‖end − C‖ by a negligible
    ``(w/r)·ulp(w)``: the arc really is h above the curve's midpoint.
    """
    w = math.sqrt(2 * r * h - h * h)
    half = math.asin(w / r)
    seg = ArcSegment(
        start=Point(-w, 0.0),
        end=Point(w, 0.0),
        center=Point(0.0, h - r),
        radius=r,
        direction="cw",
        start_angle_rad=math.pi / 2 + half,
        sweep_rad=-2 * half,
        length=2 * r * half,
        u_start=0.0,
        u_end=1.0,
        max_deviation=h,
        u_at_max_deviation=0.5,
    )
    return np.array([[-w + 2 * w * i / 3, 0.0] for i in range(4)]), seg


@dataclass
class FakeSpline:
    """Just the public surface of an ``ArcSpline`` that the oracle reads."""

    segments: tuple
    stats: SplineStats
    tolerance: float

    def __len__(self) -> int:
        return len(self.segments)


def fake_spline(cp, segments, tolerance, **overrides) -> FakeSpline:
    devs = [s.max_deviation for s in segments]
    worst = int(np.argmax(devs))
    radii = [s.radius for s in segments if s.type == "arc"]
    fields = {
        "arc_count": len(radii),
        "line_count": len(segments) - len(radii),
        "max_deviation": devs[worst],
        "u_at_max_deviation": segments[worst].u_at_max_deviation,
        "deviation_ratio": devs[worst] / tolerance,
        "mean_segment_deviation": sum(devs) / len(devs),
        "spiral_length": oracle.arc_length(cp),
        "spline_length": sum(s.length for s in segments),
        "min_radius": min(radii) if radii else None,
        "max_radius": max(radii) if radii else None,
    }
    fields.update(overrides)
    return FakeSpline(tuple(segments), SplineStats(**fields), tolerance)


# -- the Bézier curve -------------------------------------------------------------------


def test_bezier_ends_and_midpoint() -> None:
    cp = np.array([[0.0, 1.0], [2.0, 5.0], [-3.0, 4.0], [7.0, -1.0]])
    assert np.array_equal(oracle.bezier_point(cp, 0.0), cp[0])
    assert np.array_equal(oracle.bezier_point(cp, 1.0), cp[3])
    np.testing.assert_allclose(
        oracle.bezier_point(cp, 0.5), (cp[0] + 3 * cp[1] + 3 * cp[2] + cp[3]) / 8, rtol=1e-15
    )


def test_bezier_matches_the_specs_monomial_form() -> None:
    # §1: Q(u) = B0 + 3a·T0·u + (b·T1 − a·T0)·u³ and Q'(u) = 3a·T0 + 3(b·T1 − a·T0)·u².
    u = np.linspace(0, 1, 101)
    t0 = np.array([1.0, 0.0])
    t1 = (PAPER[3] - PAPER[2]) / PAPER_B
    mono = (
        PAPER[0] + 3 * PAPER_A * t0 * u[:, None] + (PAPER_B * t1 - PAPER_A * t0) * u[:, None] ** 3
    )
    np.testing.assert_allclose(oracle.bezier_point(PAPER, u), mono, rtol=1e-14, atol=1e-14)
    dmono = 3 * PAPER_A * t0 + 3 * (PAPER_B * t1 - PAPER_A * t0) * u[:, None] ** 2
    np.testing.assert_allclose(oracle.bezier_deriv(PAPER, u), dmono, rtol=1e-14, atol=1e-14)
    ddmono = 6 * (PAPER_B * t1 - PAPER_A * t0) * u[:, None]
    np.testing.assert_allclose(oracle.bezier_deriv2(PAPER, u), ddmono, rtol=1e-13, atol=1e-13)


def test_curvature_is_zero_at_start_and_c_at_end() -> None:
    assert abs(float(oracle.signed_curvature(PAPER, 0.0))) < 1e-15
    assert float(oracle.signed_curvature(PAPER, 1.0)) == pytest.approx(0.41574, rel=1e-12)
    mirror, _, _ = paper_form(51.34, -0.41574)
    assert float(oracle.signed_curvature(mirror, 1.0)) == pytest.approx(-0.41574, rel=1e-12)


def test_arc_length_of_a_straight_curve_and_of_a_quarter_circle_like_speed() -> None:
    assert oracle.arc_length(STRAIGHT) == pytest.approx(3.0, rel=1e-15)
    assert oracle.arc_length(STRAIGHT, 0.25, 0.5) == pytest.approx(0.75, rel=1e-15)
    # Against Gauss–Legendre quadrature of the speed of the monomial form (200 nodes).
    x, w = np.polynomial.legendre.leggauss(200)
    u = 0.5 * (x + 1)
    t1 = (PAPER[3] - PAPER[2]) / PAPER_B
    d = 3 * PAPER_A * np.array([1.0, 0.0]) + 3 * (PAPER_B * t1 - PAPER_A * np.array([1.0, 0.0])) * (
        u[:, None] ** 2
    )
    assert oracle.arc_length(PAPER) == pytest.approx(0.5 * np.sum(w * np.hypot(*d.T)), rel=1e-13)


# -- distance to an arc and to a line ---------------------------------------------------


@pytest.mark.parametrize("ccw", [True, False])
def test_points_on_the_arc_are_at_distance_zero(ccw: bool) -> None:
    c, r = np.array([2.0, -1.0]), 3.0
    a0, a1 = (0.3, 1.2) if ccw else (1.2, 0.3)
    start = c + r * np.array([math.cos(a0), math.sin(a0)])
    end = c + r * np.array([math.cos(a1), math.sin(a1)])
    ang = np.linspace(0.3, 1.2, 50)
    on = c + r * np.stack([np.cos(ang), np.sin(ang)], axis=-1)
    d = oracle.point_arc_distance(on, c, r, start, end, ccw)
    assert np.max(d) < 1e-15 * r


def test_the_centre_is_at_distance_r() -> None:
    d = oracle.point_arc_distance(np.array([2.0, -1.0]), [2.0, -1.0], 3.0, [5, -1], [2, 2], True)
    assert float(d) == 3.0


def test_points_in_the_sector_are_measured_radially() -> None:
    # Quarter arc about the origin from (1, 0) to (0, 1), anticlockwise.
    pts = np.array([[2.0, 2.0], [0.3, 0.4], [0.0, 5.0], [1e-3, 1e-3]])
    d = oracle.point_arc_distance(pts, [0, 0], 1.0, [1, 0], [0, 1], True)
    np.testing.assert_allclose(d, [math.sqrt(8) - 1, 0.5, 4.0, 1 - math.sqrt(2e-6)], rtol=1e-15)


@pytest.mark.parametrize("ccw", [True, False])
def test_points_outside_the_sector_are_measured_to_the_nearer_end(ccw: bool) -> None:
    # Quarter arc between (1, 0) and (0, 1); the anticlockwise one is the short way, the
    # clockwise one from (0, 1) to (1, 0) is the same set of points.
    start, end = ([1, 0], [0, 1]) if ccw else ([0, 1], [1, 0])
    pts = np.array([[2.0, -1.0], [-1.0, 3.0], [-1.0, -1.0], [0.5, -0.1]])
    want = [math.sqrt(2), math.sqrt(5), math.sqrt(5), math.hypot(0.5, 0.1)]
    d = oracle.point_arc_distance(pts, [0, 0], 1.0, start, end, ccw)
    np.testing.assert_allclose(d, want, rtol=1e-15)


def test_the_sweep_sense_selects_the_sector() -> None:
    # The same end points taken clockwise from (1, 0) to (0, 1) would be the long way round;
    # the oracle takes arcs as turning less than π, so it measures the short sector's
    # complement as "outside": (−1, 0) is 1 from the circle but √2 from both ends.
    p = np.array([-2.0, 0.0])
    assert float(oracle.point_arc_distance(p, [0, 0], 1, [1, 0], [0, 1], True)) == pytest.approx(
        math.sqrt(5)
    )


def test_huge_radius_keeps_its_digits() -> None:
    # A nearly straight arc of radius 1e6 about (0, −1e6) and a point 1e-9 above its apex:
    # in float64 ‖P − C‖ − r keeps only ~1 digit; long double keeps ~10.
    r = 1e6
    start = np.array([-1.0, math.sqrt(r * r - 1.0) - r])
    end = np.array([1.0, start[1]])
    d = oracle.point_arc_distance(np.array([0.0, 1e-9]), [0.0, -r], r, end, start, True)
    assert float(d) == pytest.approx(1e-9, rel=1e-6)


def test_line_distance() -> None:
    pts = np.array([[1.0, 2.0], [-3.0, 4.0], [7.0, -3.0], [2.5, 0.0]])
    d = oracle.point_line_distance(pts, [0, 0], [3, 0])
    np.testing.assert_allclose(d, [2.0, 5.0, 5.0, 0.0], rtol=1e-15)
    assert float(oracle.point_line_distance(np.array([3.0, 4.0]), [0, 0], [0, 0])) == 5.0


# -- distance to the curve ---------------------------------------------------------------


def test_distance_to_a_straight_curve_including_beyond_its_ends() -> None:
    pts = np.array([[1.3, 0.7], [-1.0, 1.0], [5.0, -2.0], [3.0, 0.0]])
    d, u = oracle.distance_to_curve(STRAIGHT, pts)
    np.testing.assert_allclose(d.astype(float), [0.7, math.sqrt(2), math.sqrt(8), 0.0], atol=1e-15)
    np.testing.assert_allclose(u, [1.3 / 3, 0.0, 1.0, 1.0], atol=1e-15)


@pytest.mark.parametrize("offset", [1e-9, -1e-6, 1e-3, -0.05])
def test_distance_to_the_spiral_along_its_normal_is_exact(offset: float) -> None:
    # A point displaced along the normal at Q(u0) is |offset| from the curve (the offset is
    # far below the radius of curvature, ≥ 1/0.41574), with foot u0: exact, not a chord.
    # The points are built in long double: in float64 their rounding alone (~1e-15 at
    # coordinates ~5) would swamp a 1e-9 offset.
    cp = PAPER.astype(np.longdouble)
    u0 = np.linspace(0.01, 0.99, 37)
    t = oracle.bezier_deriv(cp, u0)
    n = np.stack([-t[:, 1], t[:, 0]], axis=-1) / np.hypot(t[:, 0], t[:, 1])[:, None]
    d, u = oracle.distance_to_curve(cp, oracle.bezier_point(cp, u0) + offset * n)
    np.testing.assert_allclose(d.astype(float), abs(offset), rtol=1e-12, atol=1e-17)
    np.testing.assert_allclose(u, u0, atol=1e-12)


# -- two-sided distance ------------------------------------------------------------------


@pytest.mark.parametrize(("r", "h"), [(2.0**20, 2.0**-20), (8.0, 2.0**-7), (2.0, 0.25)])
def test_measure_a_single_arc_of_known_sagitta(r: float, h: float) -> None:
    # A straight curve against the arc through its ends that bulges by h: both one-sided
    # distances are h, at the middle. At r ≈ 1e6, h ≈ 1e-6 float64 would keep ~4 digits.
    cp, seg = exact_sagitta(r, h)
    dev = oracle.measure(cp, [seg])
    assert dev.spiral_to_spline == pytest.approx(h, rel=1e-9)
    assert dev.spline_to_spiral == pytest.approx(h, rel=1e-9)
    assert dev.global_spiral_to_spline == pytest.approx(h, rel=1e-6)
    assert dev.segment_deviation[0] == pytest.approx(h, rel=1e-9)
    assert dev.segment_u_at_max[0] == pytest.approx(0.5, abs=1e-6)
    assert dev.u_spiral_to_spline == pytest.approx(0.5, abs=1e-6)
    assert dev.point_spline_to_spiral == pytest.approx((0.0, h), rel=1e-6, abs=1e-9)


def test_measure_sees_an_uncovered_end_one_way_only() -> None:
    # A line covering only (0,0)–(2,0) of the curve (0,0)–(3,0): the curve's end is 1 away
    # from the spline, while every spline point is on the curve.
    dev = oracle.measure(STRAIGHT, [line((0, 0), (2, 0))])
    assert dev.spiral_to_spline == pytest.approx(1.0, rel=1e-12)
    assert dev.u_spiral_to_spline == 1.0
    assert dev.spline_to_spiral < 1e-15
    assert dev.max == pytest.approx(1.0, rel=1e-12)


def test_measure_per_segment_uses_each_segments_own_range() -> None:
    # Two lines on the curve, u ranges [0, 0.5] and [0.5, 1]; the second is lifted by 0.1.
    segs = [line((0, 0), (1.5, 0), (0, 0.5)), line((1.5, 0.1), (3, 0.1), (0.5, 1))]
    dev = oracle.measure(STRAIGHT, segs)
    assert dev.segment_deviation[0] < 1e-15
    assert dev.segment_deviation[1] == pytest.approx(0.1, rel=1e-12)
    assert dev.spline_to_spiral == pytest.approx(0.1, rel=1e-12)
    # Spiral points of the second range are nearer the first line near the joint, never
    # nearer than 0.1 elsewhere: the windowed maximum is still 0.1.
    assert dev.spiral_to_spline == pytest.approx(0.1, rel=1e-12)


def test_deviation_at_a_given_u() -> None:
    cp, seg = exact_sagitta(8.0, 2.0**-7)
    assert oracle.deviation_at(cp, seg, 0.5) == pytest.approx(2.0**-7, rel=1e-14)
    assert oracle.deviation_at(cp, seg, 0.0) < 1e-15


# -- continuity and consistency ------------------------------------------------------------

# An S-curve of two unit arcs, G1 at (1, 1): anticlockwise about (0, 1) from (0, 0), then
# clockwise about (2, 1) to (2, 2). Its end tangents are (1, 0) and (1, 0).
S_CURVE_CP = np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 2.0], [2.0, 2.0]])
S_CURVE = [arc((0, 1), 1.0, -90, 0, (0, 0.5)), arc((2, 1), 1.0, 180, 90, (0.5, 1))]


def test_continuity_of_a_g1_s_curve() -> None:
    cont = oracle.continuity(S_CURVE_CP, S_CURVE)
    assert cont.violations() == []
    assert cont.joint_angle_rad[0] < 1e-15
    assert cont.start_angle_rad < 1e-15
    assert cont.end_angle_rad < 1e-15


def test_continuity_reports_a_kink_a_gap_and_wrong_end_tangents() -> None:
    kinked = [S_CURVE[0], arc((2, 1), 1.0, 179, 90, (0.5, 1))]  # starts 1° further round
    cont = oracle.continuity(S_CURVE_CP, kinked)
    assert cont.joint_angle_rad[0] == pytest.approx(math.radians(1), rel=1e-12)
    assert cont.joint_gap[0] == pytest.approx(2 * math.sin(math.radians(0.5)), rel=1e-12)
    problems = " | ".join(cont.violations())
    assert "joint 0/1: tangents" in problems
    assert "joint 0/1: end points" in problems
    tilted = S_CURVE_CP.copy()
    tilted[1] = [1.0, 0.001]  # start tangent turned by atan(0.001)
    cont = oracle.continuity(tilted, S_CURVE)
    assert cont.start_angle_rad == pytest.approx(math.atan(0.001), rel=1e-12)
    assert "start tangent off" in " | ".join(cont.violations())


def test_continuity_of_lines_uses_their_direction() -> None:
    cont = oracle.continuity(STRAIGHT, [line((0, 0), (1, 0)), line((1, 0), (3, 0))])
    assert cont.violations() == []
    cont = oracle.continuity(STRAIGHT, [line((0, 0), (1, 0.01)), line((1, 0.01), (3, 0))])
    assert cont.joint_angle_rad[0] == pytest.approx(math.atan(0.01) + math.atan(0.005), 1e-12)


def test_arc_violations_accepts_good_segments() -> None:
    assert oracle.arc_violations([*S_CURVE, sagitta_arc(0.3), line((0, 0), (3, 4))]) == []


@pytest.mark.parametrize(
    ("change", "needle"),
    [
        ({"radius": 1.001}, "radius ="),
        ({"radius": -1.0}, "not finite and positive"),
        ({"start_angle_rad": 0.1}, "start_angle_rad"),
        ({"sweep_rad": 0.5}, "sweep_rad"),
        ({"direction": "cw"}, "direction"),
        ({"length": 2.0}, "length"),
    ],
)
def test_arc_violations_names_each_inconsistency(change: dict, needle: str) -> None:
    good = arc((0, 0), 1.0, 10, 60)
    bad = ArcSegment(**{**{f: getattr(good, f) for f in good.__slots__}, **change})
    problems = oracle.arc_violations([bad])
    assert problems
    assert any(needle in p for p in problems), problems


def test_line_length_inconsistency() -> None:
    bad = LineSegment(Point(0, 0), Point(3, 4), 4.0, 0.0, 1.0, 0.0, 0.5)
    assert "length" in oracle.arc_violations([bad])[0]


# -- statistics and the whole verdict -------------------------------------------------------


def test_check_passes_a_consistent_spline_within_tolerance() -> None:
    # Two lines on the straight curve: exact, G1, every statistic consistent.
    segs = [line((0, 0), (1.2, 0), (0, 0.4)), line((1.2, 0), (3, 0), (0.4, 1))]
    verdict = oracle.check(STRAIGHT, fake_spline(STRAIGHT, segs, 1e-6), 1e-6)
    assert verdict.violations == [], verdict.describe()
    assert verdict.deviation.max < 1e-15


def test_check_reports_tolerance_tangents_and_deviation_mismatch() -> None:
    h = 0.01
    spline = fake_spline(STRAIGHT, [sagitta_arc(h)], h / 2)
    problems = oracle.check(STRAIGHT, spline, h / 2).violations
    text = " | ".join(problems)
    assert "exceeds tolerance" in text
    assert "start tangent off" in text
    assert "end tangent off" in text
    assert "but stats.max_deviation" not in text  # measured and reported agree
    wrong = [
        ArcSegment(**{**{f: getattr(s, f) for f in s.__slots__}, "max_deviation": h / 3})
        for s in [sagitta_arc(h)]
    ]
    problems = oracle.check(STRAIGHT, fake_spline(STRAIGHT, wrong, h), h).violations
    assert any("segment 0" in p and "reported" in p for p in problems), problems
    assert any("stats.max_deviation" in p for p in problems), problems


@pytest.mark.parametrize(
    ("override", "needle"),
    [
        ({"arc_count": 2}, "arc_count"),
        ({"max_deviation": 0.5}, "stats.max_deviation"),
        ({"deviation_ratio": 0.5}, "deviation_ratio"),
        ({"mean_segment_deviation": 1.0}, "mean_segment_deviation"),
        ({"spiral_length": 3.001}, "spiral_length"),
        ({"spline_length": 1.0}, "spline_length"),
        ({"min_radius": 0.5}, "min/max radius"),
    ],
)
def test_stats_violations_names_each_wrong_statistic(override: dict, needle: str) -> None:
    segs = [arc((0, 1), 1.0, -90, 0, (0, 0.5), 0.1), line((1, 1), (1, 2), (0.5, 1), 0.2)]
    assert oracle.stats_violations(S_CURVE_CP, fake_spline(S_CURVE_CP, segs, 1.0), 1.0) == []
    spline = fake_spline(S_CURVE_CP, segs, 1.0, **override)
    problems = oracle.stats_violations(S_CURVE_CP, spline, 1.0)
    assert any(needle in p for p in problems), problems


def test_stats_violations_checks_that_u_ranges_tile() -> None:
    segs = [line((0, 0), (1, 0), (0, 0.4)), line((1, 0), (3, 0), (0.5, 1))]
    problems = oracle.stats_violations(STRAIGHT, fake_spline(STRAIGHT, segs, 1.0), 1.0)
    assert any("do not tile" in p for p in problems), problems


@pytest.mark.parametrize("c", [2.0, -2.0])
def test_paper_control_points_match_the_closed_form_at_60_degrees(c: float) -> None:
    # cos 60° = 1/2, sin 60° = √3/2: a = 25·sinθ/(54·|c|·cos²θ) = 50√3/(54·|c|),
    # b = 5·sinθ/(9·|c|·cosθ) = 5√3/(9·|c|), T1 = (1/2, ±√3/2).
    r3 = math.sqrt(3.0)
    a, b = 50 * r3 / (54 * abs(c)), 5 * r3 / (9 * abs(c))
    sign = math.copysign(1.0, c)
    want = [(0.0, 0.0), (a, 0.0), (2 * a, 0.0), (2 * a + b / 2, sign * b * r3 / 2)]
    got = oracle.paper_control_points((0.0, 0.0), (2.0, 0.0), 60.0, c)
    np.testing.assert_allclose(got, want, rtol=4 * oracle.EPS, atol=0)
    t1 = oracle.paper_end_tangent((2.0, 0.0), 60.0, c)
    np.testing.assert_allclose(t1, (0.5, sign * r3 / 2), rtol=4 * oracle.EPS, atol=0)


def test_paper_control_points_near_90_degrees_keep_the_leg_ratio() -> None:
    # |B3 − B2| / |B1 − B0| = 1.2·cos θ, with cos(90° − φ) = sin φ ≈ φ − φ³/6 for tiny φ.
    theta_deg = 90.0 - 1e-6
    phi = math.pi / 180 * (90.0 - theta_deg)  # the subtraction is exact (Sterbenz)
    cp = oracle.paper_control_points((0.0, 0.0), (1.0, 0.0), theta_deg, 1.0)
    ratio = math.dist(cp[2], cp[3]) / math.dist(cp[0], cp[1])
    # The points are ~1e15 and the last leg ~1e7: its rounding is ~1e-8 of it.
    assert ratio == pytest.approx(1.2 * (phi - phi**3 / 6), rel=1e-7)
