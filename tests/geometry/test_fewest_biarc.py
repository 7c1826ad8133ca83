"""One Sabin's-circle biarc and its proof in floats give the array versions' numbers.

``fewest_biarc.sabin_biarc_one`` and ``verify_one`` serve the steps that look at one
candidate at a time; each number must be, bit for bit, what ``sabin_biarcs`` and ``verify``
compute for that candidate among others.
"""

from __future__ import annotations

import math

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from arcspline.geometry import fewest_biarc
from arcspline.geometry.fewest_biarc import SabinBiarcs
from tests.geometry.test_fewest_newton import _bits, _rows


@settings(max_examples=20, deadline=None)
@given(seed=st.integers(0, 2**32 - 1))
def test_one_biarc_and_its_proof_are_the_array_result(seed: int) -> None:
    rng = np.random.default_rng(seed)
    k, m, u0, tol, hint, lam, _ = _rows(seed, 30)
    u1 = np.minimum(u0 + hint * rng.uniform(0.5, 3.0, k.size), 1.0)
    lam[:3] = (0.0, 1.0, 0.5)  # the ends of the family, where a biarc degenerates
    u1[3] = u0[3]  # an empty piece
    with np.errstate(all="ignore"):
        many = fewest_biarc.sabin_biarcs(k, m, u0, u1, lam)
        d0, w0, d1, w1 = fewest_biarc.verify(k, m, u0, many, tol)
        for i in range(k.size):
            b = fewest_biarc.sabin_biarc_one(
                float(k[i]), float(m[i]), float(u0[i]), float(u1[i]), float(lam[i])
            )
            for name, value in zip(SabinBiarcs.__slots__, b, strict=False):
                assert _bits(value) == _bits(getattr(many, name)[i]), (i, name)
            dev = fewest_biarc.verify_one(float(k[i]), float(m[i]), float(u0[i]), b, float(tol[i]))
            assert _bits((dev[0], dev[2])) == _bits((d0[i], d1[i]))
            if b.ok and math.isfinite(dev[0]) and math.isfinite(dev[2]):
                assert _bits((dev[1], dev[3])) == _bits((w0[i], w1[i]))
