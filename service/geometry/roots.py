"""A vectorised, bracketed Newton iteration for one simple root per interval."""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from .types import FloatArray

#: Newton converges quadratically from the start points used here; the cap only matters for
#: pathological input, where the bisection fallback still halves the bracket every step.
MAX_ITERATIONS = 100

#: Near a root the polynomials here evaluate to rounding noise (a few ulps of their O(1)
#: terms) over slopes that can be small, so Newton steps stall at tens of ulps, not one.
#: The roots are used where an error of this size is immaterial: at a maximum of the
#: deviation (which is flat there) and as split points.
RESOLUTION_ULPS = 256.0

_EPS = float(np.finfo(np.float64).eps)

ValueAndSlope = Callable[[FloatArray], tuple[FloatArray, FloatArray]]


def bracketed_newton(
    fn: ValueAndSlope, lo: FloatArray, hi: FloatArray, start: FloatArray
) -> FloatArray:
    """The root of ``fn`` in each ``[lo, hi]``, where ``fn(lo) ≤ 0 ≤ fn(hi)``.

    Newton steps that would leave the (shrinking) bracket are replaced by bisection, so every
    element converges; an element is done once its Newton step is below ``RESOLUTION_ULPS``
    ulps of the bracket's magnitude, and the iteration ends when all are. ``fn`` returns value
    and slope.
    """
    x = np.clip(start, lo, hi)
    lo, hi = lo.copy(), hi.copy()
    resolution = RESOLUTION_ULPS * _EPS * np.maximum(np.abs(lo), np.abs(hi))
    for _ in range(MAX_ITERATIONS):
        f, df = fn(x)
        below = f < 0.0
        lo = np.where(below, x, lo)
        hi = np.where(below, hi, x)
        with np.errstate(divide="ignore", invalid="ignore"):
            step = f / df
        converged = np.abs(step) <= resolution
        newton = x - step
        inside = (newton > lo) & (newton < hi)
        x = np.where(converged, newton, np.where(inside, newton, 0.5 * (lo + hi)))
        if converged.all():
            break
    return x
