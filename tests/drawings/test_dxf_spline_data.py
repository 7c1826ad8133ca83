"""SPLINE entities → NURBS data: OpenCascade's periodic splines (the knots of one period)
unwrapped, checked by ezdxf's evaluation of the NURBS written out by hand, which must close
with C2 continuity at the seam: an independent computation."""

from __future__ import annotations

import math

import ezdxf
import numpy as np
from ezdxf.math import BSpline

from arcspline.drawings.dxf_spline import spline_segments
from arcspline.drawings.dxf_spline_data import spline_data
from arcspline.geometry.curves.segments import Cubic
from tests.drawings.test_dxf_spline import bezier, control, data, on_domain, spans
from tests.support.nurbs_oracle import cubic_chain, hausdorff, nurbs


def periodic_entity(points, knots, weights=()):  # type: ignore[no-untyped-def]
    doc = ezdxf.new("R2000")
    spline = doc.modelspace().add_spline()
    spline.control_points = [(*p, 0.0) for p in points]
    spline.knots = knots
    spline.weights = list(weights)
    spline.dxf.degree = 3
    spline.dxf.flags = 2 | 1 | (4 if weights else 0)
    return spline


def test_periodic_nonuniform_knots_unwrap_to_a_closed_c2_curve() -> None:
    points = [(0.0, 0.0), (12.0, 15.0), (31.0, 6.0), (22.0, 12.0), (5.0, 20.0)]
    knots = [0.0, 1.0, 3.0, 4.0, 7.0, 8.0]
    spline, notes = spline_data(periodic_entity(points, knots))
    assert any("periodic" in n for n in notes)
    # written out by hand: P0…P4, P0, P1, P2; the spacing 1, 2, 1, 3, 1 repeated both ways
    unwrapped = [*points, *points[:3]]
    extended = [-5.0, -4.0, -1.0, 0.0, 1.0, 3.0, 4.0, 7.0, 8.0, 9.0, 11.0, 12.0]
    assert spline == data(unwrapped, extended)
    # independently: ezdxf's curve of the written-out NURBS closes with C2 at the seam
    reference = BSpline([(*p, 0) for p in unwrapped], order=4, knots=extended)
    at_start = reference.derivative(on_domain(reference, 8, 0.0), 2)
    at_end = reference.derivative(on_domain(reference, 8, 1.0), 2)
    for a, b in zip(at_start, at_end, strict=True):
        assert a.isclose(b, abs_tol=1e-9 * max(1.0, b.magnitude))
    result = spline_segments(spline)
    assert result.closed
    assert len(result.segments) == 5
    assert result.segments[-1].end == result.segments[0].start
    for segment, (a, b) in zip(result.segments, spans(extended, 3, 8), strict=True):
        for t in np.linspace(0, 1, 21):
            want = reference.point(on_domain(reference, 8, (a + t * (b - a)) / 8.0))
            assert math.dist(bezier(control(segment), t), (want.x, want.y)) < 1e-9


def test_periodic_rational_cubic_is_approximated_and_closes() -> None:
    points = [(0.0, 0.0), (1250.0, 1560.0), (3130.0, 610.0), (2250.0, 1250.0)]
    weights = [3.0, 1.0, 1.0, 1.0]
    spline, _ = spline_data(periodic_entity(points, [0.0, 1.0, 2.0, 3.0, 4.0], weights))
    unwrapped = [*points, *points[:3]]
    extended = [float(k) for k in range(-3, 8)]
    assert spline == data(unwrapped, extended, [*weights, *weights[:3]])
    result = spline_segments(spline, 1e-3)
    assert result.closed
    assert result.segments[-1].end == result.segments[0].start
    assert 0.0 < result.approximated <= 1e-3
    measured = hausdorff(
        nurbs(unwrapped, extended, 3, [*weights, *weights[:3]]), cubic_chain(result.segments)
    )
    assert result.approximated / 1000 <= measured <= result.approximated
    # G1 across the seam
    first, last = result.segments[0], result.segments[-1]
    assert isinstance(first, Cubic)
    assert isinstance(last, Cubic)
    u = (last.end[0] - last.control2[0], last.end[1] - last.control2[1])
    v = (first.control1[0] - first.start[0], first.control1[1] - first.start[1])
    assert abs(u[0] * v[1] - u[1] * v[0]) <= 1e-9 * math.hypot(*u) * math.hypot(*v)


def test_a_closed_spline_with_ordinary_knots_is_not_unwrapped() -> None:
    points = [(0.0, 0.0), (1.0, 2.0), (3.0, 2.0), (4.0, 0.0)]
    spline, notes = spline_data(periodic_entity(points, [0, 0, 0, 0, 1, 1, 1, 1]))
    assert spline == data(points, [0, 0, 0, 0, 1, 1, 1, 1])
    assert not notes
