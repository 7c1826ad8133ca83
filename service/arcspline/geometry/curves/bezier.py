"""The planar cubic Bézier curve by its four control points (``(4, 2)`` float64 arrays):
evaluation by de Casteljau's algorithm, and its first two derivatives (the spiral's world
coordinates for the preview and the tests; the kernels measure pieces, ``measure.pyx``).
"""

from __future__ import annotations

import itertools

import numpy as np
import numpy.typing as npt

FloatArray = npt.NDArray[np.float64]


def point(control_points: FloatArray, u: float | FloatArray) -> FloatArray:
    """``Q(u)`` by de Casteljau's algorithm; shape ``(..., 2)`` for ``u`` of shape ``(...)``."""
    return _de_casteljau(control_points, np.asarray(u, dtype=np.float64))


def derivative(control_points: FloatArray, u: float | FloatArray) -> FloatArray:
    """``Q'(u)``."""
    return _de_casteljau(3.0 * np.diff(control_points, axis=0), np.asarray(u, np.float64))


def second_derivative(control_points: FloatArray, u: float | FloatArray) -> FloatArray:
    """``Q''(u)``."""
    second = 6.0 * np.diff(control_points, n=2, axis=0)
    return _de_casteljau(second, np.asarray(u, dtype=np.float64))


def _de_casteljau(points: FloatArray, u: FloatArray) -> FloatArray:
    w = u[..., None]
    layer = [np.broadcast_to(p, (*u.shape, 2)) for p in points]
    while len(layer) > 1:
        layer = [(1.0 - w) * p + w * q for p, q in itertools.pairwise(layer)]
    return np.array(layer[0], dtype=np.float64)
