"""One triarc built in floats gives the array version's numbers.

``fewest_tail.triarc_one`` builds one spiral's winning triarc for its proof; each number must
be, bit for bit, what ``_triarcs`` computes for it among other candidates.
"""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from arcspline.geometry import fewest_tail
from tests.geometry.test_fewest_newton import _bits


@settings(max_examples=25, deadline=None)
@given(seed=st.integers(0, 2**32 - 1))
def test_one_triarc_is_the_array_result(seed: int) -> None:
    rng = np.random.default_rng(seed)
    n = 30
    theta = rng.uniform(0.02, 1.55, n)
    k, m = 1.2 * np.cos(theta) ** 2 - 1.0, 1.2 * np.cos(theta) * np.sin(theta)
    ua = rng.uniform(0.0, 0.95, n)
    v = ua + (1.0 - ua) * rng.uniform(0.05, 0.95, n)
    delta = 10 ** rng.uniform(-7.0, -2.0, n) * rng.choice([-1.0, 0.0, 1.0], n)
    lam = rng.uniform(0.0, 1.0, n)
    lam[:2] = (0.0, 1.0)  # the ends of the family
    v[2] = ua[2]  # a first joint at the start
    with np.errstate(all="ignore"):
        many = fewest_tail._triarcs(k, m, ua, v, delta, lam)
        for i in range(n):
            one = fewest_tail.triarc_one(
                float(k[i]), float(m[i]), float(ua[i]), float(v[i]), float(delta[i]), float(lam[i])
            )
            for name in ("x", "y", "phi", "kappa", "s"):
                assert _bits(getattr(one, name)) == _bits(getattr(many, name)[i]), (i, name)
            assert one.ok == many.ok[i]
            assert _bits(one.cos_phi) == _bits(np.cos(many.phi[i, :3]))
            assert _bits(one.sin_phi) == _bits(np.sin(many.phi[i, :3]))


def test_many_of_these_triarcs_are_valid() -> None:
    # The comparison above would mean little if every candidate were degenerate.
    rng = np.random.default_rng(1)
    n = 200
    theta = rng.uniform(0.1, 1.4, n)
    k, m = 1.2 * np.cos(theta) ** 2 - 1.0, 1.2 * np.cos(theta) * np.sin(theta)
    ua = rng.uniform(0.0, 0.9, n)
    v = ua + (1.0 - ua) * rng.uniform(0.2, 0.6, n)
    with np.errstate(all="ignore"):
        t = fewest_tail._triarcs(k, m, ua, v, np.zeros(n), np.full(n, 0.5))
    assert t.ok.mean() > 0.5
