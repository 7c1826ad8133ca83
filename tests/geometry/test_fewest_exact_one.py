"""The float restatement of the ``fewest-arcs`` proof gives the array version's numbers.

``fewest_exact_one`` is an accelerator: one arc's exact deviation (and one joint's split
parameter) in Python floats must equal, bit for bit, what the numpy cascade computes for it
in a batch of any size, or hand the element back. Whole ``fewest-arcs`` results must not
change when every proof is forced through numpy.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from arcspline.geometry import (
    Spiral,
    approximate,
    approximate_many,
    fewest_exact,
    fewest_newton,
    fewest_tail,
)
from arcspline.geometry import fewest as fewest_module
from arcspline.geometry import fewest_exact_one as one
from tests.geometry.test_fewest import PAPER


def _arcs(seed: int, n: int) -> tuple[np.ndarray, ...]:
    """``n`` arcs near the canonical spiral: off it, tilted and bent, as the search makes
    them (and some that fail the polar-graph test, which must fail alike)."""
    rng = np.random.default_rng(seed)
    theta = rng.uniform(0.02, 1.55, n)
    k, m = 1.2 * np.cos(theta) ** 2 - 1.0, 1.2 * np.cos(theta) * np.sin(theta)
    u_a = rng.uniform(0.0, 0.9, n)
    u_b = np.minimum(1.0, u_a + 10 ** rng.uniform(-3.0, -0.5, n))
    qa = np.stack([3 * u_a + k * u_a**3, m * u_a**3])
    qb = np.stack([3 * u_b + k * u_b**3, m * u_b**3])
    phi = np.arctan2(m * u_a**2, 1 + k * u_a**2) + rng.uniform(-0.02, 0.02, n)
    normal = np.stack([-np.sin(phi), np.cos(phi)])
    start = qa + rng.uniform(-0.01, 0.01, n) * normal
    chord = qb - start
    # The arc from ``start`` with direction φ through ``qb`` (nudged): κ = 2 sin(χ − φ) / L.
    chi = np.arctan2(chord[1], chord[0])
    kappa = 2 * np.sin(chi - phi) / np.hypot(*chord) * rng.uniform(0.9, 1.1, n)
    centre = start + normal / kappa
    sweep = 2 * (chi - phi)
    rot = np.stack([np.cos(sweep), -np.sin(sweep), np.sin(sweep), np.cos(sweep)])
    r = start - centre
    end = centre + np.stack([rot[0] * r[0] + rot[1] * r[1], rot[2] * r[0] + rot[3] * r[1]])
    s_lo = fewest_exact.joint_split(k, m, start[0], start[1], phi)
    s_hi = fewest_exact.joint_split(k, m, end[0], end[1], phi + sweep)
    tol = 10 ** rng.uniform(-7.0, -2.0, n)
    return k, m, start[0], start[1], phi, kappa, end[0], end[1], s_lo, s_hi, tol


def _bits(values: np.ndarray) -> bytes:
    return np.asarray(values, dtype=np.float64).tobytes()


@settings(max_examples=25, deadline=None)
@given(seed=st.integers(0, 2**32 - 1))
def test_arc_deviation_in_floats_is_the_array_result(seed: int) -> None:
    args = _arcs(seed, 40)
    batch = fewest_exact._arc_deviation_arrays(*args)  # 40 arcs: numpy throughout
    assert len(args[0]) > fewest_exact.FLOAT_ELEMENTS
    finite = np.isfinite(batch.value)
    for i in range(len(args[0])):
        single = fewest_exact.arc_deviation(*(a[i : i + 1] for a in args))  # floats
        assert _bits(single.value) == _bits(batch.value[i : i + 1]), i
        if finite[i]:
            assert _bits(single.u) == _bits(batch.u[i : i + 1]), i
    # Both kinds occur: proven arcs and refused ones.
    assert finite.any()


@settings(max_examples=25, deadline=None)
@given(seed=st.integers(0, 2**32 - 1))
def test_joint_split_in_floats_is_the_array_result(seed: int) -> None:
    rng = np.random.default_rng(seed)
    n = 30
    theta = rng.uniform(0.02, 1.55, n)
    k, m = 1.2 * np.cos(theta) ** 2 - 1.0, 1.2 * np.cos(theta) * np.sin(theta)
    u = rng.uniform(0.0, 1.0, n)
    phi = np.arctan2(m * u**2, 1 + k * u**2) + rng.uniform(-0.05, 0.05, n)
    jx = 3 * u + k * u**3 + rng.uniform(-0.01, 0.01, n)
    jy = m * u**3 + rng.uniform(-0.01, 0.01, n)
    jx[0] = -1.0  # before the spiral's start: no split (NaN) in both
    batch = fewest_exact.joint_split(k, m, jx, jy, phi)
    assert n > fewest_exact.FLOAT_ELEMENTS
    for i in range(n):
        single = fewest_exact.joint_split(
            k[i : i + 1], m[i : i + 1], jx[i : i + 1], jy[i : i + 1], phi[i : i + 1]
        )
        assert _bits(single) == _bits(batch[i : i + 1]), i
    assert math.isnan(batch[0])


def test_a_piece_outside_the_spiral_is_refused_alike() -> None:
    # Pieces tile u ∈ [0, 1]; one that starts before 0 or ends after 1 is refused by both.
    base = _arcs(7, 1)
    for index, value in ((8, -0.05), (9, 1.05)):  # s_lo, s_hi
        args = [a[:1].copy() for a in base]
        args[index][0] = value
        assert fewest_exact.arc_deviation(*args).value[0] == math.inf
        assert fewest_exact._arc_deviation_arrays(*args).value[0] == math.inf


def test_a_circle_too_small_to_square_is_refused_not_zero() -> None:
    # κ·‖Q − J‖ beyond 1e154 overflows the square in the distance's denominator, which would
    # read as distance 0; both paths refuse the arc instead. (A real arc is far larger.)
    k, m, u, off, kappa, sweep = 0.1, 0.5, 0.5, 0.1, 1e160, 1e-3
    q = np.array([3 * u + k * u**3, m * u**3])
    phi = math.atan2(3 * m * u * u, 3 + 3 * k * u * u)
    normal = np.array([-math.sin(phi), math.cos(phi)])
    joint = q + off * normal
    centre = joint + normal / kappa
    turn = np.array([[math.cos(sweep), -math.sin(sweep)], [math.sin(sweep), math.cos(sweep)]])
    end = centre + turn @ (joint - centre)
    arr = lambda *v: [np.array([x], dtype=np.float64) for x in v]  # noqa: E731
    s_lo = fewest_exact.joint_split(*arr(k, m, joint[0], joint[1], phi))
    s_hi = fewest_exact.joint_split(*arr(k, m, end[0], end[1], phi + sweep))
    args = [*arr(k, m, joint[0], joint[1], phi, kappa, end[0], end[1]), s_lo, s_hi, *arr(1e-3)]
    assert fewest_exact.arc_deviation(*args).value[0] == math.inf
    assert fewest_exact._arc_deviation_arrays(*args).value[0] == math.inf
    # The circle's radial distance itself (the screen of the proof) is not 0 but refused.
    assert fewest_exact.radial(k, m, joint[0], joint[1], phi, kappa, np.array([0.5]))[0] > 0.0


def test_a_joint_split_the_floats_cannot_follow_is_handed_back() -> None:
    # k = 1e308 overflows the Newton step in floats (a non-finite value): numpy's answer.
    args = [np.array([v]) for v in (1e308, 0.0, 3.0, 0.0, 0.0)]
    with pytest.raises(one.HandBackError):
        one.joint_split(1e308, 0.0, 3.0, 0.0, 1.0, 0.0)
    many = [np.repeat(a, fewest_exact.FLOAT_ELEMENTS + 1) for a in args]
    with np.errstate(over="ignore", invalid="ignore"):  # the array iteration overflows too
        alone, batch = fewest_exact.joint_split(*args), fewest_exact.joint_split(*many)
    assert _bits(alone) == _bits(batch[:1])


def _columns(spline: object) -> list[bytes]:
    c = spline.columns  # type: ignore[attr-defined]
    return [np.asarray(getattr(c, name)).tobytes() for name in c.__slots__]


@pytest.mark.parametrize("seed", [11, 12])
def test_fewest_results_do_not_depend_on_the_float_path(
    seed: int, monkeypatch: pytest.MonkeyPatch
) -> None:
    rng = np.random.default_rng(seed)
    cases = [(Spiral.from_parameters(**PAPER, end_curvature=0.41574), t) for t in (1e-2, 1e-5)]
    for _ in range(12):
        direction = rng.uniform(0.0, 2.0 * math.pi)
        spiral = Spiral.from_parameters(
            start=(float(rng.uniform(-5, 5)), float(rng.uniform(-5, 5))),
            start_tangent=(math.cos(direction), math.sin(direction)),
            turn_angle_deg=float(rng.uniform(1.0, 89.0)),
            end_curvature=float(rng.choice([-1.0, 1.0]) * 10 ** rng.uniform(-2, 1)),
        )
        cases.append((spiral, spiral.chord * 10 ** float(rng.uniform(-6, -1))))
    fast = [approximate(s, t, "fewest-arcs") for s, t in cases]
    monkeypatch.setattr(fewest_exact, "FLOAT_ELEMENTS", 0)
    monkeypatch.setattr(fewest_module, "PROVE_IN_FLOATS", 0)
    monkeypatch.setattr(fewest_module, "SEARCH_ONE_IN_FLOATS", False)
    monkeypatch.setattr(fewest_newton, "FLOAT_ROWS", 0)
    monkeypatch.setattr(fewest_tail, "PROVE_ONE_IN_FLOATS", False)
    plain = [approximate(s, t, "fewest-arcs") for s, t in cases]
    many = approximate_many([s for s, _ in cases], [t for _, t in cases], "fewest-arcs")
    for f, p, b in zip(fast, plain, many, strict=True):
        assert not isinstance(b, Exception)
        assert _columns(f) == _columns(p) == _columns(b)
