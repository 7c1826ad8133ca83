"""Where the spiral passes between a biarc's arcs (Theorem 1) and its largest deviation
from them (Theorem 2), paper §3–§4, in the canonical frame of ``arcspline.geometry.canonical``.

Only ``+ − × ÷`` and square roots are used, each correctly rounded in numpy as in Python: the
one-spiral path (``arcspline.geometry.subdivide_one``) writes the same operations out in floats
and gives bit-identical numbers.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
import numpy.typing as npt

from .biarc import Biarcs
from .roots import polynomial_root
from .types import FloatArray

#: Newton steps before the first convergence test, for Theorem 1's cubic and Theorem 2's
#: quartics: from the start points used here nearly every root is within the resolution after
#: two steps (the cubic) or one (the quartics), which the next step confirms.
SPLIT_FIXED_ITERATIONS = 3
SIDE_FIXED_ITERATIONS = 2


class Deviation(NamedTuple):
    """The largest radial deviation of each spiral piece from its biarc.

    ``split`` is Theorem 1's ``t``; ``arc0``/``arc1`` are the maxima over ``[u0, t]`` and
    ``[t, u1]`` (reached at ``u_arc0``/``u_arc1``); ``value`` and ``u`` are the overall
    maximum δ and where it occurs, ``u_d`` of §4.
    """

    split: FloatArray
    arc0: FloatArray
    u_arc0: FloatArray
    arc1: FloatArray
    u_arc1: FloatArray
    value: FloatArray
    u: FloatArray


class Cubic(NamedTuple):
    """``c3·v³ + c2·v² + c1·v + c0`` and a start for Newton."""

    c3: FloatArray
    c2: FloatArray
    c1: FloatArray
    c0: FloatArray
    start: FloatArray


def split_cubic(
    k: FloatArray,
    m: FloatArray,
    u0: FloatArray,
    h: FloatArray,
    ecx: FloatArray,
    ecy: FloatArray,
    cos_half_a: FloatArray,
    join_distance: FloatArray,
    chord_length: FloatArray,
) -> Cubic:
    """Theorem 1: ``t = u0 + v`` for the unique root ``v ∈ (0, h)`` of this cubic.

    ``(Q(t) − G)·H = 0`` with the chord direction ``H = ec`` and ``K = (k, m)·H`` is
    ``K·v³ + 3u0·K·v² + (3H_x + 3u0²·K)·v − (G − A0)·H = 0``, increasing on ``(0, h)`` (the
    theorem's ``f' > 0``); ``(G − A0)·H = |G − A0|·cos(α/2)``. Newton starts where ``G``
    projects on the chord, as a fraction of ``h``.
    """
    big_k = k * ecx + m * ecy
    c0 = -join_distance * cos_half_a
    return Cubic(
        c3=big_k,
        c2=3.0 * u0 * big_k,
        c1=3.0 * ecx + 3.0 * u0 * u0 * big_k,
        c0=c0,
        start=h * (-c0 / chord_length),
    )


class Quartic(NamedTuple):
    """Theorem 2's ``q_i(u) = a4·u⁴ + c3·u³ + c2·u² + c1·u + c0`` for arc ``i``, and the arc's
    radius vector ``r·N = (−rs, rc)`` from its tangent point."""

    a4: FloatArray
    c3: FloatArray
    c2: FloatArray
    c1: FloatArray
    c0: FloatArray
    rs: FloatArray
    rc: FloatArray


def side_quartic(
    k: FloatArray,
    m: FloatArray,
    a4: FloatArray,
    ui: FloatArray,
    radius: FloatArray,
    ex: FloatArray,
    ey: FloatArray,
) -> Quartic:
    """Theorem 2: the quartic whose root in the side is the deviation's interior maximum.

    ``q_i(u) = α1 + α2(u + u_i) + α3(u² + u·u_i + u_i²) + α4(u⁴ + u³u_i + u²u_i² + u·u_i³ +
    u_i⁴)`` with, canonically, ``α1 = 3``, ``α2 = −(k, m)·C_i``, ``α3 = 4k``, ``α4 = a4 = k² +
    m²``, expanded in ``u``. ``u_i`` is the arc's tangent point, where its unit tangent is
    ``(ex, ey)``; the centre is ``Q(u_i) + r·N``, ``N = (−ey, ex)``.
    """
    rs, rc = radius * ey, radius * ex
    ui2 = ui * ui
    ax, ay = ui * (3.0 + k * ui2), m * ui2 * ui  # Q(u_i)
    alpha2 = k * (rs - ax) - m * (ay + rc)
    c2 = 4.0 * k + a4 * ui2
    c1 = alpha2 + ui * c2
    return Quartic(a4=a4, c3=a4 * ui, c2=c2, c1=c1, c0=3.0 + ui * c1, rs=rs, rc=rc)


def quartic_value(q: Quartic, u: FloatArray) -> FloatArray:
    return (((q.a4 * u + q.c3) * u + q.c2) * u + q.c1) * u + q.c0


def secant(lo: FloatArray, hi: FloatArray, q_lo: FloatArray, q_hi: FloatArray) -> FloatArray:
    """Where the chord of ``q`` over ``[lo, hi]`` crosses zero."""
    return lo + (hi - lo) * q_lo / (q_lo - q_hi)


def towards(x: FloatArray, q_x: FloatArray, end: FloatArray, q_end: FloatArray) -> FloatArray:
    """The secant from ``x`` to the end of the sub-bracket where ``q`` has the other sign."""
    return x + (end - x) * q_x / (q_x - q_end)


def radial_gap(
    k: FloatArray, m: FloatArray, ui: FloatArray, u: FloatArray, q: Quartic, radius: FloatArray
) -> FloatArray:
    """``|‖Q(u) − C‖ − r|`` for the circle tangent at ``Q(u_i)``.

    With ``P = Q(u) − Q(u_i)`` (factored: ``(u − u_i)·(3 + k·σ, m·σ)``) and ``C = Q(u_i) +
    r·N``, ``‖Q − C‖ − r = (‖P‖² − 2r·P·N) / (‖P − r·N‖ + r)``, free of the cancellation
    between two nearly equal large numbers that the direct form suffers for large radii.
    """
    h = u - ui
    sigma = u * u + u * ui + ui * ui
    px, py = h * (3.0 + k * sigma), h * m * sigma
    numerator = px * px + py * py + 2.0 * (px * q.rs - py * q.rc)
    dx, dy = px + q.rs, py - q.rc
    return abs(numerator) / (np.sqrt(dx * dx + dy * dy) + radius)


def join_gap(
    k: FloatArray,
    m: FloatArray,
    u0: FloatArray,
    t: FloatArray,
    join_dx: FloatArray,
    join_dy: FloatArray,
) -> FloatArray:
    """``‖Q(t) − G‖``, the deviation at Theorem 1's ``t``, from ``Q(t) − A0`` factored."""
    h = t - u0
    sigma = t * t + t * u0 + u0 * u0
    dx, dy = h * (3.0 + k * sigma) - join_dx, h * m * sigma - join_dy
    return np.sqrt(dx * dx + dy * dy)


def split_parameter(k: FloatArray, m: FloatArray, b: Biarcs) -> FloatArray:
    """Theorem 1's ``t`` of each piece (:func:`split_cubic`)."""
    h = b.u1 - b.u0
    c = split_cubic(k, m, b.u0, h, b.ecx, b.ecy, b.cos_half_a, b.join_distance, b.chord_length)
    coefficients = (c.c3, c.c2, c.c1, c.c0)
    v = polynomial_root(coefficients, np.zeros_like(h), h, c.start, SPLIT_FIXED_ITERATIONS)
    return b.u0 + v


def max_deviation(k: FloatArray, m: FloatArray, b: Biarcs, t: FloatArray) -> Deviation:
    """Theorem 2: the exact largest radial deviation of each piece from its biarc.

    On each side the deviation's only interior maximum is at the root of
    :func:`side_quartic`; a sign change of ``q_i`` over the side brackets it; the deviation at
    ``t`` is ``‖Q(t) − G‖``. Both sides are solved in one stacked array.
    """
    n = t.shape[0]

    def stack(first: FloatArray, second: FloatArray) -> FloatArray:
        return np.concatenate((first, second))

    ui, lo, hi = stack(b.u0, b.u1), stack(b.u0, t), stack(t, b.u1)
    kk, mm = stack(k, k), stack(m, m)
    r = stack(b.radius0, b.radius1)
    q = side_quartic(kk, mm, kk * kk + mm * mm, ui, r, stack(b.e0x, b.e1x), stack(b.e0y, b.e1y))
    q_lo, q_hi = quartic_value(q, lo), quartic_value(q, hi)
    bracketed = q_lo * q_hi < 0.0
    # Only bracketed sides have an interior maximum; solve for those alone (usually all).
    every = np.count_nonzero(bracketed) == bracketed.size
    which: slice | npt.NDArray[np.intp] = slice(None) if every else np.flatnonzero(bracketed)
    root = lo if every else lo.copy()
    w_lo, w_hi, w_q_lo = lo[which], hi[which], q_lo[which]
    if w_lo.size:
        w_q = Quartic(*(c[which] for c in q))
        w_q_hi = q_hi[which]
        # One step of false position: q can be strongly curved over a side (it is where the
        # side ends at u = 1), and the secant of the sub-bracket is a far better start.
        x = secant(w_lo, w_hi, w_q_lo, w_q_hi)
        q_x = quartic_value(w_q, x)
        right = (q_x < 0.0) == (w_q_lo < 0.0)  # the root lies right of the secant point
        x = towards(x, q_x, np.where(right, w_hi, w_lo), np.where(right, w_q_hi, w_q_lo))
        found = polynomial_root(w_q[:5], w_lo, w_hi, x, SIDE_FIXED_ITERATIONS)
        if every:
            root = found
        else:
            root[which] = found
    side = radial_gap(kk, mm, ui, root, q, r)
    if not every:
        side = np.where(bracketed, side, 0.0)

    at_t = join_gap(k, m, b.u0, t, b.join_dx, b.join_dy)
    arc0, arc1 = side[:n], side[n:]
    u_arc0 = np.where(arc0 > at_t, root[:n], t)
    u_arc1 = np.where(arc1 > at_t, root[n:], t)
    arc0, arc1 = np.maximum(arc0, at_t), np.maximum(arc1, at_t)
    first = arc0 >= arc1
    return Deviation(
        split=t,
        arc0=arc0,
        u_arc0=u_arc0,
        arc1=arc1,
        u_arc1=u_arc1,
        value=np.where(first, arc0, arc1),
        u=np.where(first, u_arc0, u_arc1),
    )
