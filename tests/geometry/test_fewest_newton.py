"""One row's Newton step in floats gives the numpy lockstep's numbers.

``fewest_newton.newton_one`` is an accelerator for a single spiral: it must equal, bit for
bit, what ``newton_many`` computes for that row inside a batch, or a spiral's arcs would
depend on its neighbours.
"""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from arcspline.geometry import fewest, fewest_newton
from arcspline.geometry.fewest_biarc import SabinBiarcs


def _rows(seed: int, n: int) -> tuple[np.ndarray, ...]:
    """Steps as the walk makes them: a spiral, a start, a tolerance, the previous span and
    join parameter, and a Jacobian near the default one."""
    rng = np.random.default_rng(seed)
    theta = rng.uniform(0.02, 1.55, n)
    k, m = 1.2 * np.cos(theta) ** 2 - 1.0, 1.2 * np.cos(theta) * np.sin(theta)
    u0 = rng.uniform(0.0, 0.9, n)
    tol = 10 ** rng.uniform(-8.0, -2.0, n)
    hint = (1.0 - u0) * 10 ** rng.uniform(-2.5, -0.3, n)
    lam = rng.uniform(0.05, 0.95, n)
    jac = np.array(fewest_newton.NEWTON_JACOBIAN) * (1.0 + 0.2 * rng.standard_normal((n, 2, 2)))
    return k, m, u0, tol, hint, lam, jac


def _bits(values: object) -> bytes:
    return np.asarray(values, dtype=np.float64).tobytes()


@settings(max_examples=20, deadline=None)
@given(seed=st.integers(0, 2**32 - 1))
def test_newton_one_is_the_lockstep_result(seed: int) -> None:
    k, m, u0, tol, hint, lam, jac = _rows(seed, 12)
    found, chosen, devs, jacobians = fewest_newton.newton_many(k, m, u0, tol, hint, lam, jac)
    for i in range(k.size):
        one = fewest_newton.newton_one(
            float(k[i]), float(m[i]), float(u0[i]), float(tol[i]), float(hint[i]),
            float(lam[i]), jac[i].tolist(),
        )  # fmt: skip
        assert one.found == found[i]
        assert _bits(one.jacobian) == _bits(jacobians[i])
        if one.found:  # the biarc and deviations of a row without a result mean nothing
            for name, value in zip(SabinBiarcs.__slots__, one.biarc, strict=False):
                assert _bits(value) == _bits(getattr(chosen, name)[i]), name
            assert _bits(one.devs) == _bits([d[i] for d in devs])


def _walk_steps() -> list[tuple[np.ndarray, ...]]:
    """The Newton steps of real walks: a batch of random spirals in lockstep."""
    rng = np.random.default_rng(2026)
    theta = rng.uniform(0.05, 1.5, 40)
    k, m = 1.2 * np.cos(theta) ** 2 - 1.0, 1.2 * np.cos(theta) * np.sin(theta)
    tol = 10 ** rng.uniform(-6.0, -3.0, 40)
    steps: list[tuple[np.ndarray, ...]] = []
    real = fewest.newton_step

    def spy(*args: np.ndarray) -> tuple[np.ndarray, SabinBiarcs, fewest_newton.Devs, np.ndarray]:
        steps.append(tuple(np.array(a) for a in args))
        return real(*args)

    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(fewest, "newton_step", spy)
        fewest.fewest_chains(k, m, tol, np.full(40, 1000))
    return steps


def test_newton_one_is_the_lockstep_result_along_real_walks() -> None:
    steps = _walk_steps()
    found_rows = 0
    for args in steps:
        found, chosen, devs, jacobians = fewest_newton.newton_many(*args)
        found_rows += int(found.sum())
        for i in range(found.size):
            one = fewest_newton.newton_one(*(float(a[i]) for a in args[:6]), args[6][i].tolist())
            assert one.found == found[i]
            assert _bits(one.jacobian) == _bits(jacobians[i])
            if one.found:
                for name, value in zip(SabinBiarcs.__slots__, one.biarc, strict=False):
                    assert _bits(value) == _bits(getattr(chosen, name)[i]), name
                assert _bits(one.devs) == _bits([d[i] for d in devs])
    # Real walks take the Newton step often, and it mostly succeeds.
    assert found_rows >= 100


def test_newton_step_takes_floats_for_few_rows_with_the_same_result() -> None:
    args = _rows(5, fewest_newton.FLOAT_ROWS)
    few = fewest_newton.newton_step(*args)
    many = fewest_newton.newton_many(*args)
    assert np.array_equal(few[0], many[0])
    assert _bits(few[3]) == _bits(many[3])
    for name in SabinBiarcs.__slots__:
        a, b = getattr(few[1], name)[few[0]], getattr(many[1], name)[many[0]]
        assert _bits(a) == _bits(b), name
