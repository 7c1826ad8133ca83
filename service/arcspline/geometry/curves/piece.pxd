# cython: language_level=3
"""A curve piece in its local frame, for the compiled kernels (docs/method.md §2, §11).

Every curve the kernels fit — the paper's spiral, a piece of a cubic or quadratic Bézier, a
piece of an elliptical arc — is a rational curve of degree at most three, written in the power
basis on ``u ∈ [0, 1]``::

    Q(u) = (X(u), Y(u)) / W(u)      X = x1·u + x2·u² + x3·u³ (so Q(0) = 0), W = 1 + w1·u + w2·u²

in a frame where the piece starts at the origin, leaves along +x, turns left (a mirror is
part of the frame) and has size about 1. Polynomial pieces have ``W = 1`` (``rational``
false); an elliptical piece is a rational quadratic (a conic, exactly). The paper's spiral of
turn angle θ is ``X = 3u + k·u³``, ``Y = m·u³`` with ``k = 1.2·cos²θ − 1``, ``m = 1.2·cos θ·sin θ``.

Differences of points are formed in factored form, ``Q(v) − Q(u) = (v − u)·(ΔX·W(u) −
X(u)·ΔW) / (W(u)·W(v))`` with the divided differences ``ΔX = x1 + x2(u + v) + x3(u² + uv +
v²)`` and ``ΔW = w1 + w2(u + v)``, so that short pieces keep full relative precision.
"""

from libc.float cimport DBL_EPSILON
from libc.math cimport atan2, fabs

from arcspline.geometry.maths.quadrature cimport HALF_NODES, NODES, WEIGHTS
from arcspline.geometry.maths.vec cimport Vec, norm, vec

cdef enum:
    # Adaptive quadrature: panels halve until two levels agree to LENGTH_RTOL, at most this
    # deep (2^-40 of the piece; pieces are monotone in curvature, so few panels are needed).
    MAX_LENGTH_DEPTH = 40
    LENGTH_STACK = 96
    MAX_LENGTH_PANELS = 4096


cdef struct Piece:
    double x[4]       # x[0] = 0
    double y[4]       # y[0] = 0
    double w[3]       # w[0] = 1
    bint rational     # w1 or w2 non-zero


cdef inline Piece spiral_piece(double k, double m) noexcept nogil:
    """The paper's canonical spiral ``(3u + k·u³, m·u³)`` (docs/method.md §2). It takes
    ``k = 1.2·cos²θ − 1`` and ``m = 1.2·cos θ·sin θ``, not θ: near 90° ``cos`` of θ in
    radians has lost the relative accuracy that ``cos θ`` needs (docs/method.md §1)."""
    cdef Piece p
    p.x[0], p.x[1], p.x[2], p.x[3] = 0.0, 3.0, 0.0, k
    p.y[0], p.y[1], p.y[2], p.y[3] = 0.0, 0.0, 0.0, m
    p.w[0], p.w[1], p.w[2] = 1.0, 0.0, 0.0
    p.rational = False
    return p


cdef inline double weight(const Piece* p, double u) noexcept nogil:
    return 1.0 + u * (p.w[1] + u * p.w[2]) if p.rational else 1.0


cdef inline void tangent_numerators(const Piece* p, double* dx, double* dy) noexcept nogil:
    """The coefficients (5 each, ascending) of ``X'W − XW'``: ``W²·Q'``."""
    cdef int i
    for i in range(5):
        dx[i] = 0.0
        dy[i] = 0.0
    for i in range(1, 4):
        dx[i - 1] += i * p.x[i]
        dy[i - 1] += i * p.y[i]
    if not p.rational:
        return
    cdef int j
    # X'·(W − 1) − X·W'
    for i in range(1, 4):
        for j in range(1, 3):
            dx[i - 1 + j] += i * p.x[i] * p.w[j] - j * p.w[j] * p.x[i]
            dy[i - 1 + j] += i * p.y[i] * p.w[j] - j * p.w[j] * p.y[i]


cdef inline void relative_numerators(
    const Piece* p, Vec j, double* px, double* py
) noexcept nogil:
    """The coefficients (4 each, ascending) of ``X − J·W``: ``W·(Q − J)``."""
    cdef int i
    for i in range(4):
        px[i], py[i] = p.x[i], p.y[i]
    for i in range(3):
        px[i] -= j.x * p.w[i]
        py[i] -= j.y * p.w[i]


cdef inline void add_weighted_dot(
    const Piece* p, double vx, double vy, const double* dx, const double* dy, double* out
) noexcept nogil:
    """``out += W·(V·D)`` for ``D`` of :func:`tangent_numerators` (5 coefficients each)."""
    cdef double c
    cdef int i
    for i in range(5):
        out[i] += vx * dx[i] + vy * dy[i]
    if not p.rational:
        return
    cdef double w1 = p.w[1], w2 = p.w[2]
    for i in range(5):
        c = vx * dx[i] + vy * dy[i]
        out[i + 1] += w1 * c
        out[i + 2] += w2 * c


cdef inline Vec numerator(const Piece* p, double u) noexcept nogil:
    """``(X(u), Y(u))``."""
    return vec(u * (p.x[1] + u * (p.x[2] + u * p.x[3])), u * (p.y[1] + u * (p.y[2] + u * p.y[3])))


cdef inline Vec point(const Piece* p, double u) noexcept nogil:
    """``Q(u)``."""
    cdef Vec n = numerator(p, u)
    cdef double w
    if not p.rational:
        return n
    w = weight(p, u)
    return vec(n.x / w, n.y / w)


cdef inline Vec offset(const Piece* p, double u, double v) noexcept nogil:
    """``Q(v) − Q(u)`` in factored form."""
    cdef double h = v - u, s1 = u + v, s2 = u * u + u * v + v * v
    cdef double dx = p.x[1] + p.x[2] * s1 + p.x[3] * s2
    cdef double dy = p.y[1] + p.y[2] * s1 + p.y[3] * s2
    cdef double wu, wv, dw
    cdef Vec n
    if not p.rational:
        return vec(h * dx, h * dy)
    wu, wv, dw = weight(p, u), weight(p, v), p.w[1] + p.w[2] * s1
    n = numerator(p, u)
    return vec(h * (dx * wu - n.x * dw) / (wu * wv), h * (dy * wu - n.y * dw) / (wu * wv))


cdef inline Vec derivative_numerator(const Piece* p, double u) noexcept nogil:
    """``X'·W − X·W'``: ``W²·Q'(u)``, a positive multiple of the tangent."""
    cdef Vec d = vec(p.x[1] + u * (2.0 * p.x[2] + 3.0 * u * p.x[3]),
                     p.y[1] + u * (2.0 * p.y[2] + 3.0 * u * p.y[3]))
    cdef double w, dw
    cdef Vec n
    if not p.rational:
        return d
    w, dw = weight(p, u), p.w[1] + 2.0 * u * p.w[2]
    n = numerator(p, u)
    return vec(d.x * w - n.x * dw, d.y * w - n.y * dw)


cdef inline Vec direction(const Piece* p, double u) noexcept nogil:
    """A positive multiple of the tangent at ``u`` (not a unit vector). Where the speed is 0
    to rounding (a cusp, a turning point or coincident control points, at an end) it is the
    limit of the tangent from inside the piece: ``±(W²Q')'`` or ``(W²Q')''``."""
    cdef Vec d = derivative_numerator(p, u)
    # Zero to rounding (a cusp or turning point where a piece was cut): its sign is noise.
    cdef double noise = 64.0 * DBL_EPSILON * (
        fabs(p.x[1]) + fabs(p.y[1]) + 2.0 * (fabs(p.x[2]) + fabs(p.y[2]))
        + 3.0 * (fabs(p.x[3]) + fabs(p.y[3]))
    )
    if fabs(d.x) + fabs(d.y) > noise:
        return d
    cdef double side = 1.0 if u < 0.5 else -1.0
    cdef double w = weight(p, u), dw = p.w[1] + 2.0 * u * p.w[2], ddw = 2.0 * p.w[2]
    cdef Vec n = numerator(p, u)
    cdef Vec d1 = vec(p.x[1] + u * (2.0 * p.x[2] + 3.0 * u * p.x[3]),
                      p.y[1] + u * (2.0 * p.y[2] + 3.0 * u * p.y[3]))
    cdef Vec d2 = vec(2.0 * p.x[2] + 6.0 * u * p.x[3], 2.0 * p.y[2] + 6.0 * u * p.y[3])
    # (X'W − XW')' = X''W − XW''
    d = vec(side * (d2.x * w - n.x * ddw), side * (d2.y * w - n.y * ddw))
    if d.x != 0.0 or d.y != 0.0:
        return d
    # (X'W − XW')'' = X'''W + X''W' − X'W''
    return vec(6.0 * p.x[3] * w + d2.x * dw - d1.x * ddw, 6.0 * p.y[3] * w + d2.y * dw - d1.y * ddw)


cdef inline Vec unit_tangent(const Piece* p, double u) noexcept nogil:
    """The unit tangent at ``u``."""
    cdef Vec d = direction(p, u)
    cdef double n = norm(d)
    return vec(d.x / n, d.y / n)


cdef inline double tangent(const Piece* p, double u, Vec* unit) noexcept nogil:
    """The tangent at ``u``: its polar angle, and its unit vector into ``unit``."""
    cdef Vec d = direction(p, u)
    cdef double n = norm(d)
    unit[0] = vec(d.x / n, d.y / n)
    return atan2(d.y, d.x)


cdef inline double speed(const Piece* p, double u) noexcept nogil:
    """``‖Q'(u)‖``."""
    cdef double w = weight(p, u)
    return norm(derivative_numerator(p, u)) / (w * w)


cdef inline double panel_length(const Piece* p, double lo, double hi) noexcept nogil:
    """12-point Gauss–Legendre on ``[lo, hi]``."""
    cdef double half = 0.5 * (hi - lo), mid = 0.5 * (lo + hi), total = 0.0
    cdef int j
    for j in range(HALF_NODES):
        total += WEIGHTS[j] * (speed(p, mid - half * NODES[j]) + speed(p, mid + half * NODES[j]))
    return half * total


cdef inline double arc_length(const Piece* p, double u0, double u1) noexcept nogil:
    """Length of ``Q`` over ``[u0, u1]`` (docs/method.md §6): adaptive 12-point
    Gauss–Legendre, a panel kept where it agrees with its two halves to 1e-14 of itself or
    of the whole length (the speed is smooth, but can dip steeply near a cusp or as the
    spiral's θ → 90°, where it is known only to its rounding relative to its larger terms),
    and at most ``MAX_LENGTH_PANELS`` panels in all."""
    cdef double lo_stack[LENGTH_STACK]
    cdef double hi_stack[LENGTH_STACK]
    cdef double whole_stack[LENGTH_STACK]
    cdef int depth_stack[LENGTH_STACK]
    cdef int top = 0, depth
    cdef double total = 0.0, lo, hi, whole, mid, left, right
    lo_stack[0], hi_stack[0], whole_stack[0], depth_stack[0] = u0, u1, panel_length(p, u0, u1), 0
    cdef double floor = 1e-14 * fabs(whole_stack[0])
    cdef int panels = 0
    top = 1
    while top > 0:
        top -= 1
        lo, hi, whole, depth = lo_stack[top], hi_stack[top], whole_stack[top], depth_stack[top]
        mid = 0.5 * (lo + hi)
        left, right = panel_length(p, lo, mid), panel_length(p, mid, hi)
        panels += 2
        if depth >= MAX_LENGTH_DEPTH or top + 2 > LENGTH_STACK or panels >= MAX_LENGTH_PANELS or (
            fabs(left + right - whole) <= max(1e-14 * fabs(left + right), floor)
        ):
            total += left + right
            continue
        lo_stack[top], hi_stack[top], whole_stack[top], depth_stack[top] = mid, hi, right, depth + 1
        lo_stack[top + 1], hi_stack[top + 1], whole_stack[top + 1] = lo, mid, left
        depth_stack[top + 1] = depth + 1
        top += 2
    return total
