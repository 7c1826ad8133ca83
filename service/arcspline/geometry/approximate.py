"""The core's entry points: one curve, or many at once, under explicit limits."""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from .curves import Curve
from .errors import GeometryError
from .fit import STRATEGIES, FitMany, StrategyName
from .fit.batch import STATUS, frame_table
from .limits import DEFAULT_LIMITS, Limits, min_tolerance
from .spline import ArcSpline, FloatArray

_OK = STATUS["ok"]
_BAD_TOLERANCE = STATUS["bad_tolerance"]


def approximate(
    curve: Curve,
    tolerance: float,
    strategy: StrategyName = "subdivide",
    limits: Limits = DEFAULT_LIMITS,
) -> ArcSpline:
    """The arc spline of ``curve`` within ``tolerance``, by ``strategy``.

    Raises :class:`GeometryError` for a tolerance that is not a finite number > 0 or is below
    :func:`~arcspline.geometry.limits.min_tolerance`, an unknown strategy, a result that would
    exceed ``limits.max_segments``, or one that double precision cannot hold.
    """
    (result,) = approximate_many([curve], [tolerance], strategy, limits)
    if isinstance(result, GeometryError):
        raise result
    return result


def approximate_many(
    curves: Sequence[Curve],
    tolerances: Sequence[float],
    strategy: StrategyName = "subdivide",
    limits: Limits = DEFAULT_LIMITS,
) -> list[ArcSpline | GeometryError]:
    """Approximate many curves in one compiled loop, in the order given. A curve whose
    tolerance or limits fail gets its :class:`GeometryError` in its place; the others are
    unaffected (each result is the one the curve gets alone, bit for bit)."""
    if len(curves) != len(tolerances):
        raise ValueError("curves and tolerances differ in length")
    fit = fit_of(strategy)
    tol = _tolerances(tolerances)
    frames = frame_table([c.frame for c in curves])
    blocks, where, stats, status, aux = fit(
        frames, tol, limits.max_segments, limits.min_relative_tolerance
    )
    of_batch = ArcSpline._of_batch
    results: list[ArcSpline | GeometryError] = [
        of_batch(blocks[block], begin, end, stats, i, t, strategy)
        if code == _OK
        else _error(code, curves[i], tolerances[i], limits, aux[i])
        for i, (code, (block, begin, end), t) in enumerate(
            zip(status.tolist(), where.tolist(), tol.tolist(), strict=True)
        )
    ]
    return results


def fit_of(name: str) -> FitMany:
    """The fit of the strategy named ``name``; :class:`GeometryError` if there is none."""
    try:
        return STRATEGIES[name]
    except (KeyError, TypeError):
        raise GeometryError(
            "strategy", f"unknown strategy {name!r}; choose one of {', '.join(STRATEGIES)}"
        ) from None


def _tolerances(tolerances: Sequence[float]) -> FloatArray:
    """The tolerances as floats; anything that is not a Python number (``int`` or ``float``,
    numpy's float64 included) becomes NaN, refused by the kernels as ``bad_tolerance`` and
    worded from the value given."""
    if set(map(type, tolerances)) <= {float}:  # the common case: one conversion
        return np.array(tolerances, dtype=np.float64)
    return np.array(
        [float(t) if isinstance(t, int | float) else math.nan for t in tolerances],
        dtype=np.float64,
    )


def _error(
    code: int, curve: Curve, tolerance: object, limits: Limits, aux: FloatArray
) -> GeometryError:
    """The error of a curve the kernels refused, with its message."""
    if code == _BAD_TOLERANCE or not isinstance(tolerance, int | float):
        return GeometryError("tolerance", f"must be a finite number > 0, got {tolerance!r}")
    why = _STATUS_NAME[code]
    if why == "tolerance_floor":
        floor = min_tolerance(curve, limits)
        return GeometryError(
            "tolerance",
            f"{tolerance:.6g} is below the smallest reachable tolerance {floor:.6g} for this "
            f"spiral (chord {curve.chord:.6g}, coordinates up to {curve.coordinate_scale:.6g}); "
            "double precision cannot deliver less",
            kind="tolerance_floor",
            limit=floor,
        )
    if why == "segment_limit":
        return GeometryError(
            "tolerance",
            f"{tolerance:.6g} needs more than the limit of {limits.max_segments} segments for "
            "this spiral; raise the tolerance",
            kind="segment_limit",
            limit=float(limits.max_segments),
        )
    if why == "stuck":
        return GeometryError(
            "tolerance",
            f"{tolerance:.6g} cannot be reached in double precision for this spiral "
            "(a piece became too short to split); raise the tolerance",
            kind="precision",
            limit=min_tolerance(curve, limits),
        )
    if why == "unplaceable":
        worst, max_radius = float(aux[0]), float(aux[1])
        return GeometryError(
            "tolerance",
            f"{tolerance:.6g} cannot be held in double precision for this spiral: its arcs "
            f"have radii up to {max_radius:.6g}, whose centres and radii round by up to "
            f"{worst:.3g}; raise the tolerance",
            kind="precision",
            limit=4.0 * worst,
        )
    return GeometryError(
        "tolerance", "the arc spline overflowed double precision for this spiral", kind="precision"
    )


_STATUS_NAME = {code: name for name, code in STATUS.items()}
