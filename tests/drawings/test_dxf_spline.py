"""SPLINE → Bézier pieces and conic arcs, checked against ezdxf's own evaluation
(``BSpline.point``) by dense sampling: an independent computation."""

from __future__ import annotations

import itertools
import math

import numpy as np
import pytest
from ezdxf.math import BSpline

from arcspline.drawings.dxf_spline import (
    SplineData,
    SplineRefusedError,
    spline_segments,
)
from arcspline.geometry.curves.segments import (
    CircularArc,
    Cubic,
    EllipticalArc,
    Line,
    Quadratic,
    Segment,
)
from arcspline.geometry.spline import Point
from tests.support.nurbs_oracle import cubic_chain, hausdorff, nurbs, rational_bezier


def bezier(points: list[tuple[float, float]], t: float) -> tuple[float, float]:
    """de Casteljau, written here (not the code under test)."""
    pts = [np.array(p, dtype=float) for p in points]
    while len(pts) > 1:
        pts = [(1 - t) * a + t * b for a, b in itertools.pairwise(pts)]
    return float(pts[0][0]), float(pts[0][1])


def control(segment: Segment) -> list[tuple[float, float]]:
    if isinstance(segment, Line):
        return [segment.start, segment.end]
    if isinstance(segment, Quadratic):
        return [segment.start, segment.control, segment.end]
    assert isinstance(segment, Cubic)
    return [segment.start, segment.control1, segment.control2, segment.end]


def on_conic(segment: CircularArc | EllipticalArc, x: float, y: float) -> float:
    """How far ``(x, y)`` is from the arc's ellipse, in the ellipse's implicit form."""
    if isinstance(segment, CircularArc):
        return math.hypot(x - segment.center[0], y - segment.center[1]) / segment.radius - 1
    dx, dy = x - segment.center[0], y - segment.center[1]
    c, s = math.cos(segment.rotation_rad), math.sin(segment.rotation_rad)
    u, v = (c * dx + s * dy) / segment.rx, (-s * dx + c * dy) / segment.ry
    return u * u + v * v - 1


def spans(knots: list[float], degree: int, count: int) -> list[tuple[float, float]]:
    return [(knots[k], knots[k + 1]) for k in range(degree, count) if knots[k] < knots[k + 1]]


def data(points, knots, weights=()) -> SplineData:  # type: ignore[no-untyped-def]
    degree = len(knots) - len(points) - 1
    return SplineData(degree, tuple(knots), tuple(Point(*p) for p in points), tuple(weights))


def on_domain(reference: BSpline, count: int, s: float) -> float:
    """ezdxf's parameter at the fraction ``s`` of the domain ``[U[p], U[n]]``: ezdxf may
    rescale the knots it was given (it does when the first is negative)."""
    knots = reference.knots()
    a, b = knots[reference.degree], knots[count]
    return a + s * (b - a)


def assert_chained(segments: tuple[Segment, ...]) -> None:
    for a, b in itertools.pairwise(segments):
        assert a.end is b.start or a.end == b.start


@pytest.mark.parametrize(
    "knots",
    [
        [0, 0, 0, 0, 1, 2, 2, 3, 3, 3, 3],  # clamped, a double knot
        [0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10],  # unclamped, uniform
        [0, 0.5, 1, 1, 1, 2, 3, 4, 5, 6, 7],  # unclamped start, a triple knot
    ],
)
def test_polynomial_cubic_matches_ezdxf_pointwise(knots: list[float]) -> None:
    rng = np.random.default_rng(7)
    points = [tuple(p) for p in rng.uniform(-50, 50, size=(7, 2))]
    result = spline_segments(data(points, knots))
    reference = BSpline([(*p, 0) for p in points], order=4, knots=knots)
    pieces = spans(knots, 3, len(points))
    assert len(result.segments) == len(pieces)
    assert_chained(result.segments)
    for segment, (a, b) in zip(result.segments, pieces, strict=True):
        assert isinstance(segment, Cubic)
        for t in np.linspace(0, 1, 41):
            want = reference.point(a + t * (b - a))
            got = bezier(control(segment), t)
            assert math.hypot(got[0] - want.x, got[1] - want.y) < 1e-9


def test_degree_one_and_two_pieces() -> None:
    lines = spline_segments(data([(0, 0), (1, 0), (1, 1)], [0, 0, 1, 2, 2]))
    assert lines.segments == (Line((0.0, 0.0), (1.0, 0.0)), Line((1.0, 0.0), (1.0, 1.0)))
    points = [(0, 0), (2, 3), (4, -1), (6, 2)]
    knots = [0, 0, 0, 0.3, 1, 1, 1]
    quads = spline_segments(data(points, knots))
    reference = BSpline([(*p, 0) for p in points], order=3, knots=knots)
    for segment, (a, b) in zip(quads.segments, spans(knots, 2, 4), strict=True):
        assert isinstance(segment, Quadratic)
        for t in np.linspace(0, 1, 21):
            want = reference.point(a + t * (b - a))
            assert math.dist(bezier(control(segment), t), (want.x, want.y)) < 1e-12


def test_rational_full_circle_is_four_exact_quarter_arcs() -> None:
    # the arcs-as-splines.dxf layout: 9 points, weights 1, √½, …, knots doubled
    r, cx, cy = 32.32, 201.3, 180.1
    offsets = [(1, 0), (1, 1), (0, 1), (-1, 1), (-1, 0), (-1, -1), (0, -1), (1, -1), (1, 0)]
    points = [(cx + r * x, cy + r * y) for x, y in offsets]
    weights = [1.0, math.sqrt(0.5)] * 4 + [1.0]
    knots = [0, 0, 0, 1, 1, 2, 2, 3, 3, 4, 4, 4]
    result = spline_segments(data(points, knots, weights))
    assert result.closed
    assert len(result.segments) == 4
    assert result.segments[-1].end == result.segments[0].start
    assert_chained(result.segments)
    reference = BSpline([(*p, 0) for p in points], order=3, knots=knots, weights=weights)
    for segment in result.segments:
        assert isinstance(segment, CircularArc | EllipticalArc)
        assert segment.sweep_rad == pytest.approx(math.pi / 2, abs=1e-12)
    for u in np.linspace(0, 4, 401):
        p = reference.point(u)
        assert math.hypot(p.x - cx, p.y - cy) == pytest.approx(r, rel=1e-12)
        assert min(abs(on_conic(s, p.x, p.y)) for s in result.segments) < 1e-12


@pytest.mark.parametrize("w", [0.05, 0.3, 0.9, 0.999])
def test_rational_quadratic_ellipse_matches_ezdxf(w: float) -> None:
    points = [(3.0, -1.0), (7.0, 6.0), (12.0, 1.5)]
    weights = [2.0, 2.0 * w * 1.5, 4.5]  # end weights 2 and 4.5: normalised middle weight w
    result = spline_segments(data(points, [0, 0, 0, 1, 1, 1], weights))
    (arc,) = result.segments
    assert isinstance(arc, EllipticalArc)
    assert arc.start == points[0]
    assert arc.end == points[2]
    reference = BSpline(
        [(*p, 0) for p in points], order=3, knots=[0, 0, 0, 1, 1, 1], weights=weights
    )
    scale = max(arc.rx, arc.ry)
    for u in np.linspace(0, 1, 101):
        p = reference.point(u)
        assert abs(on_conic(arc, p.x, p.y)) < 1e-11 * max(1.0, scale)
    # the arc's own middle point lies on ezdxf's curve (checked on the other side)
    mid = arc.start_angle_rad + arc.sweep_rad / 2
    c, s = math.cos(arc.rotation_rad), math.sin(arc.rotation_rad)
    x = arc.center[0] + c * arc.rx * math.cos(mid) - s * arc.ry * math.sin(mid)
    y = arc.center[1] + s * arc.rx * math.cos(mid) + c * arc.ry * math.sin(mid)
    samples = np.array([(q.x, q.y) for q in reference.points(np.linspace(0, 1, 20001))])
    assert np.min(np.hypot(samples[:, 0] - x, samples[:, 1] - y)) < 1e-3


def test_hyperbola_and_bad_splines_are_refused() -> None:
    points = [(0, 0), (1, 1), (2, 0)]
    with pytest.raises(SplineRefusedError, match="hyperbolic"):
        spline_segments(data(points, [0, 0, 0, 1, 1, 1], [1, 2, 1]))
    with pytest.raises(SplineRefusedError, match="decrease"):
        spline_segments(data(points, [0, 0, 0, 1, 0.5, 1]))
    with pytest.raises(SplineRefusedError, match="degree 0"):
        spline_segments(data(points, [0, 1, 2, 3]))
    with pytest.raises(SplineRefusedError, match="weights"):
        spline_segments(data(points, [0, 0, 0, 1, 1, 1], [1, 1]))
    with pytest.raises(SplineRefusedError, match="not > 0"):
        spline_segments(data(points, [0, 0, 0, 1, 1, 1], [1, -1, 1]))


def test_rational_cubic_elevated_conic_is_read_and_others_refused() -> None:
    # quadratic (1,0),(1,1),(0,1) weights 1, √½, 1 elevated to degree 3 (homogeneous)
    g = [
        np.array([1.0, 0.0, 1.0]),
        np.array([1.0, 1.0, 1.0]) * math.sqrt(0.5),
        np.array([0.0, 1.0, 1.0]),
    ]
    h = [g[0], (g[0] + 2 * g[1]) / 3, (2 * g[1] + g[2]) / 3, g[2]]
    points = [(p[0] / p[2], p[1] / p[2]) for p in h]
    weights = [float(p[2]) for p in h]
    (arc,) = spline_segments(data(points, [0] * 4 + [1] * 4, weights)).segments
    assert isinstance(arc, CircularArc | EllipticalArc)
    reference = BSpline(
        [(*p, 0) for p in points], order=4, knots=[0] * 4 + [1] * 4, weights=weights
    )
    for u in np.linspace(0, 1, 51):
        p = reference.point(u)
        assert math.hypot(p.x, p.y) == pytest.approx(1.0, abs=1e-12)
        assert abs(on_conic(arc, p.x, p.y)) < 1e-12
    with pytest.raises(SplineRefusedError, match="rational cubic"):
        spline_segments(data(points, [0] * 4 + [1] * 4, [1.0, 0.5, 0.9, 1.0]))
    same = spline_segments(data(points, [0] * 4 + [1] * 4, [2.0] * 4)).segments
    assert same == (Cubic(*(Point(*p) for p in points)),)


# --- rational cubics approximated, certified ---------------------------------------------------


def test_rational_cubic_nurbs_becomes_cubics_within_the_bound() -> None:
    points = [(0.0, 0.0), (10.0, 25.0), (30.0, -5.0), (45.0, 20.0), (60.0, 0.0), (70.0, 30.0)]
    weights = [1.0, 4.0, 0.5, 2.0, 0.25, 2.0]
    knots = [0, 0, 0, 0, 1, 2.5, 3, 3, 3, 3]
    tolerance = 1e-4
    result = spline_segments(data(points, knots, weights), tolerance)
    assert all(isinstance(s, Cubic) for s in result.segments)
    assert result.approximating == len(result.segments) > 3
    assert 0.0 < result.approximated <= tolerance
    assert_chained(result.segments)
    assert result.segments[0].start == points[0]
    assert result.segments[-1].end == points[-1]
    # the oracle (Cox–de Boor) agrees with ezdxf's own evaluation
    oracle = nurbs(points, knots, 3, weights)
    reference = BSpline([(*p, 0) for p in points], order=4, knots=knots, weights=weights)
    for s in np.linspace(0, 1, 101):
        want = reference.point(on_domain(reference, len(points), s))
        assert math.dist(oracle(np.array([s]))[0], (want.x, want.y)) < 1e-9
    measured = hausdorff(oracle, cubic_chain(result.segments))
    assert result.approximated / 1000 <= measured <= result.approximated
    # G1 everywhere: the NURBS is C2 at its simple knots
    for a, b in itertools.pairwise(result.segments):
        assert isinstance(a, Cubic)
        assert isinstance(b, Cubic)
        u = (a.end[0] - a.control2[0], a.end[1] - a.control2[1])
        v = (b.control1[0] - b.start[0], b.control1[1] - b.start[1])
        assert abs(u[0] * v[1] - u[1] * v[0]) <= 1e-9 * math.hypot(*u) * math.hypot(*v)
        assert u[0] * v[0] + u[1] * v[1] > 0


def test_rational_cubic_beyond_the_cubic_budget_is_refused() -> None:
    points = [(0.0, 0.0), (1e6, 2e6), (3e6, 2e6), (4e6, 0.0)]
    with pytest.raises(SplineRefusedError, match="more than 4096 cubics"):
        spline_segments(data(points, [0] * 4 + [1] * 4, [1.0, 3.0, 0.5, 2.0]), 1e-12)
    with pytest.raises(SplineRefusedError, match="no curve tolerance"):
        spline_segments(data(points, [0] * 4 + [1] * 4, [1.0, 3.0, 0.5, 2.0]))


# --- lowering and closing are relative to the piece, not to the origin -------------------------


def far_conic(offset: float, perturbation: float) -> tuple[list[tuple[float, float]], list[float]]:
    """The quarter circle of radius 10 about (offset, offset) as a rational cubic (the
    quadratic (R,0),(R,R),(0,R) with weights 1, √½, 1 elevated), its third weight raised by
    ``perturbation`` times its largest homogeneous coordinate (the old, origin-relative
    tolerance was 1e-9 of that): a rational cubic that is not a conic."""
    r, w = 10.0, math.sqrt(0.5)
    g = [(r, 0.0, 1.0), (r * w, r * w, w), (0.0, r, 1.0)]
    h = [g[0], *(tuple((a + 2 * b) / 3 for a, b in zip(g[0], g[1], strict=True)),)]
    h += [tuple((2 * b + c) / 3 for b, c in zip(g[1], g[2], strict=True)), g[2]]
    h = [(x + offset * s, y + offset * s, s) for x, y, s in h]
    size = max(abs(c) for p in h for c in p)
    h[2] = (h[2][0], h[2][1], h[2][2] + perturbation * size)
    return [(x / s, y / s) for x, y, s in h], [s for _, _, s in h]


@pytest.mark.parametrize("offset", [0.0, 1e4, 1e5, 1e6])
def test_a_cubic_near_a_conic_is_not_lowered_far_from_the_origin(offset: float) -> None:
    points, weights = far_conic(offset, 0.6e-9)
    knots = [0] * 4 + [1] * 4
    with pytest.raises(SplineRefusedError, match="not an elevated conic"):
        spline_segments(data(points, knots, weights))
    result = spline_segments(data(points, knots, weights), 1e-4)
    assert all(isinstance(s, Cubic) for s in result.segments)
    assert 0.0 < result.approximated <= 1e-4
    # the true curve by the Bernstein formula, in coordinates relative to the offset (exact:
    # the offset is a whole number), against the cubics moved the same way
    local = [(x - offset, y - offset) for x, y in points]
    moved = [
        Cubic(*(Point(p[0] - offset, p[1] - offset) for p in control(c))) for c in result.segments
    ]
    measured = hausdorff(rational_bezier(local, weights), cubic_chain(moved))
    assert measured <= result.approximated


def test_an_elevated_conic_is_lowered_wherever_it_lies_exactly() -> None:
    # the quadratic (0,0), (2,4), (4,0) with weights 1, ½, 1 (an ellipse arc) elevated by hand:
    # H1 = (G0 + 2·G1)/3 = (2/3, 4/3, 2/3), H2 = (2·G1 + G2)/3 = (2, 4/3, 2/3), i.e. points
    # (1, 2), (3, 2) of weight ⅔. Offsets that are whole numbers keep every point exact, so
    # the piece relative to itself is the same wherever it lies: lowered each time.
    weights = [1.0, 2 / 3, 2 / 3, 1.0]
    conic = rational_bezier([(0.0, 0.0), (2.0, 4.0), (4.0, 0.0)], [1.0, 0.5, 1.0])
    for offset in (0.0, 1e6, 2.0**40):
        points = [(offset + x, offset + y) for x, y in ((0, 0), (1, 2), (3, 2), (4, 0))]
        result = spline_segments(data(points, [0] * 4 + [1] * 4, weights))
        (arc,) = result.segments
        assert isinstance(arc, EllipticalArc | CircularArc)
        assert result.approximated == 0.0
        assert arc.start == points[0]
        assert arc.end == points[3]
        for x, y in conic(np.linspace(0, 1, 41)):
            # to the rounding of the coordinates (their ulp is 2.2e-16 of the offset)
            assert abs(on_conic(arc, x + offset, y + offset)) < 1e-12 + 1e-15 * offset


def test_closing_snap_is_relative_to_the_extent_and_reported() -> None:
    knots = [0] * 4 + [1] * 4
    for offset in (0.0, 1e6):
        # a loop of extent 10 whose end misses its start by 2e-9: within 1e-9 of 10, closed
        near = [(offset, offset), (offset + 10, offset + 10), (offset - 10, offset + 10),
                (offset + 2e-9, offset)]  # fmt: skip
        gap = math.dist(near[0], near[3])
        result = spline_segments(data(near, knots))
        assert result.closed
        assert result.segments[-1].end == result.segments[0].start
        assert result.approximating == 0
        assert result.approximated == gap > 0.0
        # 1e-6 off: 1e-7 of the extent, not closed (the old test, relative to 1e6, took it)
        far = [*near[:3], (offset + 1e-6, offset)]
        opened = spline_segments(data(far, knots))
        assert not opened.closed
        assert opened.approximated == 0.0
        assert opened.segments[-1].end == far[3]


def test_knot_multiplicity_is_counted_in_one_pass() -> None:
    # 60 000 control points: the count was quadratic (18.9 s at 32 000); now linear
    n = 60_000
    points = [(float(i), float((i * 7919) % 13)) for i in range(n)]
    knots = [0.0] * 4 + [float(i) for i in range(1, n - 3)] + [float(n - 3)] * 4
    result = spline_segments(data(points, knots))
    assert len(result.segments) == n - 3
    assert result.segments[0].start == points[0]
    assert result.segments[-1].end == points[-1]
    with pytest.raises(SplineRefusedError, match="knot 5 repeats 4 times"):
        spline_segments(data(points[:12], [0, 0, 0, 0, 1, 2, 3, 4, 5, 5, 5, 5, 6, 6, 6, 6]))
