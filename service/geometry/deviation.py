"""Where the spiral passes between a biarc's arcs (Theorem 1) and its largest deviation
from them (Theorem 2), paper §3–§4, in the canonical frame of ``service.geometry.canonical``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from . import canonical
from .biarc import Biarcs
from .roots import polynomial_root
from .types import FloatArray


@dataclass(frozen=True, slots=True)
class Deviation:
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


def split_parameter(k: FloatArray, m: FloatArray, b: Biarcs) -> FloatArray:
    """Theorem 1: the unique ``t ∈ (u0, u1)`` with ``(Q(t) − G)·H = 0``.

    ``H`` is the chord direction. With ``v = t − u0`` and ``K = (k, m)·H`` the condition is the
    cubic ``K·v³ + 3u0·K·v² + (3H_x + 3u0²·K)·v − (G − A0)·H = 0``, increasing on ``(0, u1 − u0)``
    (the theorem's ``f' > 0``). ``(G − A0)·H = |G − A0|·cos(α/2)``.
    """
    hx, hy = np.cos(b.chord_rad), np.sin(b.chord_rad)
    big_k = k * hx + m * hy
    c2 = 3.0 * b.u0 * big_k
    c1 = 3.0 * hx + 3.0 * b.u0 * b.u0 * big_k
    c0 = -b.join_distance * np.cos(0.5 * b.alpha_rad)

    h = b.u1 - b.u0
    start = h * (-c0 / b.chord_length)  # where G projects on the chord, as a parameter guess
    v = polynomial_root((big_k, c2, c1, c0), np.zeros_like(h), h, start)
    return b.u0 + v


def max_deviation(k: FloatArray, m: FloatArray, b: Biarcs, t: FloatArray) -> Deviation:
    """Theorem 2: the exact largest radial deviation of each piece from its biarc.

    On side ``i`` the deviation's only interior maximum is at the root of the quartic
    ``q_i(u) = α1 + α2(u + u_i) + α3(u² + u·u_i + u_i²) + α4(u⁴ + u³u_i + u²u_i² + u·u_i³ + u_i⁴)``
    where ``u_i`` is the arc's tangent point; canonically ``α1 = 3``, ``α2 = −(k, m)·C_i``,
    ``α3 = 4k``, ``α4 = k² + m²``. A sign change of ``q_i`` over the side brackets it; the
    deviation at ``t`` is ``‖Q(t) − G‖``. Both sides are solved in one stacked array.
    """
    n = t.shape[0]
    ui = np.concatenate((b.u0, b.u1))
    lo = np.concatenate((b.u0, t))
    hi = np.concatenate((t, b.u1))
    kk, mm = np.concatenate((k, k)), np.concatenate((m, m))
    phi = np.concatenate((b.phi0_rad, b.phi1_rad))
    r = np.concatenate((b.radius0, b.radius1))
    # The centre is Q(u_i) + r·N with N = (−sin φ, cos φ): r·N = (−rs, rc).
    rs, rc = r * np.sin(phi), r * np.cos(phi)
    ui2 = ui * ui
    ax, ay = ui * (3.0 + kk * ui2), mm * ui2 * ui  # Q(u_i), canonical.point
    alpha2 = kk * (rs - ax) - mm * (ay + rc)
    alpha4 = kk * kk + mm * mm
    # q(u) = c0 + c1·u + c2·u² + c3·u³ + α4·u⁴ after expanding the symmetric sums in u_i
    # (α3 = 4k); the slope's coefficients are formed once, not per Newton step.
    c2 = 4.0 * kk + alpha4 * ui2
    c1 = alpha2 + ui * c2
    c0 = 3.0 + ui * c1
    c3 = alpha4 * ui
    q_lo = (((alpha4 * lo + c3) * lo + c2) * lo + c1) * lo + c0
    q_hi = (((alpha4 * hi + c3) * hi + c2) * hi + c1) * hi + c0
    bracketed = q_lo * q_hi < 0.0
    # Only bracketed sides have an interior maximum; solve for those alone (usually all).
    every = np.count_nonzero(bracketed) == bracketed.size
    which: slice | npt.NDArray[np.intp] = slice(None) if every else np.flatnonzero(bracketed)
    root = lo if every else lo.copy()
    w_lo, w_hi, w_q_lo = lo[which], hi[which], q_lo[which]
    if w_lo.size:
        w_a4, w_c3, w_c2, w_c1, w_c0 = alpha4[which], c3[which], c2[which], c1[which], c0[which]
        w_q_hi = q_hi[which]
        secant = w_lo + (w_hi - w_lo) * w_q_lo / (w_q_lo - w_q_hi)
        # One step of false position: q can be strongly curved over a side (it is where the
        # side ends at u = 1), and the secant of the sub-bracket is a far better start.
        q_s = (((w_a4 * secant + w_c3) * secant + w_c2) * secant + w_c1) * secant + w_c0
        right = (q_s < 0.0) == (w_q_lo < 0.0)  # the root lies right of the secant point
        # The sub-bracket is the secant point and the end where q has the other sign.
        end, q_end = np.where(right, w_hi, w_lo), np.where(right, w_q_hi, w_q_lo)
        secant = secant + (end - secant) * q_s / (q_s - q_end)
        found = polynomial_root((w_a4, w_c3, w_c2, w_c1, w_c0), w_lo, w_hi, secant)
        if every:
            root = found
        else:
            root[which] = found
    # |‖Q(u) − C‖ − r| for the circle tangent at Q(u_i): with P = Q(u) − Q(u_i) and
    # C = Q(u_i) + r·N, ‖Q − C‖ − r = (‖P‖² − 2r·P·N) / (‖P − r·N‖ + r), free of the
    # cancellation between two nearly equal large numbers that the direct form suffers for
    # large radii. P is formed in factored form (canonical.offset).
    h = root - ui
    sigma = root * root + root * ui + ui2
    px, py = h * (3.0 + kk * sigma), h * mm * sigma
    numerator = px * px + py * py + 2.0 * (px * rs - py * rc)
    side = np.abs(numerator) / (canonical.norm(px + rs, py - rc) + r)
    if not every:
        side = np.where(bracketed, side, 0.0)

    tx, ty = canonical.offset(k, m, b.u0, t)
    at_t = canonical.norm(tx - b.join_dx, ty - b.join_dy)
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
