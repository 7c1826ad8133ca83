"""The incentre biarc of a piece of the canonical spiral (paper §2, after Sabin).

For the piece ``[u0, u1]`` with end points ``A0 = Q(u0)``, ``A1 = Q(u1)``, let ``α`` be the
angle from the tangent at ``A0`` to the chord ``A0→A1`` and ``β`` the angle from the chord to
the tangent at ``A1`` (both positive: the canonical spiral turns left). The join point ``G`` is
the incentre of the triangle ``(A0, V, A1)``, ``V`` where the two tangents meet, so it lies on
the bisectors of ``α`` at ``A0`` and of ``β`` at ``A1``. With the chord length ``L`` and
``S = sin((α + β)/2)``, the law of sines in ``(A0, G, A1)`` gives, without forming ``V``::

    |G − A0| = L·sin(β/2) / S          |A1 − G| = L·sin(α/2) / S
    r0 = |G − A0| / (2·sin(α/2))       r1 = |A1 − G| / (2·sin(β/2))

Arc 0 turns through ``α`` from ``A0`` to ``G``, arc 1 through ``β`` from ``G`` to ``A1``; at ``G``
both are tangent to the chord direction, so the pair is G1. Every quantity is formed from
angle differences and factored point differences (``service.geometry.canonical``), so a short
or nearly straight piece keeps full relative precision — ``V`` would be ill-conditioned there.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from . import canonical
from .types import FloatArray


@dataclass(frozen=True, slots=True)
class Biarcs:
    """Incentre biarcs of pieces ``[u0, u1]``, one per array element, canonical frame.

    ``phi0_rad``, ``chord_rad`` and ``phi1_rad`` are the directions at ``A0``, along the chord
    (= at ``G``) and at ``A1``; ``join_dx``, ``join_dy`` is ``G − A0``.
    """

    u0: FloatArray
    u1: FloatArray
    alpha_rad: FloatArray
    beta_rad: FloatArray
    phi0_rad: FloatArray
    chord_rad: FloatArray
    phi1_rad: FloatArray
    chord_length: FloatArray
    join_distance: FloatArray
    join_dx: FloatArray
    join_dy: FloatArray
    radius0: FloatArray
    radius1: FloatArray


def incentre_biarcs(k: FloatArray, m: FloatArray, u0: FloatArray, u1: FloatArray) -> Biarcs:
    """The incentre biarc of each piece ``[u0, u1]`` (``u0 < u1``) of spirals ``(k, m)``.

    The directions at ``u0``, along the chord and at ``u1`` are ``(1 + k·w, m·w)`` for
    ``w = u0²``, ``σ/3`` and ``u1²`` (``σ = u0² + u0·u1 + u1²``), formed once; the angles
    between them come from their exact cross products (as in ``canonical.turn_rad``).
    """
    h = u1 - u0
    w0, w1 = u0 * u0, u1 * u1
    sigma = w1 + u1 * u0 + w0
    w_chord = sigma / 3.0  # the chord is parallel to (1 + k·w, m·w) here
    x0, xc, x1 = 1.0 + k * w0, 1.0 + k * w_chord, 1.0 + k * w1
    y0, yc, y1 = m * w0, m * w_chord, m * w1
    alpha = np.arctan2(m * (h * (u1 + 2.0 * u0) / 3.0), x0 * xc + y0 * yc)
    beta = np.arctan2(m * (h * (2.0 * u1 + u0) / 3.0), xc * x1 + yc * y1)
    phi0 = np.arctan2(y0, x0)
    chord_dir = phi0 + alpha
    # Q(u1) − Q(u0) = h·(3 + k·σ, m·σ) (canonical.offset).
    length = canonical.norm(h * (3.0 + k * sigma), h * m * sigma)
    half_a, half_b = 0.5 * alpha, 0.5 * beta
    sin_half_a, sin_half_b = np.sin(half_a), np.sin(half_b)
    chord_over_s = length / np.sin(half_a + half_b)
    d0 = chord_over_s * sin_half_b
    bisector = phi0 + half_a
    return Biarcs(
        u0=u0,
        u1=u1,
        alpha_rad=alpha,
        beta_rad=beta,
        phi0_rad=phi0,
        chord_rad=chord_dir,
        phi1_rad=chord_dir + beta,
        chord_length=length,
        join_distance=d0,
        join_dx=d0 * np.cos(bisector),
        join_dy=d0 * np.sin(bisector),
        radius0=d0 / (2.0 * sin_half_a),
        radius1=chord_over_s * sin_half_a / (2.0 * sin_half_b),
    )
