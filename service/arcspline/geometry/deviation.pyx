# cython: language_level=3, boundscheck=False, wraparound=False, cdivision=True
"""The exact two-sided deviation of an arc from a piece of the canonical spiral
(docs/method.md §10 "Certified deviation"), for the arcs of ``fewest-arcs``, which need not
touch the spiral.

**Which piece an arc answers for.** Arc ``i`` of a G1 chain runs from joint ``J_i`` (unit
tangent ``T_i``) to ``J_{i+1}``; its end rays from its centre are the chain's normal lines at
the joints, so the root ``s_i`` of ``(Q(s) − J_i)·T_i`` (:func:`joint_split`, a cubic
increasing in ``s``) splits the spiral between the arcs before and after ``J_i``.

**Why the radial deviation is the two-sided distance.** If the polar angle of ``Q(u)`` about
the centre ``C`` is strictly monotone on the piece and its ends lie on the rays through the
arc's ends (not on the opposite side of ``C``), the piece and the arc are polar graphs
``ρ(ψ)`` over the same angles, so their Hausdorff distance is ``max |‖Q(u) − C‖ − r|``.
Both conditions are checked exactly: the angle is monotone iff ``w(u) = κ·(Q − J)×Q' + T·Q'
> 0``, and ``w/3 = κ·j_y + T_x + (κ(k·j_y − m·j_x) + k·T_x + m·T_y)·u² + 2mκ·u³`` is a cubic
whose minimum is at an end or its one interior critical point; the sides are signs of
``(κ(Q(s) − J) − N)·(κ(E − J) − N)``. An arc failing either is refused (``inf``).

**The maximum, exactly.** ``e(u) = |κ‖P‖² − 2P·N| / (‖κP − N‖ + 1)`` (``P = Q(u) − J``, no
cancellation for huge radii) has its interior extrema at roots of the quintic
``h(u) = κ·P·Q'/3 − N·Q'/3 = c0 + c1·u + c2·u² + c3·u³ + c5·u⁵``. Every root in the piece is
isolated by the *derivative cascade*: ``h⁽⁴⁾ = 120·c5·u`` has no root in ``u > 0``; between
consecutive roots of ``h⁽ᵈ⁺¹⁾`` the function ``h⁽ᵈ⁾`` is monotone, so a sign change brackets
its only root there and no sign change means none. Going down from ``h⁽³⁾`` (its root in
closed form) to ``h`` yields every root; the maximum of ``e`` over the ends and these roots
is the deviation. No sample is involved.
"""

from libc.float cimport DBL_EPSILON as EPS
from libc.math cimport INFINITY, NAN, cos, fabs, isfinite, sin, sqrt

from arcspline.geometry.curves.canonical cimport Canonical, point
from arcspline.geometry.maths.roots cimport horner, polynomial_root
from arcspline.geometry.maths.vec cimport Vec, vec

cdef extern from *:
    """
    /* An arc's centre is stored with an error of about eps·radius; this many ulps of the
       radius must fit in the tolerance (an error of at most 1e-4 of it). */
    #define ARCSPLINE_CENTRE_ULPS 1e4
    """
    const double CENTRE_ULPS "ARCSPLINE_CENTRE_ULPS"

# Newton steps before the first convergence test, from a joint's start or a secant.
cdef enum:
    FIXED_ITERATIONS = 4
    # Points of the cascade at most: the ends and the roots of four derivatives (at most 14
    # in exact arithmetic; room for rounding noise that brackets more).
    MAX_POINTS = 32


cdef double joint_split(Canonical s, Vec joint, double tx, double ty) noexcept nogil:
    """The ``u ∈ [0, 1]`` where the spiral crosses the normal line at ``joint`` (unit tangent
    ``(tx, ty)``); NaN if it does not. ``f(u) = (Q(u) − J)·T`` has ``f' = 3(T_x(1 + k·u²) +
    T_y·m·u²) > 0`` for the directions used here, so a sign change over ``[0, 1]`` brackets
    its only root."""
    cdef double c[4]
    c[0] = -(joint.x * tx + joint.y * ty)
    c[1] = 3.0 * tx
    c[2] = 0.0
    c[3] = s.k * tx + s.m * ty
    cdef double f_hi = c[0] + c[1] + c[3]
    cdef double slope_lo = 3.0 * tx, slope_hi = 3.0 * (tx * (1.0 + s.k) + ty * s.m)
    if not (c[0] <= 0.0 and f_hi >= 0.0 and slope_lo > 0.0 and slope_hi > 0.0):
        return NAN
    return polynomial_root(c, 3, 0.0, 1.0, min(max(joint.x / 3.0, 0.0), 1.0), FIXED_ITERATIONS)


cdef inline bint is_graph(
    Canonical s, Vec j, double tx, double ty, double kappa, Vec e, double lo, double hi
) noexcept nogil:
    """Both polar-graph conditions of the module text, exactly."""
    cdef double nx = -ty, ny = tx
    cdef double w0 = kappa * j.y + tx
    cdef double w2 = kappa * (s.k * j.y - s.m * j.x) + s.k * tx + s.m * ty
    cdef double w3 = 2.0 * s.m * kappa
    cdef double w_min = min(w0 + lo * lo * (w2 + w3 * lo), w0 + hi * hi * (w2 + w3 * hi))
    cdef double critical
    if w3 != 0.0:
        critical = -w2 / (1.5 * w3)
        if lo < critical < hi:
            w_min = min(w_min, w0 + critical * critical * (w2 + w3 * critical))
    if not (w_min > 0.0 and hi > lo):
        return False
    cdef double dx = kappa * (e.x - j.x) - nx, dy = kappa * (e.y - j.y) - ny
    cdef Vec q = point(s, lo)
    if not (kappa * (q.x - j.x) - nx) * dx + (kappa * (q.y - j.y) - ny) * dy > 0.0:
        return False
    q = point(s, hi)
    return (kappa * (q.x - j.x) - nx) * dx + (kappa * (q.y - j.y) - ny) * dy > 0.0


cdef inline double radial(
    Canonical s, Vec j, double nx, double ny, double kappa, double u
) noexcept nogil:
    """``|‖Q(u) − C‖ − r|`` as ``|κ‖P‖² − 2P·N| / (‖κP − N‖ + 1)``; a square that overflows
    (a circle far too small) reads as ``inf``, never as distance 0."""
    cdef Vec q = point(s, u)
    cdef double px = q.x - j.x, py = q.y - j.y
    cdef double numerator = kappa * (px * px + py * py) - 2.0 * (px * nx + py * ny)
    cdef double ax = kappa * px - nx, ay = kappa * py - ny
    cdef double square = ax * ax + ay * ay
    if not isfinite(square):
        return INFINITY
    return fabs(numerator) / (sqrt(square) + 1.0)


cdef inline int cascade_roots(
    const double* h, double lo, double hi, double* points
) noexcept nogil:
    """Every root in ``[lo, hi]`` (``lo ≥ 0``) of the quintic ``h`` (ascending, ``c4 = 0``),
    with the ends and the roots of its derivatives, sorted into ``points``; their number."""
    # The derivatives h⁽³⁾, h⁽²⁾, h⁽¹⁾ (ascending); h⁽⁴⁾ = 120·c5·u has no root in u > 0.
    cdef double d1[5]
    cdef double d2[4]
    cdef double d3[3]
    cdef int j
    for j in range(5):
        d1[j] = (j + 1) * h[j + 1]
    for j in range(4):
        d2[j] = (j + 1) * d1[j + 1]
    for j in range(3):
        d3[j] = (j + 1) * d2[j + 1]
    cdef const double* levels[4]
    cdef int degree[4]
    levels[0], levels[1], levels[2], levels[3] = d3, d2, d1, h
    degree[0], degree[1], degree[2], degree[3] = 2, 3, 4, 5
    points[0], points[1] = lo, hi
    cdef int n = 2, level, i, found
    cdef double roots[MAX_POINTS]
    cdef double fa, fb, a, b, root, ratio
    cdef const double* c
    for level in range(4):
        c = levels[level]
        found = 0
        fb = horner(c, degree[level], points[0])
        for i in range(n - 1):
            a, b = points[i], points[i + 1]
            fa, fb = fb, horner(c, degree[level], b)
            if not ((fa < 0.0 and fb > 0.0) or (fa > 0.0 and fb < 0.0)):
                continue
            if level == 0:
                # h⁽³⁾ = 6·c3 + 60·c5·u²: its root in u > 0 in closed form.
                ratio = -c[0] / c[2]
                root = min(max(sqrt(ratio), a), b)
            else:
                root = polynomial_root(c, degree[level], a, b, a + (b - a) * fa / (fa - fb),
                                       FIXED_ITERATIONS)
            roots[found] = root
            found += 1
        n = merge(points, n, roots, found)
    return n


cdef inline int merge(double* points, int n, const double* roots, int count) noexcept nogil:
    """Insert ``roots`` (ascending, each within its bracket) into the sorted ``points``,
    dropping repeats; the new count."""
    cdef double merged[MAX_POINTS]
    cdef int i = 0, j = 0, m = 0
    cdef double x
    while i < n or j < count:
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


cdef Peak arc_deviation(
    Canonical s, Vec j, double tx, double ty, double kappa, Vec e, double lo, double hi,
    double tolerance
) noexcept nogil:
    """The exact two-sided deviation of the arc from ``j`` (unit tangent ``(tx, ty)``,
    curvature ``κ``) to ``e`` from the spiral piece ``[lo, hi]``, and where it is reached.

    ``inf`` where the piece is not a polar graph over the arc, lies outside ``[0, 1]``, or
    the arc is so flat that its centre (``radius/tolerance`` beyond ``1/(CENTRE_ULPS·eps)``)
    cannot be written in double precision to a small fraction of the tolerance.
    """
    cdef Peak peak
    peak.value, peak.u = INFINITY, lo
    if not (lo >= 0.0 and hi <= 1.0 and is_graph(s, j, tx, ty, kappa, e, lo, hi)):
        return peak
    if not (kappa == 0.0 or fabs(kappa) * tolerance >= CENTRE_ULPS * EPS):
        return peak
    cdef double nx = -ty, ny = tx
    cdef double h[6]
    h[0] = -kappa * j.x - nx
    h[1] = 3.0 * kappa
    h[2] = -kappa * (s.k * j.x + s.m * j.y) - (s.k * nx + s.m * ny)
    h[3] = 4.0 * s.k * kappa
    h[4] = 0.0
    h[5] = kappa * (s.k * s.k + s.m * s.m)
    cdef double points[MAX_POINTS]
    cdef int n = cascade_roots(h, lo, hi, points), i
    cdef double value
    peak.value = -INFINITY
    for i in range(n):
        value = radial(s, j, nx, ny, kappa, points[i])
        if value != value:
            peak.value = NAN
            return peak
        if value > peak.value:
            peak.value, peak.u = value, points[i]
    return peak


def deviation_of_arc(
    double k, double m, double jx, double jy, double phi_rad, double kappa, double ex,
    double ey, double lo, double hi, double tolerance
):
    """:func:`arc_deviation` for Python (tests): ``(value, u)`` for the canonical spiral
    ``(k, m)`` and the arc from ``(jx, jy)`` with direction ``phi_rad`` to ``(ex, ey)``."""
    cdef Canonical s
    s.k, s.m = k, m
    cdef Peak peak = arc_deviation(
        s, vec(jx, jy), cos(phi_rad), sin(phi_rad), kappa, vec(ex, ey), lo, hi, tolerance
    )
    return peak.value, peak.u
