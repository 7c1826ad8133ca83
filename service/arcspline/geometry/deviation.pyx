# cython: language_level=3, boundscheck=False, wraparound=False, cdivision=True
"""The exact two-sided deviation of an arc (or a line) from a piece of a curve
(docs/method.md §10 "Certified deviation"), for every arc any strategy keeps.

**Which piece an arc answers for.** Arc ``i`` of a G1 chain runs from joint ``J_i`` (unit
tangent ``T_i``) to ``J_{i+1}``; its end rays from its centre are the chain's normal lines at
the joints, so the root ``s_i`` of ``(Q(s) − J_i)·T_i`` (:func:`joint_split`, increasing in
``s`` on a piece that turns by less than a half turn) splits the piece between the arcs
before and after ``J_i``.

**Why the radial deviation is the two-sided distance.** If the polar angle of ``Q(u)`` about
the centre ``C`` is strictly monotone on the piece and its ends lie on the rays through the
arc's ends (not on the opposite side of ``C``), the piece and the arc are polar graphs
``ρ(ψ)`` over the same angles, so their Hausdorff distance is ``max |‖Q(u) − C‖ − r|``.
Both conditions are checked exactly: the angle is monotone iff ``w(u) = κ·(Q − J)×Q' + T·Q'
> 0`` on the piece — with ``Q = (X, Y)/W``, ``W³·w = κ·(X − J·W)×D + W·(T·D)``, ``D = X'W −
XW'``, a polynomial proven positive by its Bernstein coefficients or, failing that, by its
minimum (at an end or a root of its derivative, ``maths/poly.pxd``); the sides are signs
of ``(κ(Q(s) − J) − N)·(κ(E − J) − N)``.
An arc failing either is refused (``inf``).

**The maximum, exactly.** ``e(u) = |κ‖P‖² − 2P·N| / (‖κP − N‖ + 1)`` (``P = Q(u) − J``, no
cancellation for huge radii) has its interior extrema at roots of ``(Q − C)·Q'``, that is of
the polynomial ``h = κ·(X − J·W)·D − W·(N·D)`` (degree 5 for a cubic, 4 for a conic). Every
root in the piece is isolated by the derivative cascade; the maximum of ``e`` over the ends
and these roots is the deviation. No sample is involved.
"""

from libc.float cimport DBL_EPSILON as EPS
from libc.math cimport INFINITY, NAN, cos, fabs, isfinite, sin, sqrt

from arcspline.geometry.curves.piece cimport (
    Piece,
    add_weighted_dot,
    direction,
    point,
    relative_numerators,
    spiral_piece,
    tangent_numerators,
)
from arcspline.geometry.maths.poly cimport (
    MAX_COEFFS,
    MAX_POINTS,
    add_product,
    critical_points,
    positive_on,
)
from arcspline.geometry.maths.roots cimport polynomial_root
from arcspline.geometry.maths.vec cimport Vec, vec

cdef extern from *:
    """
    /* An arc's centre is stored with an error of about eps·radius; this many ulps of the
       radius must fit in the tolerance (an error of at most 1e-4 of it). */
    #define ARCSPLINE_CENTRE_ULPS 1e4
    /* Where the distance polynomial's Bernstein coefficients stand less than this far above
       their rounding bound, its roots are refined by searching the gap itself. */
    #define ARCSPLINE_WELL_CONDITIONED 1e9
    """
    const double CENTRE_ULPS "ARCSPLINE_CENTRE_ULPS"
    const double WELL_CONDITIONED "ARCSPLINE_WELL_CONDITIONED"

# Newton steps before the first convergence test, from a secant start; golden-section steps
# of a refinement (0.618^60 of a tenth of the piece: below rounding).
cdef enum:
    FIXED_ITERATIONS = 4
    REFINE_STEPS = 60


cdef double joint_split(const Piece* p, Vec joint, double tx, double ty) noexcept nogil:
    """The ``u ∈ [0, 1]`` where the piece crosses the normal line at ``joint`` (unit tangent
    ``(tx, ty)``); NaN if it does not. ``f(u) = (Q(u) − J)·T`` has the sign of the cubic
    ``(X − J·W)·T``; with ``Q'·T > 0`` at both ends of a piece whose tangent turns
    monotonically by less than a half turn, ``f`` increases and a sign change over ``[0, 1]``
    brackets its only root."""
    cdef double px[4]
    cdef double py[4]
    cdef double c[4]
    relative_numerators(p, joint, px, py)
    cdef int i
    for i in range(4):
        c[i] = px[i] * tx + py[i] * ty
    cdef double f_hi = c[0] + c[1] + c[2] + c[3]
    cdef Vec d0 = direction(p, 0.0), d1 = direction(p, 1.0)
    if not (c[0] <= 0.0 and f_hi >= 0.0 and d0.x * tx + d0.y * ty > 0.0
            and d1.x * tx + d1.y * ty > 0.0):
        return NAN
    if c[0] == 0.0:
        return 0.0
    return polynomial_root(c, 3, 0.0, 1.0, -c[0] / (f_hi - c[0]), FIXED_ITERATIONS)


cdef inline bint is_graph(
    const Piece* p, Vec j, double tx, double ty, double kappa, Vec e, double lo, double hi,
    const double* px, const double* py, const double* dx, const double* dy
) noexcept nogil:
    """Both polar-graph conditions of the module text, exactly."""
    cdef double nx = -ty, ny = tx
    cdef double w[MAX_COEFFS]
    cdef int i
    for i in range(MAX_COEFFS):
        w[i] = 0.0
    # κ·(X − J·W)×D + W·(T·D)
    add_product(kappa, px, 3, dy, 4, w)
    add_product(-kappa, py, 3, dx, 4, w)
    add_weighted_dot(p, tx, ty, dx, dy, w)
    if not (hi > lo and positive_on(w, MAX_COEFFS - 1, lo, hi)):
        return False
    cdef double ex = kappa * (e.x - j.x) - nx, ey = kappa * (e.y - j.y) - ny
    cdef Vec q = point(p, lo)
    if not (kappa * (q.x - j.x) - nx) * ex + (kappa * (q.y - j.y) - ny) * ey > 0.0:
        return False
    q = point(p, hi)
    return (kappa * (q.x - j.x) - nx) * ex + (kappa * (q.y - j.y) - ny) * ey > 0.0


cdef inline double radial(
    const Piece* p, Vec j, double nx, double ny, double kappa, double u
) noexcept nogil:
    """``|‖Q(u) − C‖ − r|`` as ``|κ‖P‖² − 2P·N| / (‖κP − N‖ + 1)``; a square that overflows
    (a circle far too small) reads as ``inf``, never as distance 0."""
    cdef Vec q = point(p, u)
    cdef double px = q.x - j.x, py = q.y - j.y
    cdef double top = kappa * (px * px + py * py) - 2.0 * (px * nx + py * ny)
    cdef double ax = kappa * px - nx, ay = kappa * py - ny
    cdef double square = ax * ax + ay * ay
    if not isfinite(square):
        return INFINITY
    return fabs(top) / (sqrt(square) + 1.0)


cdef inline (double, double) refine(
    const Piece* p, Vec j, double nx, double ny, double kappa, double u, double lo, double hi
) noexcept nogil:
    """The largest :func:`radial` within a tenth of the piece around ``u``, by golden-section
    search (the gap is unimodal there), and where it is."""
    cdef double width = 0.1 * (hi - lo)
    cdef double a = max(lo, u - width), b = min(hi, u + width)
    cdef double golden = 0.6180339887498949
    cdef double x1 = b - golden * (b - a), x2 = a + golden * (b - a)
    cdef double f1 = radial(p, j, nx, ny, kappa, x1), f2 = radial(p, j, nx, ny, kappa, x2)
    cdef int _k
    for _k in range(REFINE_STEPS):
        if f1 < f2:
            a, x1, f1 = x1, x2, f2
            x2 = a + golden * (b - a)
            f2 = radial(p, j, nx, ny, kappa, x2)
        else:
            b, x2, f2 = x2, x1, f1
            x1 = b - golden * (b - a)
            f1 = radial(p, j, nx, ny, kappa, x1)
    return (f1, x1) if f1 >= f2 else (f2, x2)


cdef Peak arc_deviation(
    const Piece* p, Vec j, double tx, double ty, double kappa, Vec e, double lo, double hi,
    double tolerance
) noexcept nogil:
    """The exact two-sided deviation of the arc from ``j`` (unit tangent ``(tx, ty)``,
    curvature ``κ``) to ``e`` from the piece ``[lo, hi]``, and where it is reached.

    ``inf`` where the piece is not a polar graph over the arc, lies outside ``[0, 1]``, or
    the arc is so flat that its centre (``radius/tolerance`` beyond ``1/(CENTRE_ULPS·eps)``)
    cannot be written in double precision to a small fraction of the tolerance — unless
    ``tolerance`` is 0: ``subdivide``'s arcs touch the curve at both ends, and the assembly
    writes the flattest as their chords and measures the placement of the rest.
    """
    cdef Peak peak
    peak.value, peak.u = INFINITY, lo
    if not (lo >= 0.0 and hi <= 1.0):
        return peak
    if not (kappa == 0.0 or tolerance == 0.0 or fabs(kappa) * tolerance >= CENTRE_ULPS * EPS):
        return peak
    cdef double px[4]
    cdef double py[4]
    cdef double dx[5]
    cdef double dy[5]
    relative_numerators(p, j, px, py)
    tangent_numerators(p, dx, dy)
    if not is_graph(p, j, tx, ty, kappa, e, lo, hi, px, py, dx, dy):
        return peak
    cdef double nx = -ty, ny = tx
    cdef double h[MAX_COEFFS]
    cdef int i
    for i in range(MAX_COEFFS):
        h[i] = 0.0
    # κ·(X − J·W)·D − W·(N·D)
    add_product(kappa, px, 3, dx, 4, h)
    add_product(kappa, py, 3, dy, 4, h)
    add_weighted_dot(p, -nx, -ny, dx, dy, h)
    # Where the arc starts (ends) on the piece's first (last) point it is tangent there (a
    # G1 chain through a point of the curve), and h has a root at that end.
    cdef Vec at_lo = point(p, lo), at_hi = point(p, hi)
    cdef double points[MAX_POINTS]
    cdef double conditioning
    cdef int n = critical_points(
        h, MAX_COEFFS - 1, lo, hi, points, at_lo.x == j.x and at_lo.y == j.y,
        at_hi.x == e.x and at_hi.y == e.y, &conditioning,
    )
    cdef double value, u
    peak.value = -INFINITY
    for i in range(n):
        value = radial(p, j, nx, ny, kappa, points[i])
        if value != value:
            peak.value = NAN
            return peak
        if value > peak.value:
            peak.value, peak.u = value, points[i]
    if conditioning < WELL_CONDITIONED:
        # The polynomial stands barely above its rounding on this short or flat piece (the
        # tip of a very thin ellipse): its roots can sit off the maxima they stand for.
        # Search each interior candidate's neighbourhood for the largest gap itself.
        for i in range(1, n - 1):
            value, u = refine(p, j, nx, ny, kappa, points[i], lo, hi)
            if value > peak.value:
                peak.value, peak.u = value, u
    return peak


cdef double line_deviation(const Piece* p, Vec start, Vec end, double lo, double hi) noexcept nogil:
    """Largest distance from the piece ``[lo, hi]`` to the line through ``start`` and
    ``end``: ``(Q(u) − S)×ĉ`` has its interior extrema where ``D(u)×ĉ = 0``."""
    cdef double cx = end.x - start.x, cy = end.y - start.y
    cdef double length = sqrt(cx * cx + cy * cy)
    cx, cy = cx / length, cy / length
    cdef double dx[5]
    cdef double dy[5]
    cdef double c[MAX_COEFFS]
    tangent_numerators(p, dx, dy)
    cdef int i
    for i in range(MAX_COEFFS):
        c[i] = dx[i] * cy - dy[i] * cx if i < 5 else 0.0
    cdef double points[MAX_POINTS]
    cdef int n = critical_points(c, 4, lo, hi, points, False, False)
    cdef double worst = 0.0
    cdef Vec q
    for i in range(n):
        q = point(p, points[i])
        worst = max(worst, fabs((q.x - start.x) * cy - (q.y - start.y) * cx))
    return worst


def deviation_of_arc(
    double k, double m, double jx, double jy, double phi_rad, double kappa, double ex,
    double ey, double lo, double hi, double tolerance
):
    """:func:`arc_deviation` for Python (tests): ``(value, u)`` for the polynomial piece
    ``(3u + k·u³, m·u³)`` — the paper's canonical spiral for its ``(k, m)`` — and the arc from
    ``(jx, jy)`` with direction ``phi_rad`` to ``(ex, ey)``."""
    cdef Piece s = spiral_piece(k, m)
    cdef Peak peak = arc_deviation(
        &s, vec(jx, jy), cos(phi_rad), sin(phi_rad), kappa, vec(ex, ey), lo, hi, tolerance
    )
    return peak.value, peak.u
