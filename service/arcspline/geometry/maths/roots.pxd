# cython: language_level=3
"""Roots of small polynomials in a bracket, for the compiled kernels (docs/method.md §7).

Polynomials are ascending coefficient arrays: ``c[0] + c[1]·x + … + c[d]·x^d``. Every root is
found by :func:`polynomial_root`: Newton's method from a caller's start point, with a
bisection-safeguarded Newton iteration where plain steps fail (a zero slope, a step out of the
bracket, no convergence). The kernels call these from C with no Python in between.
"""

from libc.math cimport fabs

cdef extern from *:
    """
    /* Near a root the kernels' polynomials evaluate to rounding noise (a few ulps of their
       O(1) terms) over slopes that can be small, so Newton steps stall at tens of ulps: a
       step below this many ulps of the bracket's magnitude counts as converged. The roots
       are used where such an error is immaterial (at a flat maximum, as split points). */
    #define ARCSPLINE_RESOLUTION (256.0 * 2.220446049250313e-16)
    /* Plain Newton steps before the safeguarded iteration takes over; its own cap. */
    #define ARCSPLINE_FAST_ITERATIONS 8
    #define ARCSPLINE_MAX_ITERATIONS 100
    """
    const double RESOLUTION "ARCSPLINE_RESOLUTION"
    const int FAST_ITERATIONS "ARCSPLINE_FAST_ITERATIONS"
    const int MAX_ITERATIONS "ARCSPLINE_MAX_ITERATIONS"


cdef inline double horner(const double* c, int degree, double x) noexcept nogil:
    """``c(x)`` by Horner's rule."""
    cdef double value = c[degree]
    cdef int j
    for j in range(degree - 1, -1, -1):
        value = value * x + c[j]
    return value


cdef inline double horner_slope(const double* c, int degree, double x) noexcept nogil:
    """``c'(x)`` by Horner's rule (``degree ≥ 1``)."""
    cdef double slope = degree * c[degree]
    cdef int j
    for j in range(degree - 1, 0, -1):
        slope = slope * x + j * c[j]
    return slope


cdef inline double safeguarded_root(
    const double* c, int degree, double lo, double hi, double start, double resolution
) noexcept nogil:
    """Newton inside the shrinking bracket ``[lo, hi]``, bisecting wherever a step would
    leave it; ``c(lo)`` and ``c(hi)`` differ in sign (either orientation)."""
    cdef double x = min(max(start, lo), hi)
    cdef double sign = 1.0 if horner(c, degree, lo) <= 0.0 else -1.0
    cdef double f, step, newton
    cdef int _i
    for _i in range(MAX_ITERATIONS):
        f = sign * horner(c, degree, x)
        if f < 0.0:
            lo = x
        else:
            hi = x
        step = f / (sign * horner_slope(c, degree, x))
        newton = x - step
        if fabs(step) <= resolution:
            return newton
        x = newton if lo < newton < hi else 0.5 * (lo + hi)
    return x


cdef inline double polynomial_root(
    const double* c, int degree, double lo, double hi, double start, int fixed
) noexcept nogil:
    """The root of ``c`` in ``[lo, hi]``, where ``c(lo)`` and ``c(hi)`` differ in sign.

    Plain Newton steps from ``start`` (clamped into the bracket): ``fixed`` of them before
    the first convergence test (callers whose start is good need fewer), then until a step is
    below ``RESOLUTION`` ulps of the bracket's magnitude, at most ``FAST_ITERATIONS`` in all.
    A result outside the bracket, or none, is found again by :func:`safeguarded_root`.
    """
    cdef double resolution = RESOLUTION * max(fabs(lo), fabs(hi))
    cdef double x = min(max(start, lo), hi)
    cdef double step
    cdef int i
    for i in range(FAST_ITERATIONS):
        step = horner(c, degree, x) / horner_slope(c, degree, x)
        x = x - step
        if i + 1 >= fixed and fabs(step) <= resolution:
            if lo <= x <= hi:
                return x
            break
    return safeguarded_root(c, degree, lo, hi, start, resolution)
