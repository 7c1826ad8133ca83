"""A vectorised, bracketed Newton iteration for one simple root per interval."""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from .types import FloatArray

#: Newton converges quadratically from the start points used here; the cap only matters for
#: pathological input, where the bisection fallback still halves the bracket every step.
MAX_ITERATIONS = 100

_EPS = float(np.finfo(np.float64).eps)

ValueAndSlope = Callable[[FloatArray], tuple[FloatArray, FloatArray]]


def bracketed_newton(
    fn: ValueAndSlope, lo: FloatArray, hi: FloatArray, start: FloatArray
) -> FloatArray:
    """The root of ``fn`` in each ``[lo, hi]``, where ``fn(lo) ≤ 0 ≤ fn(hi)``.

    Newton steps that leave the (shrinking) bracket are replaced by bisection, so every
    element converges; iteration stops when all steps are below a few ulps of the bracket.
    ``fn`` returns value and slope for an array of abscissae.
    """
    x = np.clip(start, lo, hi)
    lo, hi = lo.copy(), hi.copy()
    scale = np.maximum(np.abs(lo), np.abs(hi))
    for _ in range(MAX_ITERATIONS):
        f, df = fn(x)
        below = f < 0.0
        lo = np.where(below, x, lo)
        hi = np.where(below, hi, x)
        with np.errstate(divide="ignore", invalid="ignore"):
            newton = x - f / df
        inside = (newton > lo) & (newton < hi)
        nxt = np.where(inside, newton, 0.5 * (lo + hi))
        nxt = np.where(f == 0.0, x, nxt)
        done = np.abs(nxt - x) <= 4.0 * _EPS * scale
        x = nxt
        if done.all():
            break
    return x
