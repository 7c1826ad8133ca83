"""A vectorised, bracketed Newton iteration for one simple root per interval."""

from __future__ import annotations

from collections.abc import Callable, Sequence

import numpy as np
import numpy.typing as npt

from .types import FloatArray

#: Newton converges quadratically from the start points used here; the cap only matters for
#: pathological input, where the bisection fallback still halves the bracket every step.
MAX_ITERATIONS = 100

#: Plain Newton steps tried before the safeguarded iteration: from the callers' start points
#: nearly every element converges in three to six.
FAST_ITERATIONS = 8

#: Steps every element takes before any convergence test: from the callers' start points
#: nearly every element is within the resolution after three, so the fourth confirms it.
FIXED_ITERATIONS = 4

#: Arrays up to this size continue on all elements rather than on a gathered subset.
SMALL = 256

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
    """The root of ``fn`` in each ``[lo, hi]``, where ``fn(lo)`` and ``fn(hi)`` differ in sign.

    (Either orientation is accepted; the callers' ``fn(lo) ≤ 0 ≤ fn(hi)`` is one.) ``fn``
    returns value and slope. First, plain Newton steps from ``start`` — each costs one
    evaluation and a handful of array operations. An element stops at its first step below
    ``RESOLUTION_ULPS`` ulps of its bracket's magnitude and holds that value, so its result
    depends on its own iterates only — not on the other elements of the batch. Elements not
    done after ``FAST_ITERATIONS`` steps, or that end outside their bracket, are solved again
    by the safeguarded iteration from ``start``: Newton steps that would leave the (shrinking)
    bracket are replaced by bisection, so every element converges.
    """
    resolution = RESOLUTION_ULPS * _EPS * np.maximum(np.abs(lo), np.abs(hi))
    # One error-state switch per call, not per step: a zero slope only makes a step non-finite,
    # which the convergence and bracket tests reject.
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        x = _fast(fn, lo, hi, start, resolution)
        good = np.isfinite(x)
        if np.count_nonzero(good) == good.size:
            return x
        redo = np.flatnonzero(~good)
        x[redo] = _safeguarded(
            _subset(fn, redo, x), lo[redo], hi[redo], start[redo], resolution[redo]
        )
        return x


def polynomial_root(
    coefficients: Sequence[FloatArray],
    lo: FloatArray,
    hi: FloatArray,
    start: FloatArray,
    fixed_iterations: int = FIXED_ITERATIONS,
) -> FloatArray:
    """:func:`bracketed_newton` for the polynomials ``Σ coefficients[j]·x^(d−j)`` (highest
    degree first, one polynomial per element), evaluated by Horner's rule.

    Same iteration and result as ``bracketed_newton``, with ``fixed_iterations`` steps
    before the first convergence test (callers whose start points are better need fewer);
    knowing the polynomial lets the safeguarded fallback evaluate only the elements it
    re-solves.
    """
    resolution = RESOLUTION_ULPS * _EPS * np.maximum(np.abs(lo), np.abs(hi))
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        x = _fast(
            horner(coefficients),
            lo,
            hi,
            start,
            resolution,
            lambda rows: horner([c[rows] for c in coefficients]),
            fixed_iterations,
        )
        good = np.isfinite(x)
        if np.count_nonzero(good) == good.size:
            return x
        redo = np.flatnonzero(~good)
        x[redo] = _safeguarded(
            horner([c[redo] for c in coefficients]),
            lo[redo],
            hi[redo],
            start[redo],
            resolution[redo],
        )
        return x


def horner(coefficients: Sequence[FloatArray]) -> ValueAndSlope:
    """Value and slope of ``Σ coefficients[j]·x^(d−j)`` (``d ≥ 1``, highest degree first)."""
    degree = len(coefficients) - 1
    slope_coefficients = [
        c if j == degree - 1 else (degree - j) * c for j, c in enumerate(coefficients[:-1])
    ]

    def value_and_slope(x: FloatArray) -> tuple[FloatArray, FloatArray]:
        value = coefficients[0] * x + coefficients[1]
        for c in coefficients[2:]:
            value = value * x + c
        slope = slope_coefficients[0]
        for c in slope_coefficients[1:]:
            slope = slope * x + c
        return value, slope

    return value_and_slope


def _fast(
    fn: ValueAndSlope,
    lo: FloatArray,
    hi: FloatArray,
    start: FloatArray,
    resolution: FloatArray,
    restrict: Callable[[npt.NDArray[np.intp]], ValueAndSlope] | None = None,
    fixed_iterations: int = FIXED_ITERATIONS,
) -> FloatArray:
    """Plain Newton steps; elements not done or outside their bracket come back as NaN.

    Every element first takes ``fixed_iterations`` steps with no per-step bookkeeping: fixed
    work per element, so its result does not depend on the batch. An element whose last step
    was still above the resolution goes on, alone with the others like it, until its first
    step below the resolution, as long as ``FAST_ITERATIONS`` steps in all.
    """
    x = np.minimum(np.maximum(start, lo), hi)  # np.clip costs several times more
    for _ in range(fixed_iterations):
        f, df = fn(x)
        step = f / df
        x = x - step
    done = np.abs(step) <= resolution
    if np.count_nonzero(done) != done.size:
        if x.size <= SMALL:
            # Gathering a subset costs more than stepping every element of a small array;
            # the finished elements hold, so the result is the same either way.
            x, done = _continue(fn, x, resolution, done, fixed_iterations)
        else:
            rest = np.flatnonzero(~done)
            part = restrict(rest) if restrict else _subset(fn, rest, x)
            x[rest], done[rest] = _continue(
                part, x[rest], resolution[rest], done[rest], fixed_iterations
            )
    good = done & (x >= lo) & (x <= hi)
    if np.count_nonzero(good) == good.size:
        return x
    return np.where(good, x, np.nan)


def _continue(
    fn: ValueAndSlope,
    x: FloatArray,
    resolution: FloatArray,
    done: npt.NDArray[np.bool_],
    fixed_iterations: int,
) -> tuple[FloatArray, npt.NDArray[np.bool_]]:
    """Newton steps after the fixed ones for the elements not ``done``: each holds its value
    from its first step below the resolution, up to ``FAST_ITERATIONS`` steps in all."""
    for _ in range(FAST_ITERATIONS - fixed_iterations):
        f, df = fn(x)
        step = f / df
        x = np.where(done, x, x - step)
        done = done | (np.abs(step) <= resolution)
        if np.count_nonzero(done) == done.size:
            break
    return x, done


def _subset(fn: ValueAndSlope, which: npt.NDArray[np.intp], x: FloatArray) -> ValueAndSlope:
    """``fn`` restricted to the elements ``which`` (the others are held at ``x``)."""
    full = x.copy()

    def restricted(xs: FloatArray) -> tuple[FloatArray, FloatArray]:
        full[which] = xs
        f, df = fn(full)
        return f[which], df[which]

    return restricted


def _safeguarded(
    fn: ValueAndSlope, lo: FloatArray, hi: FloatArray, start: FloatArray, resolution: FloatArray
) -> FloatArray:
    """Newton inside a shrinking bracket, bisecting whenever a step would leave it."""
    x = np.minimum(np.maximum(start, lo), hi)
    # Orient each element so that its function rises through the bracket.
    sign = np.where(fn(lo)[0] <= 0.0, 1.0, -1.0)
    lo, hi = lo.copy(), hi.copy()
    done = np.zeros(x.shape, dtype=bool)
    for _ in range(MAX_ITERATIONS):
        value, slope = fn(x)
        f, df = sign * value, sign * slope
        below = f < 0.0
        lo = np.where(below, x, lo)
        hi = np.where(below, hi, x)
        step = f / df
        converged = np.abs(step) <= resolution
        newton = x - step
        inside = (newton > lo) & (newton < hi)
        moved = np.where(converged, newton, np.where(inside, newton, 0.5 * (lo + hi)))
        x = np.where(done, x, moved)  # as in the fast loop, a finished element holds
        done |= converged
        if done.all():
            break
    return x


def one_root(
    coefficients: tuple[float, ...], lo: float, hi: float, start: float, fixed: int
) -> float:
    """:func:`polynomial_root` on one-element arrays: elementwise, so the batch's result."""

    def one(value: float) -> FloatArray:
        return np.array([value])

    root = polynomial_root([one(c) for c in coefficients], one(lo), one(hi), one(start), fixed)
    return float(root[0])
