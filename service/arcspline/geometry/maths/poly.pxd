# cython: language_level=3
"""Small polynomials for the compiled kernels: products, derivatives and every real root in
an interval by the derivative cascade (docs/method.md §7).

Polynomials are ascending coefficient arrays of at most ``MAX_COEFFS`` entries,
``c[0] + c[1]·x + … + c[d]·x^d``, with their degree passed beside them.

**Bernstein screen.** On ``[lo, hi]`` the polynomial is first written in the Bernstein basis
of its degree; the number of sign changes of those coefficients bounds the number of roots
there and has its parity (Descartes' rule for the Bernstein basis). None: no root, and all
positive: positive throughout. One: exactly one root, bracketed by the ends. The screen is
trusted only when every coefficient is farther from 0 than its rounding error bound; only
otherwise does the cascade run. It is the common case's shortcut, not an approximation.

**The cascade.** Between consecutive roots of ``p'`` the polynomial ``p`` is monotone, so a
sign change of ``p`` over such an interval brackets its one root there and no sign change
means none. Starting from ``p⁽ᵈ⁻¹⁾`` (linear, its root in closed form) and going down one
derivative at a time yields every root of ``p`` in ``[lo, hi]`` — isolated, then polished by
:func:`polynomial_root` — with no sampling and no guess of how many there are.
"""

from libc.float cimport DBL_EPSILON
from libc.math cimport INFINITY, fabs

from arcspline.geometry.maths.roots cimport horner, polynomial_root

cdef enum:
    # Degree 7 at most (a rational cubic's distance derivative), so 8 coefficients.
    MAX_COEFFS = 8
    # The ends plus at most 7 roots on each of 7 levels, with room for rounding noise.
    MAX_POINTS = 64
    # Newton steps before the first convergence test, from a secant start.
    CASCADE_ITERATIONS = 3


cdef extern from *:
    """
    /* Binomial coefficients C(n, k), n < 8. */
    static const double ARCSPLINE_BINOMIAL[8][8] = {
        {1, 0, 0, 0, 0, 0, 0, 0}, {1, 1, 0, 0, 0, 0, 0, 0}, {1, 2, 1, 0, 0, 0, 0, 0},
        {1, 3, 3, 1, 0, 0, 0, 0}, {1, 4, 6, 4, 1, 0, 0, 0}, {1, 5, 10, 10, 5, 1, 0, 0},
        {1, 6, 15, 20, 15, 6, 1, 0}, {1, 7, 21, 35, 35, 21, 7, 1}};
    """
    const double BINOMIAL "ARCSPLINE_BINOMIAL"[8][8]


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


cdef inline void bernstein(
    const double* c, int degree, double lo, double hi, double* out
) noexcept nogil:
    """The Bernstein coefficients of ``c`` on ``[lo, hi]`` (``degree + 1`` of them): a Taylor
    shift to ``lo``, a scaling by ``hi − lo``, then ``b_i = Σ_{k≤i} C(i,k)/C(n,k)·a_k``."""
    cdef double a[MAX_COEFFS]
    cdef int i, j, k
    for i in range(degree + 1):
        a[i] = c[i]
    for i in range(degree):
        for j in range(degree - 1, i - 1, -1):
            a[j] += lo * a[j + 1]
    cdef double h = hi - lo, power = h
    for k in range(1, degree + 1):
        a[k] *= power
        power *= h
    for i in range(degree + 1):
        out[i] = 0.0
        for k in range(i + 1):
            out[i] += BINOMIAL[i][k] / BINOMIAL[degree][k] * a[k]


cdef inline double bernstein_error(
    const double* c, int degree, double lo, double hi
) noexcept nogil:
    """A bound on the rounding error of each of :func:`bernstein`'s coefficients:
    ``4(n + 1)²·eps·Σ|c_k|·max(|lo|, |hi|)^k`` (the shift and the sums each add at most
    ``n`` roundings of terms no larger than that)."""
    cdef double x = max(fabs(lo), fabs(hi)), total = 0.0, power = 1.0
    cdef int k
    for k in range(degree + 1):
        total += fabs(c[k]) * power
        power *= x
    return 4.0 * (degree + 1) * (degree + 1) * DBL_EPSILON * total


cdef inline int sign_changes(const double* b, int count, double error) noexcept nogil:
    """Sign changes along ``b``; −1 when a coefficient is within ``error`` of 0 and so has
    no certain sign."""
    cdef int changes = 0, i
    for i in range(count):
        if not fabs(b[i]) > error:
            return -1
        if i > 0 and (b[i] > 0.0) != (b[i - 1] > 0.0):
            changes += 1
    return changes


cdef inline int deflate_end(double* c, int degree, double x) noexcept nogil:
    """Divide ``c`` by ``(u − x)`` where ``c(x)`` is zero to rounding (its Horner error bound),
    as where an arc touches the curve at an end of its piece: the root at the end is known,
    and its rounding noise would hide the sign of ``c`` beside it. The new degree."""
    cdef double value = c[degree], bound = fabs(c[degree]), ax = fabs(x)
    cdef int j
    for j in range(degree - 1, -1, -1):
        value = value * x + c[j]
        bound = bound * ax + fabs(c[j])
    if degree < 1 or fabs(value) > 16.0 * degree * DBL_EPSILON * bound:
        return degree
    # Synthetic division; the remainder (the noise) is dropped.
    cdef double carry = c[degree], next_carry
    for j in range(degree - 1, -1, -1):
        next_carry = c[j] + carry * x
        c[j] = carry
        carry = next_carry
    c[degree] = 0.0
    return degree - 1


cdef inline int critical_points(
    const double* c, int degree, double lo, double hi, double* points, bint touch_lo,
    bint touch_hi, double* conditioning=NULL
) noexcept nogil:
    """``lo``, ``hi`` and every root in ``[lo, hi]`` of ``c`` (and, where the cascade runs,
    of its derivatives), sorted into ``points`` (at most ``MAX_POINTS``); their number.
    ``touch_lo``/``touch_hi`` say that ``c`` has a root at that end in exact arithmetic (an
    arc tangent to the curve there): it is divided out first (:func:`deflate_end`). If
    ``conditioning`` is given, it receives how far the polynomial stands above its rounding
    on the interval: its largest Bernstein coefficient over their error bound (``inf`` where
    there is nothing to find)."""
    if conditioning != NULL:
        conditioning[0] = INFINITY
    cdef double levels[MAX_COEFFS][MAX_COEFFS]
    cdef double roots[MAX_COEFFS]
    cdef int j
    for j in range(degree + 1):
        levels[0][j] = c[j]
    degree = degree_of(levels[0], degree)
    points[0], points[1] = lo, hi
    cdef int n = 2 if hi > lo else 1
    if degree < 1 or n == 1:
        return n
    if touch_lo:
        degree = deflate_end(levels[0], degree, lo)
    if touch_hi:
        degree = deflate_end(levels[0], degree, hi)
    if degree < 1:
        return n
    c = levels[0]
    cdef double bern[MAX_COEFFS]
    bernstein(c, degree, lo, hi, bern)
    cdef double error = bernstein_error(c, degree, lo, hi)
    cdef int changes = sign_changes(bern, degree + 1, error)
    cdef double largest = 0.0
    if conditioning != NULL:
        for j in range(degree + 1):
            largest = max(largest, fabs(bern[j]))
        conditioning[0] = largest / error if error > 0.0 else INFINITY
    if changes == 0:
        return n
    if changes == 1:
        # Exactly one root, strictly inside.
        points[2] = points[1]
        points[1] = polynomial_root(
            c, degree, lo, hi, lo + (hi - lo) * bern[0] / (bern[0] - bern[degree]),
            CASCADE_ITERATIONS,
        )
        return 3
    cdef int d, i, found
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


cdef inline bint positive_on(const double* c, int degree, double lo, double hi) noexcept nogil:
    """Whether ``c > 0`` on ``(lo, hi)`` (and ``≥ 0`` at the ends): a root at an end, within
    the rounding of its value there (the speed of a curve vanishing at a cusp or at coincident
    control points), is divided out first — as ``(u − lo)`` or ``(hi − u)``, positive inside —
    then all Bernstein coefficients positive prove it; otherwise the smallest value, at an
    end or a root of ``c'``, decides."""
    cdef double points[MAX_POINTS]
    cdef double slope[MAX_COEFFS]
    cdef double b[MAX_COEFFS]
    cdef double q[MAX_COEFFS]
    cdef int i, n, before
    for i in range(degree + 1):
        q[i] = c[i]
    degree = degree_of(q, degree)
    for _ in range(3):
        before = degree
        degree = deflate_end(q, degree, lo)
        if degree < before:
            continue
        degree = deflate_end(q, degree, hi)
        if degree < before:
            for i in range(degree + 1):
                q[i] = -q[i]  # (u − hi)·q = (hi − u)·(−q)
            continue
        break
    if degree < 0:
        return False
    bernstein(q, degree, lo, hi, b)
    cdef double error = bernstein_error(q, degree, lo, hi)
    cdef bint all_positive = True
    for i in range(degree + 1):
        all_positive = all_positive and b[i] > error
    if all_positive:
        return True
    cdef double low = min(horner(q, degree, lo), horner(q, degree, hi))
    if degree >= 2:
        derivative(q, degree, slope)
        n = critical_points(slope, degree - 1, lo, hi, points, False, False)
        for i in range(n):
            low = min(low, horner(q, degree, points[i]))
    return low > 0.0


cdef inline int roots_in(
    const double* c, int degree, double lo, double hi, double* out
) noexcept nogil:
    """The roots of ``c`` strictly inside ``(lo, hi)``, ascending, into ``out``; their number.
    Of :func:`critical_points`, those where ``c`` is zero to its rounding error (the roots
    of derivatives there are not). For split points, where a root missed or doubled only
    moves where a piece ends."""
    cdef double points[MAX_POINTS]
    cdef int n = critical_points(c, degree, lo, hi, points, False, False), i, count = 0, k
    cdef double x, value, bound
    for i in range(n):
        x = points[i]
        if not lo < x < hi:
            continue
        value, bound = c[degree], fabs(c[degree])
        for k in range(degree - 1, -1, -1):
            value = value * x + c[k]
            bound = bound * fabs(x) + fabs(c[k])
        if fabs(value) <= 1e3 * (degree + 1) * DBL_EPSILON * bound:
            out[count] = x
            count += 1
    return count
