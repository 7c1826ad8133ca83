# cython: language_level=3, boundscheck=False, wraparound=False, cdivision=True
"""Strategy ``subdivide``: Walton & Meek's recursive subdivision (docs/method.md §3–§5).

The incentre biarc of a piece ``[u0, u1]`` of the canonical spiral is kept when its exact
largest deviation δ (Theorems 1 and 2) is within the tolerance; otherwise the piece is split
at ``u_d``, where δ occurs. The recursion runs depth first on an explicit stack, so the kept
biarcs come out in parameter order.
"""

from libc.float cimport DBL_EPSILON as EPS
from libc.math cimport atan2, fabs, sqrt
from libcpp.vector cimport vector

from arcspline.geometry.curves.canonical cimport Canonical, direction, point
from arcspline.geometry.deviation cimport Peak
from arcspline.geometry.fit.arcs cimport OK, STUCK, SEGMENT_LIMIT, Arc, Status
from arcspline.geometry.fit cimport batch
from arcspline.geometry.maths.roots cimport polynomial_root
from arcspline.geometry.maths.vec cimport Vec, norm, vec

cdef extern from *:
    """
    /* A piece whose split point lies within this many ulps (of its end) of either end
       cannot be split any further in double precision. */
    #define ARCSPLINE_STUCK_ULPS 4.0
    """
    const double STUCK_ULPS "ARCSPLINE_STUCK_ULPS"

# Newton steps before the first convergence test: from the start points used here nearly
# every root is within the resolution after two steps (Theorem 1's cubic) or one (Theorem
# 2's quartics), which the next step confirms.
cdef enum:
    SPLIT_FIXED_ITERATIONS = 3
    SIDE_FIXED_ITERATIONS = 2


cdef struct End:
    # What a piece needs of one of its ends: computed once per split point for both pieces
    # that share it.
    double u
    double w      # u²
    Vec d         # the direction (1 + k·w, m·w)
    double n      # its norm
    Vec e         # its unit vector
    Vec q         # Q(u)


cdef inline End end_at(Canonical s, double u) noexcept nogil:
    cdef End end
    end.u = u
    end.w = u * u
    end.d = direction(s, end.w)
    end.n = norm(end.d)
    end.e = vec(end.d.x / end.n, end.d.y / end.n)
    end.q = point(s, u)
    return end


cdef inline Peak side_peak(
    Canonical s, double alpha4, End* tangent, double lo, double hi, double radius,
    double at_t, double t
) noexcept nogil:
    """Theorem 2 on one side ``[lo, hi]`` of the arc tangent at ``tangent``: the largest
    radial deviation and where it is (docs/method.md §4).

    ``q(u) = α1 + α2(u + u_i) + α3(u² + u·u_i + u_i²) + α4(u⁴ + u³u_i + u²u_i² + u·u_i³ + u_i⁴)``
    with, canonically, ``α1 = 3``, ``α2 = −(k, m)·C``, ``α3 = 4k``, ``α4 = k² + m²``, expanded
    in ``u``; a sign change over the side brackets its one root, the interior maximum. The
    gap ``|‖Q(u) − C‖ − r|`` is formed as ``(‖P‖² − 2r·P·N) / (‖P − r·N‖ + r)``, ``P = Q(u) −
    Q(u_i)`` factored, free of the cancellation of two large nearly equal numbers.
    """
    cdef double ui = tangent.u, ui2 = tangent.w
    cdef double rs = radius * tangent.e.y, rc = radius * tangent.e.x
    cdef double alpha2 = s.k * (rs - tangent.q.x) - s.m * (tangent.q.y + rc)
    cdef double c[5]
    c[4] = alpha4
    c[3] = alpha4 * ui
    c[2] = 4.0 * s.k + alpha4 * ui2
    c[1] = alpha2 + ui * c[2]
    c[0] = 3.0 + ui * c[1]
    cdef Peak peak
    cdef double q_lo = (((c[4] * lo + c[3]) * lo + c[2]) * lo + c[1]) * lo + c[0]
    cdef double q_hi = (((c[4] * hi + c[3]) * hi + c[2]) * hi + c[1]) * hi + c[0]
    if not q_lo * q_hi < 0.0:
        peak.value, peak.u = at_t, t
        return peak
    # One step of false position: q can be strongly curved over a side (where it ends at
    # u = 1), and the secant of the sub-bracket is a far better start for Newton.
    cdef double x = lo + (hi - lo) * q_lo / (q_lo - q_hi)
    cdef double q_x = (((c[4] * x + c[3]) * x + c[2]) * x + c[1]) * x + c[0]
    if (q_x < 0.0) == (q_lo < 0.0):
        x = x + (hi - x) * q_x / (q_x - q_hi)
    else:
        x = x + (lo - x) * q_x / (q_x - q_lo)
    cdef double u = polynomial_root(c, 4, lo, hi, x, SIDE_FIXED_ITERATIONS)
    cdef double h = u - ui
    cdef double sigma = u * u + u * ui + ui2
    cdef double px = h * (3.0 + s.k * sigma), py = h * s.m * sigma
    cdef double numerator = px * px + py * py + 2.0 * (px * rs - py * rc)
    cdef double dx = px + rs, dy = py - rc
    cdef double gap = fabs(numerator) / (sqrt(dx * dx + dy * dy) + radius)
    if gap > at_t or gap != gap:  # a NaN is kept, and refused when the arcs are assembled
        peak.value, peak.u = gap, u
    else:
        peak.value, peak.u = at_t, t
    return peak


cdef inline Peak incentre_biarc(
    Canonical s, double alpha4, End* a, End* b, Arc* arc0, Arc* arc1
) noexcept nogil:
    """The incentre biarc of the piece from ``a`` to ``b`` (§2) as two arcs, each with its
    exact largest deviation (Theorems 1 and 2, §3–§4); the piece's δ and ``u_d``.

    With the chord's length ``L``, the angles ``α`` (from the tangent at ``A0`` to the chord)
    and ``β`` (from the chord to the tangent at ``A1``) and ``S = sin((α + β)/2)``, the law of
    sines in ``(A0, G, A1)`` gives ``|G − A0| = L·sin(β/2)/S`` and the radii
    ``r0 = |G − A0|/(2 sin(α/2))``, ``r1 = L·sin(α/2)/(2 S sin(β/2))``, without forming ``V``.
    The chord is parallel to the direction at ``w = σ/3``; half angles come from exact cross
    products (``m·(w_c − w0)``) and the half-angle formulas.
    """
    cdef double u0 = a.u, u1 = b.u, h = u1 - u0
    cdef double w_chord = (b.w + u1 * u0 + a.w) / 3.0
    cdef Vec dc = direction(s, w_chord)
    cdef double nc = norm(dc)
    cdef double n0c = a.n * nc, nc1 = nc * b.n
    cdef double cos_half_a = sqrt(0.5 + 0.5 * ((a.d.x * dc.x + a.d.y * dc.y) / n0c))
    cdef double cos_half_b = sqrt(0.5 + 0.5 * ((dc.x * b.d.x + dc.y * b.d.y) / nc1))
    # sin α = m·(w_c − w0)/(n0·nc), w_c − w0 = h·(u1 + 2·u0)/3 (and so for β)
    cdef double sin_half_a = s.m * (h * (u1 + 2.0 * u0) / 3.0) / (n0c * (2.0 * cos_half_a))
    cdef double sin_half_b = s.m * (h * (2.0 * u1 + u0) / 3.0) / (nc1 * (2.0 * cos_half_b))
    cdef double chord_length = 3.0 * h * nc
    cdef double chord_over_s = chord_length / (sin_half_a * cos_half_b + cos_half_a * sin_half_b)
    cdef double join_distance = chord_over_s * sin_half_b
    cdef Vec ec = vec(dc.x / nc, dc.y / nc)
    # G − A0 along the bisector of α, (e0 + ec)/(2·cos(α/2))
    cdef double along = join_distance / (2.0 * cos_half_a)
    cdef Vec join = vec(along * (a.e.x + ec.x), along * (a.e.y + ec.y))
    cdef double radius0 = join_distance / (2.0 * sin_half_a)
    cdef double radius1 = chord_over_s * sin_half_a / (2.0 * sin_half_b)

    # Theorem 1: t = u0 + v, v the root in (0, h) of the increasing cubic (Q(t) − G)·H with
    # H = ec: K·v³ + 3u0·K·v² + (3H_x + 3u0²·K)·v − |G − A0|·cos(α/2), K = (k, m)·H.
    cdef double big_k = s.k * ec.x + s.m * ec.y
    cdef double c[4]
    c[3] = big_k
    c[2] = 3.0 * u0 * big_k
    c[1] = 3.0 * ec.x + 3.0 * u0 * u0 * big_k
    c[0] = -join_distance * cos_half_a
    # Newton starts where G projects on the chord, as a fraction of h.
    cdef double t = u0 + polynomial_root(c, 3, 0.0, h, h * (-c[0] / chord_length),
                                         SPLIT_FIXED_ITERATIONS)
    cdef double d = t - u0
    cdef double sigma = t * t + t * u0 + a.w
    cdef double gx = d * (3.0 + s.k * sigma) - join.x, gy = d * s.m * sigma - join.y
    cdef double at_t = sqrt(gx * gx + gy * gy)  # ‖Q(t) − G‖

    cdef Peak peak0 = side_peak(s, alpha4, a, u0, t, radius0, at_t, t)
    cdef Peak peak1 = side_peak(s, alpha4, b, t, u1, radius1, at_t, t)
    cdef Vec g = vec(a.q.x + join.x, a.q.y + join.y)
    arc0.x0, arc0.y0, arc0.x1, arc0.y1 = a.q.x, a.q.y, g.x, g.y
    arc0.tx, arc0.ty, arc0.radius = a.e.x, a.e.y, radius0
    arc0.sweep = 2.0 * atan2(sin_half_a, cos_half_a)
    arc0.u0, arc0.u1, arc0.dev, arc0.u_dev = u0, t, peak0.value, peak0.u
    arc1.x0, arc1.y0, arc1.x1, arc1.y1 = g.x, g.y, b.q.x, b.q.y
    arc1.tx, arc1.ty, arc1.radius = ec.x, ec.y, radius1
    arc1.sweep = 2.0 * atan2(sin_half_b, cos_half_b)
    arc1.u0, arc1.u1, arc1.dev, arc1.u_dev = t, u1, peak1.value, peak1.u
    return peak0 if peak0.value >= peak1.value else peak1


cdef Status subdivide(
    Canonical s, double tolerance, int max_arcs, vector[Arc]* arcs
) noexcept nogil:
    """``ApproxCubicSpiral`` (§5) over ``[0, 1]``: the kept biarcs' arcs, appended in order.

    Stops with ``SEGMENT_LIMIT`` as soon as the arcs kept plus two for each piece still
    pending exceed ``max_arcs``, and with ``STUCK`` when a piece is too short to split.
    """
    cdef double alpha4 = s.k * s.k + s.m * s.m
    # The ends of the pieces not yet looked at, the leftmost piece's on top.
    cdef vector[End] ends
    ends.push_back(end_at(s, 1.0))
    ends.push_back(end_at(s, 0.0))
    cdef size_t kept = 0
    cdef End a, b
    cdef Arc arc0, arc1
    cdef Peak peak
    while ends.size() >= 2:
        a = ends.back()
        ends.pop_back()
        b = ends.back()
        peak = incentre_biarc(s, alpha4, &a, &b, &arc0, &arc1)
        if peak.value > tolerance:
            if min(peak.u - a.u, b.u - peak.u) <= STUCK_ULPS * EPS * b.u:
                return STUCK
            ends.push_back(end_at(s, peak.u))
            ends.push_back(a)
            if 2 * (kept + ends.size() - 1) > <size_t>max_arcs:
                return SEGMENT_LIMIT
        else:
            arcs.push_back(arc0)
            arcs.push_back(arc1)
            kept += 1
    return OK


def fit_many(frames, tolerances, int max_segments, double min_relative_tolerance):
    """Strategy ``subdivide`` for a batch of spirals (``fit/batch.pyx`` documents the table
    and results)."""
    return batch.run(frames, tolerances, max_segments, min_relative_tolerance, subdivide)
