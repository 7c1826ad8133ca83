# cython: language_level=3
"""The canonical spiral, for the compiled kernels (docs/method.md §2).

Translating ``B0`` to the origin, rotating ``T0`` onto +x, mirroring a clockwise spiral and
dividing by ``a`` turns every cubic Bézier spiral of turn angle θ into::

    Q(u)  = (3u + k·u³, m·u³)          k = 1.2·cos²θ − 1
    Q'(u) = 3·(1 + k·u², m·u²)         m = 1.2·cos θ·sin θ

Differences of points are formed in factored form (``Q(v) − Q(u) = (v − u)·(3 + k·σ, m·σ)``,
``σ = u² + uv + v²``) so that short pieces keep full relative precision wherever they lie.
"""

from libc.math cimport atan2, ceil, cos, log2, sin, sqrt

from arcspline.geometry.maths.quadrature cimport HALF_NODES, NODES, WEIGHTS
from arcspline.geometry.maths.vec cimport Vec, norm, vec


cdef struct Canonical:
    double k
    double m


cdef inline Canonical canonical(double turn_angle_rad) noexcept nogil:
    """``(k, m)`` of the canonical spiral of turn angle θ."""
    cdef double c = cos(turn_angle_rad), s = sin(turn_angle_rad)
    cdef Canonical q
    q.k = 1.2 * c * c - 1.0
    q.m = 1.2 * c * s
    return q


cdef inline Vec point(Canonical q, double u) noexcept nogil:
    """``Q(u)``."""
    cdef double w = u * u
    return vec(u * (3.0 + q.k * w), q.m * w * u)


cdef inline Vec offset(Canonical q, double u_from, double u_to) noexcept nogil:
    """``Q(u_to) − Q(u_from)`` in factored form."""
    cdef double h = u_to - u_from
    cdef double sigma = u_to * u_to + u_to * u_from + u_from * u_from
    return vec(h * (3.0 + q.k * sigma), h * q.m * sigma)


cdef inline Vec direction(Canonical q, double w) noexcept nogil:
    """``Q'/3`` at ``u = √w``: ``(1 + k·w, m·w)`` (not a unit vector)."""
    return vec(1.0 + q.k * w, q.m * w)


cdef inline Vec unit_tangent(Canonical q, double u) noexcept nogil:
    """The unit vector along ``Q'(u)``."""
    cdef Vec d = direction(q, u * u)
    cdef double n = norm(d)
    return vec(d.x / n, d.y / n)


cdef inline double tangent(Canonical q, double u, Vec* unit) noexcept nogil:
    """The direction of ``Q'(u)``: its polar angle, and its unit vector into ``unit``."""
    cdef Vec d = direction(q, u * u)
    cdef double n = norm(d)
    unit[0] = vec(d.x / n, d.y / n)
    return atan2(d.y, d.x)


cdef inline double speed(Canonical q, double u) noexcept nogil:
    """``‖Q'(u)‖``."""
    return 3.0 * norm(direction(q, u * u))


cdef inline double arc_length(Canonical q, double u0, double u1) noexcept nogil:
    """Length of ``Q`` over ``[u0, u1]`` (docs/method.md §6).

    The speed has no zero on ``[0, 1]`` but, as θ → 90°, dips to ``3.6·cos θ`` at ``u = 1``
    over a width of about ``cos θ``: the panels halve towards ``u1`` until they are narrower
    than ``cos θ / 16``, and 12-point Gauss–Legendre integrates each to rounding.
    """
    # 1 + k = 1.2·cos²θ
    cdef double cos_theta = sqrt((1.0 + q.k) / 1.2)
    cdef int levels = <int>ceil(-log2(max(cos_theta, 2.0 ** -64))) + 4
    levels = min(max(levels, 4), 64)
    cdef double total = 0.0, lo, hi, half, mid, fraction = 1.0, panel
    cdef int p, j
    for p in range(levels + 1):
        lo = u1 - (u1 - u0) * fraction
        fraction = fraction * 0.5 if p < levels else 0.0
        hi = u1 - (u1 - u0) * fraction
        half = 0.5 * (hi - lo)
        mid = 0.5 * (lo + hi)
        panel = 0.0
        for j in range(HALF_NODES):
            panel += WEIGHTS[j] * (
                speed(q, mid - half * NODES[j]) + speed(q, mid + half * NODES[j])
            )
        total += half * panel
    return total
