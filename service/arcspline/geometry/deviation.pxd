# cython: language_level=3
from libc.math cimport INFINITY, NAN, fabs, sqrt

from arcspline.geometry.curves.piece cimport Piece, numerator, point, weight
from arcspline.geometry.maths.vec cimport Vec


cdef struct Peak:
    # A largest deviation and the piece parameter where it is reached.
    double value
    double u


cdef double joint_split(const Piece* p, Vec joint, double tx, double ty) noexcept nogil
cdef Peak arc_deviation(
    const Piece* p, Vec start, double tx, double ty, double kappa, Vec end, double lo,
    double hi, double tolerance
) noexcept nogil
cdef double line_deviation(const Piece* p, Vec start, Vec end, double lo, double hi) noexcept nogil


cdef inline double split_guess(
    const Piece* p, Vec joint, double tx, double ty, double lo, double hi, double start
) noexcept nogil:
    """Screening's guess of :func:`joint_split`: three plain Newton steps on the cubic
    ``(X(u) − J·W(u))·T`` from ``start``; NaN unless it lands inside ``(lo, hi)``. The proof
    recomputes it exactly."""
    cdef double c0 = -(joint.x * tx + joint.y * ty)
    cdef double c1 = p.x[1] * tx + p.y[1] * ty + c0 * p.w[1]
    cdef double c2 = p.x[2] * tx + p.y[2] * ty + c0 * p.w[2]
    cdef double c3 = p.x[3] * tx + p.y[3] * ty
    cdef double u = start
    cdef int _i
    for _i in range(3):
        u = u - (c0 + u * (c1 + u * (c2 + u * c3))) / (c1 + u * (2.0 * c2 + 3.0 * u * c3))
    return u if lo < u < hi else NAN


cdef inline double screen_radial(
    const Piece* p, Vec joint, double nx, double ny, double kappa, double u
) noexcept nogil:
    """``|‖Q(u) − C‖ − r|`` for the circle through ``J`` with unit normal ``N`` and curvature
    ``κ``, for screening: with ``P = Q − J`` and ``d = ‖Q − C‖ = r + e``,
    ``ν = κ‖P‖² − 2P·N = e·(2 + κe)``, so ``|e| = |ν| / (1 + √|1 + κν|)`` (one root)."""
    cdef Vec q = point(p, u)
    cdef double px = q.x - joint.x, py = q.y - joint.y
    cdef double nu = kappa * (px * px + py * py) - 2.0 * (px * nx + py * ny)
    return fabs(nu) / (1.0 + sqrt(fabs(1.0 + kappa * nu)))


cdef inline double largest(const double* values, int n) noexcept nogil:
    """The largest of ``values``; ``inf`` if one is not a number (a screen then refuses)."""
    cdef double worst = 0.0, nan_seen = 0.0
    cdef int i
    for i in range(n):
        worst = values[i] if values[i] > worst else worst
        nan_seen += values[i] - values[i]
    return worst if nan_seen == 0.0 else INFINITY


cdef inline double sampled(
    const Piece* p, Vec j, Vec t, double kappa, double lo, double hi, int samples
) noexcept nogil:
    """Largest :func:`screen_radial` of the arc from ``j`` (unit tangent ``t``, curvature
    ``κ``) at ``samples`` (at most 8) points evenly inside the piece ``[lo, hi]``: screening's
    lower bound on the arc's deviation; ``inf`` if one is not a number."""
    cdef double values[8]
    cdef int k
    for k in range(samples):
        values[k] = screen_radial(p, j, -t.y, t.x, kappa, lo + (hi - lo) * ((k + 0.5) / samples))
    return largest(values, samples)
