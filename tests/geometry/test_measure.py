"""Exact distances from curve pieces to lines and circles (``measure.pyx``), through a spiral,
against dense sampling of the oracle's own Bernstein evaluation."""

from __future__ import annotations

import numpy as np
import pytest

from arcspline.geometry import Spiral, approximate
from tests.support import oracle

SPIRALS = {
    "paper": Spiral.from_parameters((1.5, 3.0), (1.0, 0.0), 51.34, 0.41574),
    "sharp": Spiral.from_parameters((0.0, 0.0), (0.0, 1.0), 85.0, -2.0),
    "straight": Spiral.from_parameters((-3.0, 2.0), (1.0, 1.0), 0.5, 0.01),
}


def _sampled_line(cp: np.ndarray, u0: float, u1: float, a: np.ndarray, b: np.ndarray) -> float:
    p = oracle.bezier_point(cp, np.linspace(u0, u1, 20001))
    n = np.array([-(b - a)[1], (b - a)[0]]) / np.hypot(*(b - a))
    return float(np.max(np.abs((p - a) @ n)))


def _sampled_circle(cp: np.ndarray, u0: float, u1: float, c: np.ndarray, r: float) -> float:
    p = oracle.bezier_point(cp, np.linspace(u0, u1, 20001))
    return float(np.max(np.abs(np.hypot(*(p - c).T) - r)))


@pytest.mark.parametrize("name", sorted(SPIRALS))
def test_line_deviation_is_the_sampled_maximum(name: str) -> None:
    s = SPIRALS[name]
    cp = np.asarray(s.control_points)
    cols = approximate(s, 1e-3 * s.chord).columns
    exact = s.line_deviations(cols.u_start, cols.u_end, cols.start, cols.end)
    for i in range(len(cols)):
        sampled = _sampled_line(cp, cols.u_start[i], cols.u_end[i], cols.start[i], cols.end[i])
        assert exact[i] == pytest.approx(sampled, rel=1e-7, abs=1e-12 * s.coordinate_scale)
    # Off the piece's own end points it is still the distance to the line.
    shifted = cols.start[:1] + np.array([[1e-3, -2e-3]])
    exact = s.line_deviations(cols.u_start[:1], cols.u_end[:1], shifted, cols.end[:1])
    sampled = _sampled_line(cp, cols.u_start[0], cols.u_end[0], shifted[0], cols.end[0])
    assert exact[0] == pytest.approx(sampled, rel=1e-7)


@pytest.mark.parametrize("name", sorted(SPIRALS))
def test_circle_deviation_is_the_sampled_maximum(name: str) -> None:
    s = SPIRALS[name]
    cp = np.asarray(s.control_points)
    cols = approximate(s, 1e-3 * s.chord).columns
    arcs = np.flatnonzero(cols.is_arc)
    exact = s.circle_deviations(
        cols.u_start[arcs], cols.u_end[arcs], cols.center[arcs], cols.radius[arcs],
        cols.radius[arcs],
    )  # fmt: skip
    for k, i in enumerate(arcs):
        sampled = _sampled_circle(
            cp, cols.u_start[i], cols.u_end[i], cols.center[i], cols.radius[i]
        )
        assert exact[k] == pytest.approx(sampled, rel=1e-6, abs=1e-11 * s.coordinate_scale)


def test_a_degenerate_chord_measures_the_distance_to_its_point() -> None:
    s = SPIRALS["paper"]
    cp = np.asarray(s.control_points)
    point = np.array([[2.0, 3.5]])
    exact = s.line_deviations(np.array([0.1]), np.array([0.3]), point, point)
    sampled = _sampled_circle(cp, 0.1, 0.3, point[0], 0.0)
    assert exact[0] == pytest.approx(sampled, rel=1e-7)
