"""The planar cubic Bézier curve by its four control points (``(4, 2)`` float64 arrays):
evaluation, and the exact largest distance from a piece of it to a line or to a circle.

For the distances a piece ``u0 ≤ u ≤ u1`` is written in the power basis about the first
control point, ``Q(u) − B0 = c1·u + c2·u² + c3·u³`` (``c1 = 3(B1 − B0)``,
``c2 = 3(B2 − 2B1 + B0)``, ``c3 = B3 − 3B2 + 3B1 − B0``), and the largest distance is taken
over the ends and the interior critical points of the distance, which are polynomial roots
(docs/method.md §9 "Checking a program"):

* to the line through ``start`` with unit normal ``n``: ``d(u) = n·(Q(u) − start)``, a cubic;
  its critical points are the roots of the quadratic ``n·Q'(u)``;
* to a circle about ``centre``: ``ρ(u) = ‖Q(u) − centre‖`` is extreme where the quintic
  ``g(u) = (Q(u) − centre)·Q'(u)`` vanishes; its roots are the eigenvalues of the companion
  matrix.

The distance functions measure many pieces of one curve at once (one row each).
"""

from __future__ import annotations

import itertools
from typing import Any, NamedTuple

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


class _Monomial(NamedTuple):
    """``Q(u) − origin = c1·u + c2·u² + c3·u³``."""

    origin: FloatArray
    c1: FloatArray
    c2: FloatArray
    c3: FloatArray


def _monomial(control_points: FloatArray) -> _Monomial:
    p = np.asarray(control_points, dtype=np.float64)
    b = p - p[0]
    return _Monomial(
        origin=p[0],
        c1=3.0 * b[1],
        c2=3.0 * (b[2] - 2.0 * b[1]),
        c3=b[3] - 3.0 * b[2] + 3.0 * b[1],
    )


def _candidates(roots: npt.NDArray[Any], u0: FloatArray, u1: FloatArray) -> FloatArray:
    """Real ``roots`` (rows) inside ``[u0, u1]``, plus both ends; NaN marks no candidate.

    A root is taken as real when its imaginary part is tiny; a spurious candidate is harmless
    (it is a point of the piece, so it cannot raise a maximum above the true one).
    """
    real = np.real(roots)
    ok = (np.abs(np.imag(roots)) <= 1e-7) & (real > u0[:, None]) & (real < u1[:, None])
    inner = np.where(ok, real, np.nan)
    return np.concatenate([u0[:, None], u1[:, None], inner], axis=1)


def line_deviations(
    control_points: FloatArray,
    u0: FloatArray,
    u1: FloatArray,
    start: FloatArray,
    end: FloatArray,
) -> FloatArray:
    """Max over ``u ∈ [u0, u1]`` of the distance from ``Q(u)`` to the line ``start→end``.

    With ``n`` the chord's unit normal, ``n·Q'(u) = n·c1 + 2(n·c2)u + 3(n·c3)u²``: its real
    roots and the ends are the only candidates. Rows where ``start == end`` measure the
    distance to the point instead (:func:`circle_deviations` with radius 0). When ``start``
    and ``end`` are the piece's own end points and its tangent turns by less than 90° this is
    also the distance to the segment: every point of the piece projects inside the chord.
    """
    mono = _monomial(control_points)
    chord = end - start
    length = np.hypot(chord[:, 0], chord[:, 1])
    is_point = length == 0.0
    safe = np.where(is_point, 1.0, length)
    normal = np.stack([-chord[:, 1], chord[:, 0]], axis=1) / safe[:, None]
    qa = 3.0 * normal @ mono.c3
    qb = 2.0 * normal @ mono.c2
    qc = normal @ mono.c1
    disc = qb * qb - 4.0 * qa * qc
    sq = np.sqrt(np.where(disc >= 0.0, disc, np.nan))
    # The stable pair of quadratic roots; a vanishing leading coefficient leaves one root.
    big = -0.5 * (qb + np.copysign(sq, qb))
    with np.errstate(divide="ignore", invalid="ignore"):
        r1 = np.where(qa != 0.0, big / qa, np.where(qb != 0.0, -qc / qb, np.nan))
        r2 = np.where(big != 0.0, qc / big, np.nan)
    u = _candidates(np.stack([r1, r2], axis=1).astype(np.complex128), u0, u1)
    q = point(control_points, np.nan_to_num(u, nan=0.0))
    d = np.abs(np.einsum("nkj,nj->nk", q - start[:, None, :], normal))
    dev = np.nanmax(np.where(np.isnan(u), np.nan, d), axis=1)
    if np.any(is_point):
        zero = np.zeros(int(is_point.sum()))
        dev[is_point] = circle_deviations(
            control_points, u0[is_point], u1[is_point], start[is_point], zero, zero
        )
    return np.asarray(dev, dtype=np.float64)


def circle_deviations(
    control_points: FloatArray,
    u0: FloatArray,
    u1: FloatArray,
    centre: FloatArray,
    r_start: FloatArray,
    r_end: FloatArray,
) -> FloatArray:
    """Max over ``u ∈ [u0, u1]`` of the distance from ``Q(u)`` to a circle about ``centre``.

    Two radii describe an arc whose start and end radii differ (a rounded G-code arc: a
    controller cuts a spiral between the two radii (LinuxCNC) or one of them (Grbl)); the
    distance is therefore taken to the farther of the two circles,
    ``max(|ρ − r_start|, |ρ − r_end|)`` with ``ρ(u) = ‖Q(u) − centre‖``; equal radii give the
    distance to one circle, radius 0 the distance to the point ``centre``. Its extrema lie at
    the ends or at a root of the quintic ``g(u) = (Q(u) − centre)·Q'(u)``.
    """
    mono = _monomial(control_points)
    a0 = mono.origin - centre
    c1, c2, c3 = mono.c1, mono.c2, mono.c3
    coeffs = np.stack(
        [
            a0 @ c1,
            2.0 * a0 @ c2 + c1 @ c1,
            3.0 * a0 @ c3 + np.full(len(a0), 3.0 * c1 @ c2),
            np.full(len(a0), 4.0 * c1 @ c3 + 2.0 * c2 @ c2),
            np.full(len(a0), 5.0 * c2 @ c3),
        ],
        axis=1,
    ) / (3.0 * c3 @ c3)
    companion = np.zeros((len(a0), 5, 5))
    companion[:, np.arange(1, 5), np.arange(4)] = 1.0
    companion[:, :, 4] = -coeffs
    roots = np.linalg.eigvals(companion) if len(a0) else np.zeros((0, 5), np.complex128)
    u = _candidates(roots, u0, u1)
    q = point(control_points, np.nan_to_num(u, nan=0.0))
    rho = np.hypot(q[..., 0] - centre[:, None, 0], q[..., 1] - centre[:, None, 1])
    far = np.maximum(np.abs(rho - r_start[:, None]), np.abs(rho - r_end[:, None]))
    return np.asarray(np.nanmax(np.where(np.isnan(u), np.nan, far), axis=1), dtype=np.float64)
