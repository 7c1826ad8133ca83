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
both are tangent to the chord direction, so the pair is G1.

Only ``+ − × ÷`` and square roots are used — each correctly rounded, in numpy as in Python —
so the one-spiral path (``arcspline.geometry.subdivide_one``), which writes the same operations
out in floats, gives bit-identical results. The directions are the
unit vectors of ``(1 + k·w, m·w)`` (``arcspline.geometry.canonical``); the half angles come from
the exact cross products ``m·(w₂ − w₁)`` and the half-angle formulas, and point differences
are factored, so a short or nearly straight piece keeps full relative precision — ``V``
would be ill-conditioned there.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from .types import FloatArray


class Biarcs(NamedTuple):
    """Incentre biarcs of pieces ``[u0, u1]``, one per array element, canonical frame.

    ``e0``, ``ec``, ``e1`` are the unit directions at ``A0``, along the chord (= at ``G``) and
    at ``A1``; ``cos_half_a``/``sin_half_a`` are those of ``α/2`` (likewise ``β``); ``join`` is
    ``G − A0``, at distance ``join_distance``. A named tuple: built per level and per spiral,
    it costs a fraction of a frozen dataclass.
    """

    u0: FloatArray
    u1: FloatArray
    e0x: FloatArray
    e0y: FloatArray
    ecx: FloatArray
    ecy: FloatArray
    e1x: FloatArray
    e1y: FloatArray
    cos_half_a: FloatArray
    sin_half_a: FloatArray
    cos_half_b: FloatArray
    sin_half_b: FloatArray
    chord_length: FloatArray
    join_distance: FloatArray
    join_dx: FloatArray
    join_dy: FloatArray
    radius0: FloatArray
    radius1: FloatArray

    def sweeps_rad(self) -> tuple[FloatArray, FloatArray]:
        """``α`` and ``β``: the angles arc 0 and arc 1 turn through."""
        return (
            2.0 * np.arctan2(self.sin_half_a, self.cos_half_a),
            2.0 * np.arctan2(self.sin_half_b, self.cos_half_b),
        )


def incentre_biarcs(k: FloatArray, m: FloatArray, u0: FloatArray, u1: FloatArray) -> Biarcs:
    """The incentre biarc of each piece ``[u0, u1]`` (``u0 < u1``) of spirals ``(k, m)``.

    The chord is parallel to the direction at ``w = σ/3`` (``σ = u0² + u0·u1 + u1²``) and
    ``A1 − A0 = 3h·(1 + k·σ/3, m·σ/3)``, so ``L = 3h·‖(1 + k·σ/3, m·σ/3)‖``.
    ``cos(α/2) = √((1 + cos α)/2)`` has no cancellation (``α < 90°``), and
    ``sin(α/2) = sin α / (2·cos(α/2))`` keeps the cross product's relative precision.
    """
    sqrt = np.sqrt
    h = u1 - u0
    w0, w1 = u0 * u0, u1 * u1
    w_chord = (w1 + u1 * u0 + w0) / 3.0
    x0, y0 = 1.0 + k * w0, m * w0
    xc, yc = 1.0 + k * w_chord, m * w_chord
    x1, y1 = 1.0 + k * w1, m * w1
    n0, nc, n1 = sqrt(x0 * x0 + y0 * y0), sqrt(xc * xc + yc * yc), sqrt(x1 * x1 + y1 * y1)
    n0c, nc1 = n0 * nc, nc * n1
    cos_half_a = sqrt(0.5 + 0.5 * ((x0 * xc + y0 * yc) / n0c))
    cos_half_b = sqrt(0.5 + 0.5 * ((xc * x1 + yc * y1) / nc1))
    # sin α = m·(w_chord − w0) / (n0·nc), w_chord − w0 = h·(u1 + 2·u0)/3 (and so for β).
    sin_half_a = m * (h * (u1 + 2.0 * u0) / 3.0) / (n0c * (2.0 * cos_half_a))
    sin_half_b = m * (h * (2.0 * u1 + u0) / 3.0) / (nc1 * (2.0 * cos_half_b))
    chord_length = 3.0 * h * nc
    chord_over_s = chord_length / (sin_half_a * cos_half_b + cos_half_a * sin_half_b)
    join_distance = chord_over_s * sin_half_b
    e0x, e0y = x0 / n0, y0 / n0
    ecx, ecy = xc / nc, yc / nc
    # The bisector of α is (e0 + ec) / (2·cos(α/2)).
    along = join_distance / (2.0 * cos_half_a)
    return Biarcs(
        u0=u0,
        u1=u1,
        e0x=e0x,
        e0y=e0y,
        ecx=ecx,
        ecy=ecy,
        e1x=x1 / n1,
        e1y=y1 / n1,
        cos_half_a=cos_half_a,
        sin_half_a=sin_half_a,
        cos_half_b=cos_half_b,
        sin_half_b=sin_half_b,
        chord_length=chord_length,
        join_distance=join_distance,
        join_dx=along * (e0x + ecx),
        join_dy=along * (e0y + ecy),
        radius0=join_distance / (2.0 * sin_half_a),
        radius1=chord_over_s * sin_half_a / (2.0 * sin_half_b),
    )
