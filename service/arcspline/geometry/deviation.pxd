# cython: language_level=3
from libc.math cimport INFINITY, NAN, fabs, sqrt

from arcspline.geometry.curves.canonical cimport Canonical
from arcspline.geometry.maths.vec cimport Vec


cdef struct Peak:
    # A largest deviation and the spiral parameter where it is reached.
    double value
    double u


cdef double joint_split(Canonical s, Vec joint, double tx, double ty) noexcept nogil
cdef Peak arc_deviation(
    Canonical s, Vec start, double tx, double ty, double kappa, Vec end, double lo, double hi,
    double tolerance
) noexcept nogil


cdef inline double split_guess(
    Canonical s, Vec joint, double tx, double ty, double lo, double hi, double start
) noexcept nogil:
    """Screening's guess of :func:`joint_split`: three plain Newton steps on
    ``(Q(u) − J)·T = a·u³ + 3t_x·u − J·T`` (``a = k·t_x + m·t_y``) from ``start``; NaN unless it
    lands inside ``(lo, hi)``. The proof recomputes it exactly."""
    cdef double a = s.k * tx + s.m * ty, b = 3.0 * tx, c = joint.x * tx + joint.y * ty
    cdef double a3 = 3.0 * a, u = start, u2
    cdef int _i
    for _i in range(3):
        u2 = u * u
        u = u - (u * (a * u2 + b) - c) / (a3 * u2 + b)
    return u if lo < u < hi else NAN


cdef inline double screen_radial(
    Canonical s, Vec joint, double nx, double ny, double kappa, double u
) noexcept nogil:
    """``|‖Q(u) − C‖ − r|`` for the circle through ``J`` with unit normal ``N`` and curvature
    ``κ``, for screening: with ``P = Q − J`` and ``d = ‖Q − C‖ = r + e``,
    ``ν = κ‖P‖² − 2P·N = e·(2 + κe)``, so ``|e| = |ν| / (1 + √|1 + κν|)`` (one root)."""
    cdef double w = u * u
    cdef double px = u * (3.0 + s.k * w) - joint.x, py = s.m * w * u - joint.y
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
    Canonical s, Vec j, Vec t, double kappa, double lo, double hi, int samples
) noexcept nogil:
    """Largest :func:`screen_radial` of the arc from ``j`` (unit tangent ``t``, curvature
    ``κ``) at ``samples`` (at most 8) points evenly inside the piece ``[lo, hi]``: screening's
    lower bound on the arc's deviation; ``inf`` if one is not a number."""
    cdef double values[8]
    cdef int k
    for k in range(samples):
        values[k] = screen_radial(s, j, -t.y, t.x, kappa, lo + (hi - lo) * ((k + 0.5) / samples))
    return largest(values, samples)
