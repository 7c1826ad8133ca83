"""The certified deviation of an arc from a spiral piece (``deviation.pyx``), against dense
sampling computed here from scratch."""

from __future__ import annotations

import math

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from arcspline.geometry.deviation import deviation_of_arc


@settings(max_examples=40, deadline=None)
@given(
    theta_deg=st.floats(2.0, 88.0),
    u_a=st.floats(0.0, 0.9),
    length=st.floats(0.01, 0.3),
    offset=st.floats(-0.01, 0.01),
    tilt=st.floats(-0.02, 0.02),
    bend=st.floats(0.5, 1.5),
)
def test_exact_arc_deviation_matches_dense_sampling(
    theta_deg: float, u_a: float, length: float, offset: float, tilt: float, bend: float
) -> None:
    # An arc near the canonical spiral Q(u) = (3u + k·u³, m·u³), off it by ``offset`` and
    # ``tilt``, bent ``bend`` times the spiral's curvature. The proven maximum must be the
    # largest radial distance found by dense sampling of the spiral piece between the arc's
    # end normals — computed here from scratch with a plain Bézier-free polynomial and a
    # bisection for the piece's ends.
    th = math.radians(theta_deg)
    k, m = 1.2 * math.cos(th) ** 2 - 1.0, 1.2 * math.cos(th) * math.sin(th)

    def q(u: np.ndarray) -> np.ndarray:
        return np.stack([3 * u + k * u**3, m * u**3], axis=-1)

    def dq(u: float) -> np.ndarray:
        return np.array([3 + 3 * k * u * u, 3 * m * u * u])

    u_b = min(1.0, u_a + length)
    t = dq(u_a) / np.linalg.norm(dq(u_a))
    nrm = np.array([-t[1], t[0]])
    phi = math.atan2(t[1], t[0]) + tilt
    start = q(np.array(u_a)) + offset * nrm
    d1, d2 = dq(u_a), np.array([6 * k * u_a, 6 * m * u_a])
    kappa = bend * max((d1[0] * d2[1] - d1[1] * d2[0]) / np.linalg.norm(d1) ** 3, 1e-3)
    sweep = kappa * np.linalg.norm(q(np.array(u_b)) - q(np.array(u_a)))
    centre = start + np.array([-math.sin(phi), math.cos(phi)]) / kappa
    end = centre + (start - centre) @ np.array(
        [[math.cos(sweep), math.sin(sweep)], [-math.sin(sweep), math.cos(sweep)]]
    )

    def split(point: np.ndarray, direction: float) -> float:
        tangent = np.array([math.cos(direction), math.sin(direction)])
        lo, hi = 0.0, 1.0
        for _ in range(200):
            mid = 0.5 * (lo + hi)
            if (q(np.array(mid)) - point) @ tangent < 0:
                lo = mid
            else:
                hi = mid
        return 0.5 * (lo + hi)

    s_lo, s_hi = split(start, phi), split(end, phi + sweep)
    value, at = deviation_of_arc(
        k, m, start[0], start[1], phi, kappa, end[0], end[1], s_lo, s_hi, 1.0
    )
    if not np.isfinite(value):
        return  # refused (not a polar graph over the arc): nothing is claimed
    assert s_lo <= at <= s_hi
    u = np.linspace(s_lo, s_hi, 200_001)
    sampled = np.abs(np.hypot(*(q(u) - centre).T) - 1.0 / kappa).max()
    # The direct ‖Q − C‖ − r of the sampling loses about eps·radius to cancellation.
    slack = 64 * np.finfo(float).eps * (1.0 / kappa + 4.0)
    assert value >= sampled - slack
    assert value <= sampled * (1 + 1e-6) + slack


def test_an_arc_whose_piece_is_not_a_polar_graph_is_refused() -> None:
    # The canonical spiral of 60°, and an arc leaving its start backwards: the piece's
    # polar angle about the arc's centre is not monotone, so nothing can be claimed.
    th = math.radians(60.0)
    k, m = 1.2 * math.cos(th) ** 2 - 1.0, 1.2 * math.cos(th) * math.sin(th)
    value, _ = deviation_of_arc(k, m, 0.0, 0.0, math.pi, 1.0, -1.0, 1.0, 0.0, 0.3, 1.0)
    assert value == math.inf


def test_a_piece_outside_the_spiral_is_refused() -> None:
    th = math.radians(30.0)
    k, m = 1.2 * math.cos(th) ** 2 - 1.0, 1.2 * math.cos(th) * math.sin(th)
    value, _ = deviation_of_arc(k, m, 0.0, 0.0, 0.0, 0.1, 3.0, 0.5, -0.1, 0.5, 1.0)
    assert value == math.inf
