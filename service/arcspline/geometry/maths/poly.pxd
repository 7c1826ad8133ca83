# cython: language_level=3
"""Small polynomials for the compiled kernels: products, derivatives and every real root in
an interval by the derivative cascade (docs/method.md §7).

Polynomials are ascending coefficient arrays of at most ``MAX_COEFFS`` entries,
``c[0] + c[1]·x + … + c[d]·x^d``, with their degree passed beside them.

**The cascade.** Between consecutive roots of ``p'`` the polynomial ``p`` is monotone, so a
sign change of ``p`` over such an interval brackets its one root there and no sign change
means none. Starting from ``p⁽ᵈ⁻¹⁾`` (linear, its root in closed form) and going down one
derivative at a time yields every root of ``p`` in ``[lo, hi]`` — isolated, then polished by
:func:`polynomial_root` — with no sampling and no guess of how many there are.
"""

from arcspline.geometry.maths.roots cimport horner, polynomial_root

cdef enum:
    # Degree 7 at most (a rational cubic's distance derivative), so 8 coefficients.
    MAX_COEFFS = 8
    # The ends plus at most 7 roots on each of 7 levels, with room for rounding noise.
    MAX_POINTS = 64
    # Newton steps before the first convergence test, from a secant start.
    CASCADE_ITERATIONS = 3


cdef inline int degree_of(const double* c, int degree) noexcept nogil:
    """The true degree: trailing zero coefficients dropped (−1 for the zero polynomial)."""
    while degree >= 0 and c[degree] == 0.0:
        degree -= 1
    return degree


cdef inline void multiply(
    const double* a, int da, const double* b, int db, double* out
) noexcept nogil:
    """``out = a·b`` (degree ``da + db``; ``out`` must not alias ``a`` or ``b``)."""
    cdef int i, j
    for i in range(da + db + 1):
        out[i] = 0.0
    for i in range(da + 1):
        for j in range(db + 1):
            out[i + j] += a[i] * b[j]


cdef inline void add_product(
    double scale, const double* a, int da, const double* b, int db, double* out
) noexcept nogil:
    """``out += scale·a·b`` (``out`` already holds at least ``da + db + 1`` coefficients)."""
    cdef int i, j
    for i in range(da + 1):
        for j in range(db + 1):
            out[i + j] += scale * a[i] * b[j]


cdef inline void derivative(const double* c, int degree, double* out) noexcept nogil:
    """``out = c'`` (degree ``degree − 1``)."""
    cdef int j
    for j in range(degree):
        out[j] = (j + 1) * c[j + 1]


cdef inline int merge(double* points, int n, const double* roots, int count) noexcept nogil:
    """Insert ``roots`` (ascending, each within its bracket) into the sorted ``points``,
    dropping repeats; the new count."""
    cdef double merged[MAX_POINTS]
    cdef int i = 0, j = 0, m = 0
    cdef double x
    while (i < n or j < count) and m < MAX_POINTS:
        if j >= count or (i < n and points[i] <= roots[j]):
            x = points[i]
            i += 1
        else:
            x = roots[j]
            j += 1
        if m == 0 or x != merged[m - 1]:
            merged[m] = x
            m += 1
    for i in range(m):
        points[i] = merged[i]
    return m


cdef inline int critical_points(
    const double* c, int degree, double lo, double hi, double* points
) noexcept nogil:
    """``lo``, ``hi`` and every root in ``[lo, hi]`` of ``c`` and of its derivatives, sorted
    into ``points`` (at most ``MAX_POINTS``); their number. The roots of ``c`` itself are
    among them, and ``c`` is monotone between consecutive points."""
    cdef double levels[MAX_COEFFS][MAX_COEFFS]
    cdef double roots[MAX_COEFFS]
    degree = degree_of(c, degree)
    points[0], points[1] = lo, hi
    cdef int n = 2 if hi > lo else 1
    if degree < 1:
        return n
    cdef int d, j, i, found
    for j in range(degree + 1):
        levels[0][j] = c[j]
    for d in range(1, degree):
        derivative(levels[d - 1], degree - d + 1, levels[d])
    cdef const double* p
    cdef double fa, fb, a, b
    for d in range(degree - 1, -1, -1):
        p = levels[d]
        found = 0
        fb = horner(p, degree - d, points[0])
        for i in range(n - 1):
            a, b = points[i], points[i + 1]
            fa, fb = fb, horner(p, degree - d, b)
            if not ((fa < 0.0 and fb > 0.0) or (fa > 0.0 and fb < 0.0)):
                continue
            if degree - d == 1:
                roots[found] = min(max(-p[0] / p[1], a), b)
            else:
                roots[found] = polynomial_root(
                    p, degree - d, a, b, a + (b - a) * fa / (fa - fb), CASCADE_ITERATIONS
                )
            found += 1
        n = merge(points, n, roots, found)
    return n


cdef inline double minimum_on(const double* c, int degree, double lo, double hi) noexcept nogil:
    """The smallest value of ``c`` on ``[lo, hi]``: at an end or a root of ``c'``."""
    cdef double points[MAX_POINTS]
    cdef double slope[MAX_COEFFS]
    degree = degree_of(c, degree)
    cdef double low = min(horner(c, max(degree, 0), lo), horner(c, max(degree, 0), hi))
    if degree < 2:
        return low
    derivative(c, degree, slope)
    cdef int n = critical_points(slope, degree - 1, lo, hi, points), i
    for i in range(n):
        low = min(low, horner(c, degree, points[i]))
    return low
