"""An independent oracle for curves read from DXF splines: it shares no code with
``arcspline`` (cubics are read through their public fields ``start``, ``control1``,
``control2``, ``end``).

* A NURBS curve evaluated by the Cox–de Boor recursion of its basis functions,
  ``C(u) = Σ N_{i,p}(u)·w_i·P_i / Σ N_{i,p}(u)·w_i`` (Piegl & Tiller, "The NURBS Book", eq.
  2.5 and 4.2) — not by blossoms or knot insertion as the reader does.
* A rational Bézier by its Bernstein formula ``Σ B_i(t)·w_i·P_i / Σ B_i(t)·w_i``.
* A chain of cubics as one curve on ``[0, 1]``.
* The two-sided (Hausdorff) distance of two curves: dense samples on each, each sample's
  nearest sample on the other refined by golden-section search over the neighbouring
  parameters.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence

import numpy as np
from numpy.typing import NDArray

Curve = Callable[[NDArray[np.float64]], NDArray[np.float64]]

_GOLDEN = (math.sqrt(5.0) - 1.0) / 2.0


def nurbs(
    points: Sequence[Sequence[float]],
    knots: Sequence[float],
    degree: int,
    weights: Sequence[float] | None = None,
) -> Curve:
    """The NURBS curve as a function of ``s ∈ [0, 1]`` spanning its domain ``[U[p], U[n]]``."""
    ctrl = np.asarray(points, dtype=float)[:, :2]
    w = np.ones(len(ctrl)) if weights is None else np.asarray(weights, dtype=float)
    u_knots = np.asarray(knots, dtype=float)
    lo, hi = u_knots[degree], u_knots[len(ctrl)]

    def curve(s: NDArray[np.float64]) -> NDArray[np.float64]:
        u = lo + np.asarray(s, dtype=float) * (hi - lo)
        basis = _basis(u_knots, degree, len(ctrl), np.clip(u, lo, hi), hi)
        weighted = basis * w
        return (weighted @ ctrl) / weighted.sum(axis=1)[:, None]

    return curve


def _basis(
    knots: NDArray[np.float64], degree: int, count: int, u: NDArray[np.float64], end: float
) -> NDArray[np.float64]:
    """``N_{i,p}(u)`` for ``i < count``, shape ``(len(u), count)``; the domain's end is taken
    in the last non-empty span."""
    m = len(knots) - 1
    n0 = np.zeros((len(u), m))
    for i in range(m):
        inside = (knots[i] <= u) & (u < knots[i + 1])
        if knots[i] < knots[i + 1] and knots[i + 1] == end:
            inside |= u == end
        n0[:, i] = inside
    nk = n0
    for p in range(1, degree + 1):
        nxt = np.zeros((len(u), m - p))
        for i in range(m - p):
            left = knots[i + p] - knots[i]
            right = knots[i + p + 1] - knots[i + 1]
            if left > 0:
                nxt[:, i] += (u - knots[i]) / left * nk[:, i]
            if right > 0:
                nxt[:, i] += (knots[i + p + 1] - u) / right * nk[:, i + 1]
        nk = nxt
    return nk[:, :count]


def rational_bezier(points: Sequence[Sequence[float]], weights: Sequence[float]) -> Curve:
    """``R(t) = Σ B_i(t)·w_i·P_i / Σ B_i(t)·w_i``."""
    ctrl = np.asarray(points, dtype=float)
    w = np.asarray(weights, dtype=float)
    n = len(ctrl) - 1

    def curve(t: NDArray[np.float64]) -> NDArray[np.float64]:
        t = np.asarray(t, dtype=float)[:, None]
        i = np.arange(n + 1)[None, :]
        combs = np.array([math.comb(n, k) for k in range(n + 1)], dtype=float)[None, :]
        b = combs * t**i * (1.0 - t) ** (n - i) * w[None, :]
        return (b @ ctrl) / b.sum(axis=1)[:, None]

    return curve


def cubic_chain(cubics: Sequence[object]) -> Curve:
    """Cubic Béziers end to end as one curve on ``[0, 1]`` (equal parameter share each)."""
    ctrl = np.array(
        [[c.start, c.control1, c.control2, c.end] for c in cubics],  # type: ignore[attr-defined]
        dtype=float,
    )

    def curve(s: NDArray[np.float64]) -> NDArray[np.float64]:
        x = np.asarray(s, dtype=float) * len(ctrl)
        k = np.clip(np.floor(x).astype(int), 0, len(ctrl) - 1)
        t = (x - k)[:, None]
        c = ctrl[k]
        return (
            (1 - t) ** 3 * c[:, 0]
            + 3 * (1 - t) ** 2 * t * c[:, 1]
            + 3 * (1 - t) * t**2 * c[:, 2]
            + t**3 * c[:, 3]
        )

    return curve


def one_sided(a: Curve, b: Curve, samples: int = 1500, dense: int = 12000) -> float:
    """The largest distance from a point of ``a`` to the curve ``b``."""
    pa = a(np.linspace(0.0, 1.0, samples))
    tb = np.linspace(0.0, 1.0, dense)
    pb = b(tb)
    nearest = np.empty(samples, dtype=int)
    for start in range(0, samples, 256):
        chunk = pa[start : start + 256]
        d2 = ((chunk[:, None, :] - pb[None, :, :]) ** 2).sum(axis=2)
        nearest[start : start + 256] = d2.argmin(axis=1)
    lo = tb[np.maximum(nearest - 1, 0)]
    hi = tb[np.minimum(nearest + 1, dense - 1)]

    def dist(t: NDArray[np.float64]) -> NDArray[np.float64]:
        q = b(t)
        return np.hypot(q[:, 0] - pa[:, 0], q[:, 1] - pa[:, 1])

    x1, x2 = hi - _GOLDEN * (hi - lo), lo + _GOLDEN * (hi - lo)
    f1, f2 = dist(x1), dist(x2)
    for _ in range(60):
        left = f1 < f2
        hi = np.where(left, x2, hi)
        lo = np.where(left, lo, x1)
        x1, x2 = hi - _GOLDEN * (hi - lo), lo + _GOLDEN * (hi - lo)
        f1, f2 = dist(x1), dist(x2)
    best = np.minimum(np.minimum(f1, f2), np.hypot(*(pb[nearest] - pa).T))
    return float(best.max())


def hausdorff(a: Curve, b: Curve, samples: int = 1500, dense: int = 12000) -> float:
    """The two-sided distance of ``a`` and ``b`` (module docstring)."""
    return max(one_sided(a, b, samples, dense), one_sided(b, a, samples, dense))
