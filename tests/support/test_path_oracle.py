"""The path oracle itself, on hand-built cases whose answers are known in closed form."""

from __future__ import annotations

import copy
import math
from typing import Any

import numpy as np
import pytest

# The real value types; the oracle only reads their fields.
from arcspline.geometry.curves.segments import (
    CircularArc,
    Cubic,
    EllipticalArc,
    Line,
    Path,
    Quadratic,
    Subpath,
)
from tests.support import path_oracle as po

HALF_PI = math.pi / 2


def pt(x: float, y: float) -> Any:
    return (float(x), float(y))


def circular(center: Any, r: float, a0: float, sweep: float) -> CircularArc:
    """A source arc; end points from the formula."""
    c = np.asarray(center, dtype=float)
    s = c + r * np.array([math.cos(a0), math.sin(a0)])
    e = c + r * np.array([math.cos(a0 + sweep), math.sin(a0 + sweep)])
    return CircularArc(pt(*s), pt(*e), pt(*c), r, a0, sweep)


def arc_out(
    center: Any,
    r: float,
    a0: float,
    sweep: float,
    *,
    source: int = 0,
    u: tuple[float, float] = (0.0, 1.0),
    deviation: float = 0.0,
    start: Any = None,
    end: Any = None,
) -> dict[str, Any]:
    """An output arc dict as the service emits it."""
    c = np.asarray(center, dtype=float)
    s = c + r * np.array([math.cos(a0), math.sin(a0)]) if start is None else start
    e = c + r * np.array([math.cos(a0 + sweep), math.sin(a0 + sweep)]) if end is None else end
    return {
        "type": "arc",
        "start": [float(s[0]), float(s[1])],
        "end": [float(e[0]), float(e[1])],
        "center": [float(c[0]), float(c[1])],
        "radius": r,
        "direction": "ccw" if sweep > 0 else "cw",
        "start_angle_rad": a0,
        "sweep_rad": sweep,
        "source_segment": source,
        "u_start": u[0],
        "u_end": u[1],
        "max_deviation": deviation,
    }


def line_out(
    start: Any,
    end: Any,
    *,
    source: int = 0,
    u: tuple[float, float] = (0.0, 1.0),
    deviation: float = 0.0,
) -> dict[str, Any]:
    return {
        "type": "line",
        "start": [float(start[0]), float(start[1])],
        "end": [float(end[0]), float(end[1])],
        "source_segment": source,
        "u_start": u[0],
        "u_end": u[1],
        "max_deviation": deviation,
    }


# -- point distances -------------------------------------------------------------------


def test_point_arc_distance_inside_outside_and_at_the_center() -> None:
    pts = [[2.0, 0.0], [0.0, 0.5], [-1.0, 0.0], [0.0, 0.0], [0.0, -3.0]]
    d = po.point_arc_distance(pts, (0.0, 0.0), 1.0, 0.0, HALF_PI)
    # (2,0) radial; (0,0.5) radial; (-1,0) past the end (0,1): √2; centre: r; (0,-3) before
    # the start (1,0): √10.
    assert np.allclose(d.astype(float), [1.0, 0.5, math.sqrt(2), 1.0, math.sqrt(10)], 0, 1e-15)
    # Clockwise through three quarters of the circle from angle 0 (all but the first
    # quadrant): (-2, 0) and (0, 2) radial; (1.5, 1.5) in the gap, nearest the ends.
    pts = [[-2.0, 0.0], [0.0, 2.0], [1.5, 1.5]]
    d = po.point_arc_distance(pts, (0.0, 0.0), 1.0, 0.0, -1.5 * math.pi)
    assert np.allclose(d.astype(float), [1.0, 1.0, math.sqrt(2.5)], 0, 1e-15)


def test_point_arc_distance_keeps_accuracy_at_huge_radius() -> None:
    r = 1e7
    d = float(po.point_arc_distance([[0.0, 1e-3]], (0.0, -r), r, HALF_PI - 1e-6, 2e-6)[0])
    assert abs(d - 1e-3) < 1e-11  # float64 would be off by ~1e-9


def test_point_line_distance() -> None:
    d = po.point_line_distance([[1.0, 2.0], [-3.0, 4.0], [7.0, -1.0]], (0.0, 0.0), (4.0, 0.0))
    assert np.allclose(d.astype(float), [2.0, 5.0, math.hypot(3.0, 1.0)], 0, 1e-15)


# -- one piece: known answers ----------------------------------------------------------


def test_straight_cubic_against_its_line_is_zero() -> None:
    cubic = Cubic(pt(0, 0), pt(1, 1), pt(2, 2), pt(3, 3))
    assert po.measure_piece(cubic, 0.0, 1.0, line_out((0, 0), (3, 3))) < 1e-15
    # A piece of it against the matching part of the line.
    assert po.measure_piece(cubic, 0.25, 0.5, line_out((0.75, 0.75), (1.5, 1.5))) < 1e-15


def test_quarter_circle_against_a_concentric_arc_is_the_radius_difference() -> None:
    r, d = 2.0, 0.0125
    src = circular((1.0, -1.0), r, 0.3, HALF_PI)
    out = arc_out((1.0, -1.0), r + d, 0.3, HALF_PI)
    sides = po.measure_piece_sides(src, 0.0, 1.0, out)
    assert sides.source_to_output == pytest.approx(d, rel=1e-12)
    assert sides.output_to_source == pytest.approx(d, rel=1e-12)


def test_arc_against_a_source_arc_of_another_radius_and_sweep() -> None:
    # Source: radius 2 over 0..90°; output: radius 1.5 over 0..45°. The output is 0.5 from
    # the source everywhere; the source's far end (0, 2) is nearest the output's end point.
    src = circular((0.0, 0.0), 2.0, 0.0, HALF_PI)
    out = arc_out((0.0, 0.0), 1.5, 0.0, math.pi / 4)
    sides = po.measure_piece_sides(src, 0.0, 1.0, out)
    assert sides.output_to_source == pytest.approx(0.5, rel=1e-12)
    far = math.sqrt(2.0**2 + 1.5**2 - 2 * 2.0 * 1.5 * math.cos(math.pi / 4))
    assert sides.source_to_output == pytest.approx(far, rel=1e-12)
    assert sides.t == pytest.approx(1.0)
    # Half the source (0..45°) is just the radius difference.
    assert po.measure_piece(src, 0.0, 0.5, out) == pytest.approx(0.5, rel=1e-12)


def test_elliptical_arc_against_its_circumscribing_circle() -> None:
    rx, ry, rot = 2.0, 1.25, 0.4
    c = np.array([0.5, -0.25])
    rmat = np.array([[math.cos(rot), -math.sin(rot)], [math.sin(rot), math.cos(rot)]])
    s, e = c + rmat @ [rx, 0.0], c + rmat @ [0.0, ry]
    ellipse = EllipticalArc(pt(*s), pt(*e), pt(*c), rx, ry, rot, 0.0, HALF_PI)
    out = arc_out(c, rx, rot, HALF_PI)
    sides = po.measure_piece_sides(ellipse, 0.0, 1.0, out)
    assert sides.source_to_output == pytest.approx(rx - ry, rel=1e-12)
    assert sides.t == pytest.approx(1.0)  # the minor vertex
    assert sides.output_to_source == pytest.approx(rx - ry, rel=1e-12)


def test_quadratic_bump_against_its_chord() -> None:
    # y(t) = 2h·t(1 − t): at most h/2 at t = 1/2.
    h = 0.3
    quad = Quadratic(pt(0, 0), pt(1, h), pt(2, 0))
    sides = po.measure_piece_sides(quad, 0.0, 1.0, line_out((0, 0), (2, 0)))
    assert sides.source_to_output == pytest.approx(h / 2, rel=1e-12)
    assert sides.t == pytest.approx(0.5, abs=1e-7)
    assert sides.output_to_source == pytest.approx(h / 2, rel=1e-12)


def test_foot_points_are_exact_not_chords() -> None:
    # Points on the normal of a unit circle (source arc) at distance 0.1: the polyline of the
    # coarse grid would be farther; the foot point is exact.
    src = po.SourceCurve.of(circular((0.0, 0.0), 1.0, 0.0, math.pi))
    ang = np.linspace(0.05, math.pi - 0.05, 101)
    pts = 1.1 * np.stack([np.cos(ang), np.sin(ang)], axis=-1)
    d, t = po.foot_distance(src, pts)
    assert np.allclose(d.astype(float), 0.1, rtol=0, atol=1e-15)
    assert np.allclose(t.astype(float), ang / math.pi, rtol=0, atol=1e-14)


# -- the certified bounds --------------------------------------------------------------


def test_certified_known_answers() -> None:
    straight = [(0.0, 0.0), (1.0, 0.0), (2.0, 0.0), (3.0, 0.0)]
    assert po.certified_line_deviation(straight, 0.0, 1.0, (0.0, 0.0), (1.0, 0.0)) == 0.0
    # A straight cubic against a circle through its ends: farthest at the ends (t = 1/2 is
    # a root of g where it touches).
    far = po.certified_arc_deviation(straight, 0.0, 1.0, (1.5, -10.0), 10.0)
    assert far == pytest.approx(math.sqrt(1.5**2 + 100.0) - 10.0, rel=1e-15)
    assert po.certified_arc_deviation(straight, 0.5, 0.5, (1.5, -10.0), 10.0) == 0.0
    # Quadratic bump y = 2h·t(1 − t) against y = 0: h/2, exactly representable.
    bump = [(0.0, 0.0), (1.0, 0.5), (2.0, 0.0)]
    assert po.certified_line_deviation(bump, 0.0, 1.0, (0.0, 0.0), (2.0, 0.0)) == 0.25
    assert po.certified_line_deviation(bump, 0.0, 0.25, (0.0, 0.0), (5.0, 0.0)) == 0.1875
    # A quarter circle by the classic cubic (k = 4/3·tan(π/8)) is at most ~2.7e-4 outside.
    k = 4 / 3 * math.tan(math.pi / 8)
    quarter = [(1.0, 0.0), (1.0, k), (k, 1.0), (0.0, 1.0)]
    err = po.certified_arc_deviation(quarter, 0.0, 1.0, (0.0, 0.0), 1.0)
    assert err == pytest.approx(2.7253e-4, rel=1e-4)


def one_sided(source: Any, u0: float, u1: float, out: dict[str, Any]) -> float:
    """The oracle's sampled ``max_t dist(S(t), out)`` over ``[u0, u1]``."""
    return po.measure_piece_sides(source, u0, u1, out).source_to_output


def _near_arc_cubic(rng: np.random.Generator) -> tuple[np.ndarray, np.ndarray, float, float]:
    """A cubic close to an arc: the classic arc cubic with its control points disturbed."""
    c = rng.uniform(-5, 5, 2)
    r = rng.uniform(0.5, 5.0)
    a0, sweep = rng.uniform(-math.pi, math.pi), rng.choice([-1, 1]) * rng.uniform(0.3, 1.5)
    k = 4 / 3 * math.tan(sweep / 4) * r
    e0 = np.array([math.cos(a0), math.sin(a0)])
    e1 = np.array([math.cos(a0 + sweep), math.sin(a0 + sweep)])
    p0, p3 = c + r * e0, c + r * e1
    p1 = p0 + k * np.array([-e0[1], e0[0]])
    p2 = p3 - k * np.array([-e1[1], e1[0]])
    cp = np.array([p0, p1, p2, p3]) + rng.normal(0, 0.02 * r, (4, 2))
    return cp, c, r, sweep


@pytest.mark.parametrize("seed", range(6))
def test_certified_matches_dense_sampling_on_random_cubics(seed: int) -> None:
    rng = np.random.default_rng(seed)
    cp, c, r, sweep = _near_arc_cubic(rng)
    u0, u1 = sorted(rng.uniform(0, 1, 2))
    if seed % 3 == 0:
        u0, u1 = 0.0, 1.0
    cubic = Cubic(*(pt(*p) for p in cp))
    r_out = r * (1 + rng.normal(0, 0.01))
    # An output arc whose sector holds the whole piece with room to spare, so that the
    # sampled distance to it is the radial distance the certified bound measures.
    ts = np.linspace(u0, u1, 4001)
    q = po.SourceCurve.of(cubic).point(ts).astype(float) - c
    ang = np.unwrap(np.arctan2(q[:, 1], q[:, 0]))
    lo, hi = ang.min() - 0.2, ang.max() + 0.2
    out = arc_out(c, r_out, lo, hi - lo) if sweep > 0 else arc_out(c, r_out, hi, lo - hi)
    exact = po.certified_arc_deviation(cp, u0, u1, c, r_out)
    sampled = one_sided(cubic, u0, u1, out)
    assert sampled == pytest.approx(exact, rel=1e-9)
    assert sampled <= exact * (1 + 1e-15)

    # The same cubic against a line near its chord, long enough to hold every foot.
    a, b = cp[0] + rng.normal(0, 0.1, 2), cp[3] + rng.normal(0, 0.1, 2)
    direction = (b - a) / np.linalg.norm(b - a)
    a, b = a - 20 * r * direction, b + 20 * r * direction
    exact = po.certified_line_deviation(cp, u0, u1, a, b)
    sampled = one_sided(cubic, u0, u1, line_out(a, b))
    assert sampled == pytest.approx(exact, rel=1e-9)


def test_certified_quadratic_matches_sampling() -> None:
    cp = np.array([[0.0, 0.0], [1.3, 2.1], [3.0, 0.4]])
    quad = Quadratic(*(pt(*p) for p in cp))
    c, r = (1.5, -2.0), 3.1
    exact = po.certified_arc_deviation(cp, 0.0, 1.0, c, r)
    out = arc_out(c, r, 0.2, 2.8)  # holds the whole bump
    sampled = one_sided(quad, 0.0, 1.0, out)
    assert sampled == pytest.approx(exact, rel=1e-9)


# -- whole paths -----------------------------------------------------------------------


def stadium() -> tuple[Any, list[dict[str, Any]]]:
    """A closed stadium (line, semicircle, line, semicircle; G1 everywhere) and its exact
    output, each semicircle as two quarter arcs."""
    segs = (
        Line(pt(0, 0), pt(4, 0)),
        CircularArc(pt(4, 0), pt(4, 2), pt(4, 1), 1.0, -HALF_PI, math.pi),
        Line(pt(4, 2), pt(0, 2)),
        CircularArc(pt(0, 2), pt(0, 0), pt(0, 1), 1.0, HALF_PI, math.pi),
    )
    outs = [
        line_out((0, 0), (4, 0), source=0),
        arc_out((4, 1), 1.0, -HALF_PI, HALF_PI, source=1, u=(0.0, 0.5), start=(4, 0), end=(5, 1)),
        arc_out((4, 1), 1.0, 0.0, HALF_PI, source=1, u=(0.5, 1.0), start=(5, 1), end=(4, 2)),
        line_out((4, 2), (0, 2), source=2),
        arc_out((0, 1), 1.0, HALF_PI, HALF_PI, source=3, u=(0.0, 0.5), start=(0, 2), end=(-1, 1)),
        arc_out((0, 1), 1.0, math.pi, HALF_PI, source=3, u=(0.5, 1.0), start=(-1, 1), end=(0, 0)),
    ]
    return Path((Subpath(segs, closed=True),)), outs


def square() -> tuple[Any, list[dict[str, Any]]]:
    """A closed unit square of lines (a corner at every joint) and its exact output."""
    c = [pt(0, 0), pt(1, 0), pt(1, 1), pt(0, 1)]
    segs = tuple(Line(c[i], c[(i + 1) % 4]) for i in range(4))
    outs = [line_out(c[i], c[(i + 1) % 4], source=i) for i in range(4)]
    return Path((Subpath(segs, closed=True),)), outs


TOL = 1e-3


def test_exact_outputs_pass() -> None:
    path, outs = stadium()
    sq_path, sq_outs = square()
    both = Path((*path.subpaths, *sq_path.subpaths))
    verdict = po.check_path(both, [outs, sq_outs], TOL)
    assert verdict.ok, verdict.describe()
    assert max(verdict.subpath_max) < 1e-14
    assert max(verdict.subpath_union) < 1e-14


def test_a_bump_approximated_by_its_chord() -> None:
    h = 1e-3  # deviation h/2
    path = Path((Subpath((Quadratic(pt(0, 0), pt(1, h), pt(2, 0)),)),))
    good = [line_out((0, 0), (2, 0), deviation=h / 2)]
    verdict = po.check_path(path, [good], TOL)
    assert verdict.ok, verdict.describe()
    assert verdict.subpath_max[0] == pytest.approx(h / 2, rel=1e-12)
    assert verdict.subpath_union[0] == pytest.approx(h / 2, rel=1e-12)

    tight = po.check_path(path, [good], 0.4 * h)
    assert any("exceeds tolerance" in v for v in tight.violations), tight.describe()
    assert any("union Hausdorff" in v for v in tight.violations), tight.describe()

    for wrong, says in ((0.0, "above the reported"), (h, "above the measured")):
        bad = [line_out((0, 0), (2, 0), deviation=wrong)]
        verdict = po.check_path(path, [bad], TOL)
        assert any(says in v for v in verdict.violations), verdict.describe()


def test_catches_a_shifted_arc() -> None:
    path, outs = stadium()
    shifted = copy.deepcopy(outs)
    for key in ("start", "end", "center"):
        shifted[1][key][0] += 0.01
    verdict = po.check_path(path, [shifted], TOL)
    assert any("output 1" in v and "exceeds tolerance" in v for v in verdict.violations)
    assert any("gap" in v for v in verdict.violations), verdict.describe()


def test_catches_a_gap_in_the_chain() -> None:
    path, outs = stadium()
    gapped = copy.deepcopy(outs)
    gapped[3]["end"][1] += 1e-7  # still well within tolerance
    verdict = po.check_path(path, [gapped], TOL)
    assert any("joint 3/4: gap" in v for v in verdict.violations), verdict.describe()
    assert not any("exceeds tolerance" in v for v in verdict.violations)

    # The start must be exact: one ulp off is reported.
    sq_path, sq_outs = square()
    sq_outs[0]["start"][0] = math.nextafter(0.0, 1.0)
    verdict = po.check_path(sq_path, [sq_outs], TOL)
    assert any("chain start gap" in v for v in verdict.violations), verdict.describe()


def test_catches_a_tangent_break_where_the_source_is_smooth() -> None:
    path, outs = stadium()
    kinked = copy.deepcopy(outs)
    kink = (2.0, 1e-6)
    kinked[0:1] = [
        line_out((0, 0), kink, source=0, u=(0.0, 0.5), deviation=1e-6),
        line_out(kink, (4, 0), source=0, u=(0.5, 1.0), deviation=1e-6),
    ]
    verdict = po.check_path(path, [kinked], TOL)
    assert any(
        "joint 0/1: output tangents" in v and "inside source segment 0" in v
        for v in verdict.violations
    ), verdict.describe()
    # The seam (the source is smooth where the stadium closes) is broken too.
    assert any("seam 6/0: output tangents" in v for v in verdict.violations)
    assert not any("exceeds tolerance" in v or "gap" in v for v in verdict.violations)


def _arc_through(p: np.ndarray, tangent: np.ndarray, q: np.ndarray) -> tuple[Any, ...]:
    """The arc leaving ``p`` along unit ``tangent`` and ending at ``q``: ``(C, r, θ₀, Δθ)``."""
    normal = np.array([-tangent[1], tangent[0]])
    d = q - p
    signed = float(d @ d / (2 * d @ normal))
    c = p + signed * normal
    a0, a1 = math.atan2(*(p - c)[::-1]), math.atan2(*(q - c)[::-1])
    sense = 1.0 if signed > 0 else -1.0
    return c, abs(signed), a0, sense * ((sense * (a1 - a0)) % (2 * math.pi))


def biarcs(cubic: Cubic, pieces: int) -> list[dict[str, Any]]:
    """A G1 arc spline of ``cubic``: one biarc (equal tangent lengths) per equal ``t`` piece,
    the joint answering for the ``t`` of its foot point; reported deviations measured."""
    src = po.SourceCurve.of(cubic)
    ts = np.linspace(0.0, 1.0, pieces + 1)
    pts = [np.array(cubic.start)] + [src.point(t).astype(float) for t in ts[1:-1]]
    pts.append(np.array(cubic.end))
    outs = []
    for i in range(pieces):
        p0, p1 = pts[i], pts[i + 1]
        t0, t1 = (src.tangent(float(t)).astype(float) for t in ts[i : i + 2])
        t0, t1 = t0 / np.linalg.norm(t0), t1 / np.linalg.norm(t1)
        v, tt = p1 - p0, t0 + t1
        a, b, c = 2 * (1 - t0 @ t1), 2 * (v @ tt), -(v @ v)
        d = (-b + math.sqrt(b * b - 4 * a * c)) / (2 * a)
        m = 0.5 * (p0 + d * t0 + p1 - d * t1)
        um = float(po.foot_distance(src, m[None, :], ts[i], ts[i + 1])[1][0])
        c1, r1, a1, s1 = _arc_through(p0, t0, m)
        tm = math.copysign(1.0, s1) * np.array([-(m - c1)[1], (m - c1)[0]]) / r1
        c2, r2, a2, s2 = _arc_through(m, tm, p1)
        u = (float(ts[i]), um, float(ts[i + 1]))
        outs.append(arc_out(c1, r1, a1, s1, u=u[:2], start=p0, end=m))
        outs.append(arc_out(c2, r2, a2, s2, u=u[1:], start=m, end=p1))
    for o in outs:
        o["max_deviation"] = po.measure_piece(cubic, o["u_start"], o["u_end"], o)
    return outs


def test_a_g1_arc_spline_of_a_cubic_passes_and_agrees_with_flint() -> None:
    cp = [(0.0, 0.0), (30.0, 40.0), (70.0, -10.0), (100.0, 20.0)]
    cubic = Cubic(*cp)
    outs = biarcs(cubic, 3)
    verdict = po.check_path(Path((Subpath((cubic,)),)), [outs], 0.5)
    assert verdict.ok, verdict.describe()
    assert 0.4 < verdict.subpath_max[0] < 0.5
    src = po.SourceCurve.of(cubic)
    for o in outs:
        u0, u1 = o["u_start"], o["u_end"]
        radial = po.certified_arc_deviation(cp, u0, u1, o["center"], o["radius"])
        one_side, _ = po.source_to_output(src, u0, u1, po.Outputs.of([o]).take(0))
        assert one_side == pytest.approx(radial, rel=1e-9)
        assert radial <= o["max_deviation"] * (1 + 1e-12)


def test_corners_of_the_source_may_be_corners_of_the_output() -> None:
    path, outs = square()
    assert po.check_path(path, [outs], TOL).ok


def test_catches_bad_tiling_and_inconsistent_arcs() -> None:
    path, outs = stadium()
    bad = copy.deepcopy(outs)
    bad[2]["u_start"] = 0.6  # leaves u 0.5..0.6 of source 1 unanswered
    bad[4]["sweep_rad"] = -HALF_PI  # disagrees with its direction and its end points
    verdict = po.check_path(path, [bad], TOL)
    text = verdict.describe()
    assert "u ranges do not tile" in text
    assert "does not fit direction" in text
    assert "start→end turns" in text
    sq_path, sq_outs = square()
    missing = po.check_path(sq_path, [sq_outs[:2] + sq_outs[3:]], TOL)
    assert any("source segment 2 has no output" in v for v in missing.violations)


# -- regressions -----------------------------------------------------------------------


def _turning_points(cp: list[tuple[float, float]]) -> list[float]:
    """The parameters in (0, 1) where a cubic on the x axis turns back: roots of x'(t)."""
    x = [p[0] for p in cp]
    # x'(t)/3 = (x1 − x0)(1 − t)² + 2(x2 − x1)t(1 − t) + (x3 − x2)t², in the power basis.
    a, b, c = x[1] - x[0], x[2] - x[1], x[3] - x[2]
    roots = np.roots([a - 2 * b + c, 2 * (b - a), a])
    return sorted(float(r.real) for r in roots if abs(r.imag) < 1e-15 and 0 < r.real < 1)


def _lines_along(cubic: Cubic, cuts: list[float]) -> list[dict[str, Any]]:
    """The exact output of a straight cubic: one line per piece between ``cuts``."""
    src = po.SourceCurve.of(cubic)
    ts = [0.0, *cuts, 1.0]
    ends = [cubic.start, *(tuple(src.point(t).astype(float)) for t in cuts), cubic.end]
    return [line_out(ends[i], ends[i + 1], u=(ts[i], ts[i + 1])) for i in range(len(ts) - 1)]


def test_a_line_that_doubles_back_is_its_own_set() -> None:
    # x(t) runs 0 → 3.618 → 1.382 → 5: the grid crowds at the turning points, where the
    # nearest samples of a point just past the first one (x = 3.643) all lie on that turn,
    # 0.025 away, while the true foot (distance 0) lies on the last branch.
    cp = [(0.0, 0.0), (10.0, 0.0), (-5.0, 0.0), (5.0, 0.0)]
    cubic = Cubic(*(pt(*p) for p in cp))
    src = po.SourceCurve.of(cubic)
    xs = np.linspace(0.0, 5.0, 2001)
    d, _ = po.foot_distance(src, np.stack([xs, np.zeros_like(xs)], axis=-1))
    assert float(np.max(d)) < 1e-14
    outs = _lines_along(cubic, _turning_points(cp))
    verdict = po.check_path(Path((Subpath((cubic,)),)), [outs], TOL)
    assert verdict.ok, verdict.describe()
    assert verdict.subpath_union[0] < 1e-14


def test_the_seam_of_a_one_segment_subpath_compares_its_end_with_its_start() -> None:
    # A loop closed by one cubic: it leaves along +x and returns along (1, −1) — a corner at
    # the seam, though both sides of it are source segment 0.
    loop = Cubic(pt(100, 100), pt(150, 100), pt(50, 150), pt(100, 100))
    outs = biarcs(loop, 6)
    tol = 1.01 * max(o["max_deviation"] for o in outs)
    verdict = po.check_path(Path((Subpath((loop,), closed=True),)), [outs], tol)
    assert verdict.ok, verdict.describe()

    # A closed straight cubic x(t) = 3t(1 − t)(1 − 2t) leaves and returns along +x: smooth at
    # the seam, so a kink there is reported even though both sides are source segment 0.
    cp = [(0.0, 0.0), (1.0, 0.0), (-1.0, 0.0), (0.0, 0.0)]
    line = Cubic(*(pt(*p) for p in cp))
    path = Path((Subpath((line,), closed=True),))
    outs = _lines_along(line, _turning_points(cp))
    verdict = po.check_path(path, [outs], TOL)
    assert verdict.ok, verdict.describe()
    kinked = copy.deepcopy(outs)
    tip = [0.5 * kinked[-1]["start"][0], 1e-5]
    last = kinked.pop()
    u_mid = 0.5 * (last["u_start"] + last["u_end"])
    kinked += [
        line_out(last["start"], tip, u=(last["u_start"], u_mid), deviation=1e-5),
        line_out(tip, last["end"], u=(u_mid, 1.0), deviation=1e-5),
    ]
    verdict = po.check_path(path, [kinked], TOL)
    assert any(
        "seam 3/0: output tangents" in v and "at the seam" in v for v in verdict.violations
    ), verdict.describe()
