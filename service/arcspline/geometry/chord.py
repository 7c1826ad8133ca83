"""Exact largest distance from a piece of a spiral to a chord (a line) or to a circle.

A piece ``u0 ≤ u ≤ u1`` of the cubic Bézier ``Q`` is written in the power basis about its
first control point, ``Q(u) − B0 = c1·u + c2·u² + c3·u³`` (``c1 = 3(B1 − B0)``,
``c2 = 3(B2 − 2B1 + B0)``, ``c3 = B3 − 3B2 + 3B1 − B0``). The largest distance is then taken
over the ends and the interior critical points of the distance, which are polynomial roots:

* to the line through ``start`` with unit normal ``n``: ``d(u) = n·(Q(u) − start)``, a cubic;
  its critical points are the roots of the quadratic ``n·Q'(u) = n·c1 + 2(n·c2)u + 3(n·c3)u²``;
* to a circle about ``centre``: ``ρ(u) = ‖Q(u) − centre‖`` is extreme where the quintic
  ``g(u) = (Q(u) − centre)·Q'(u)`` vanishes (Walton & Meek's ``g_i``, §4 of the spec, here
  without a known root); its roots are the eigenvalues of the companion matrix.

Every function works on many pieces of one spiral at once (one row each); parameters ``u`` are
the spiral's own, points are ``(n, 2)`` float64 arrays.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any, NamedTuple

import numpy as np
import numpy.typing as npt

from .spiral import Spiral
from .types import FloatArray

__all__ = ["chord_deviation", "chord_deviations", "circle_deviations"]


class _Monomial(NamedTuple):
    """``Q(u) − origin = c1·u + c2·u² + c3·u³`` (power basis of the Bézier, local frame)."""

    origin: FloatArray
    c1: FloatArray
    c2: FloatArray
    c3: FloatArray


def _monomial(spiral: Spiral) -> _Monomial:
    p = np.asarray(spiral.control_points, dtype=np.float64)
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


def _eval(spiral: Spiral, u: FloatArray) -> FloatArray:
    return spiral.eval(np.nan_to_num(u, nan=0.0))


def chord_deviations(
    spiral: Spiral, u0: FloatArray, u1: FloatArray, start: FloatArray, end: FloatArray
) -> FloatArray:
    """Max over ``u ∈ [u0, u1]`` of the distance from ``Q(u)`` to the line ``start→end``.

    With ``n`` the chord's unit normal, ``d(u) = n·(Q(u) − start)`` is a cubic whose
    derivative ``n·Q'(u) = n·c1 + 2(n·c2)u + 3(n·c3)u²`` is a quadratic: its real roots and
    the ends are the only candidates. Rows where ``start == end`` measure the distance to the
    point instead (via :func:`circle_deviations` with radius 0).
    """
    mono = _monomial(spiral)
    chord = end - start
    length = np.hypot(chord[:, 0], chord[:, 1])
    point = length == 0.0
    safe = np.where(point, 1.0, length)
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
    q = _eval(spiral, u)
    d = np.abs(np.einsum("nkj,nj->nk", q - start[:, None, :], normal))
    dev = np.nanmax(np.where(np.isnan(u), np.nan, d), axis=1)
    if np.any(point):
        zero = np.zeros(int(point.sum()))
        dev[point] = circle_deviations(spiral, u0[point], u1[point], start[point], zero, zero)
    return np.asarray(dev, dtype=np.float64)


def circle_deviations(
    spiral: Spiral,
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
    distance to one circle, radius 0 the distance to the point ``centre``. Its
    extrema lie where ``ρ`` is extreme: at the ends or at a root of the quintic
    ``g(u) = (Q(u) − centre)·Q'(u)`` (Walton & Meek's ``g_i``, here without a known root),
    whose roots are the eigenvalues of its companion matrix, for all rows at once.
    """
    mono = _monomial(spiral)
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
    q = _eval(spiral, u)
    rho = np.hypot(q[..., 0] - centre[:, None, 0], q[..., 1] - centre[:, None, 1])
    far = np.maximum(np.abs(rho - r_start[:, None]), np.abs(rho - r_end[:, None]))
    return np.asarray(np.nanmax(np.where(np.isnan(u), np.nan, far), axis=1), dtype=np.float64)


def chord_deviation(
    spiral: Spiral,
    u_start: float,
    u_end: float,
    start: Sequence[float],
    end: Sequence[float],
) -> float:
    """The largest distance from the spiral piece ``u_start ≤ u ≤ u_end`` to the line
    through ``start`` and ``end`` (to the point, if they coincide).

    Exact up to rounding: the extrema of ``n·(Q(u) − start)`` are the roots of a quadratic.
    When ``start`` and ``end`` are the piece's own end points this is also the distance to the
    segment: the spiral's tangent turns by less than 90° over the piece and passes through
    the chord's direction, so every point of the piece projects inside the chord.
    """
    dev = chord_deviations(
        spiral,
        np.array([float(u_start)]),
        np.array([float(u_end)]),
        np.array([start], dtype=np.float64),
        np.array([end], dtype=np.float64),
    )
    return float(dev[0])
