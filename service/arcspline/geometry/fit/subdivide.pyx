# cython: language_level=3, boundscheck=False, wraparound=False, cdivision=True
"""Strategy ``subdivide``: Walton & Meek's recursive subdivision (docs/method.md §3–§5).

The incentre biarc of a piece ``[u0, u1]`` of the curve piece is kept when its exact largest
deviation δ (``deviation.pyx``, which for the paper's spiral gives what Theorems 1 and 2 give)
is within the tolerance; otherwise the piece is split at ``u_d``, where δ occurs. The
recursion runs depth first on an explicit stack, so the kept biarcs come out in parameter
order.
"""

from libc.float cimport DBL_EPSILON as EPS
from libc.math cimport INFINITY, atan2, sqrt
from libcpp.vector cimport vector

from arcspline.geometry.curves.piece cimport Piece, offset, point, unit_tangent
from arcspline.geometry.deviation cimport Peak, arc_deviation, joint_split
from arcspline.geometry.fit.arcs cimport OK, STUCK, SEGMENT_LIMIT, Arc, Status
from arcspline.geometry.fit cimport batch
from arcspline.geometry.maths.vec cimport Vec, cross, dot, norm, vec

cdef extern from *:
    """
    /* A piece whose split point lies within this many ulps (of its end) of either end
       cannot be split any further in double precision. */
    #define ARCSPLINE_STUCK_ULPS 4.0
    """
    const double STUCK_ULPS "ARCSPLINE_STUCK_ULPS"


cdef struct End:
    # What a piece needs of one of its ends: computed once per split point for both pieces
    # that share it.
    double u
    Vec e         # the unit tangent
    Vec q         # Q(u)


cdef inline End end_at(const Piece* p, double u) noexcept nogil:
    cdef End end
    end.u = u
    end.e = unit_tangent(p, u)
    end.q = point(p, u)
    return end


cdef inline Peak incentre_biarc(
    const Piece* p, End* a, End* b, Arc* arc0, Arc* arc1
) noexcept nogil:
    """The incentre biarc of the piece from ``a`` to ``b`` (§2) as two arcs, each with its
    exact largest deviation (§3–§4, §10); the piece's δ and ``u_d``.

    With the chord's length ``L``, the angles ``α`` (from the tangent at ``A0`` to the chord)
    and ``β`` (from the chord to the tangent at ``A1``) and ``S = sin((α + β)/2)``, the law of
    sines in ``(A0, G, A1)`` gives ``|G − A0| = L·sin(β/2)/S`` and the radii
    ``r0 = |G − A0|/(2 sin(α/2))``, ``r1 = L·sin(α/2)/(2 S sin(β/2))``, without forming ``V``.
    The chord is the factored difference ``Q(u1) − Q(u0)``; half angles come from the
    half-angle formulas. Theorem 1's split ``t`` is where the piece crosses the normal line at
    ``G`` (:func:`~arcspline.geometry.deviation.joint_split`).
    """
    cdef Vec chord = offset(p, a.u, b.u)
    cdef double chord_length = norm(chord)
    cdef Vec ec = vec(chord.x / chord_length, chord.y / chord_length)
    cdef double cos_half_a = sqrt(0.5 + 0.5 * dot(a.e, ec))
    cdef double cos_half_b = sqrt(0.5 + 0.5 * dot(ec, b.e))
    cdef double sin_half_a = cross(a.e, ec) / (2.0 * cos_half_a)
    cdef double sin_half_b = cross(ec, b.e) / (2.0 * cos_half_b)
    cdef double chord_over_s, join_distance, along, kappa0, kappa1
    cdef Vec g
    cdef Vec t0 = a.e, t1 = ec
    if sin_half_a > 0.0 and sin_half_b > 0.0:
        chord_over_s = chord_length / (sin_half_a * cos_half_b + cos_half_a * sin_half_b)
        join_distance = chord_over_s * sin_half_b
        # G − A0 along the bisector of α, (e0 + ec)/(2·cos(α/2))
        along = join_distance / (2.0 * cos_half_a)
        g = vec(a.q.x + along * (a.e.x + ec.x), a.q.y + along * (a.e.y + ec.y))
        kappa0 = 2.0 * sin_half_a / join_distance
        kappa1 = 2.0 * sin_half_b / (chord_over_s * sin_half_a)
    else:
        # Straight to rounding (or turning the wrong way): the chord, in two halves, measured
        # exactly as such.
        sin_half_a = sin_half_b = 0.0
        cos_half_a = cos_half_b = 1.0
        g = vec(a.q.x + 0.5 * chord.x, a.q.y + 0.5 * chord.y)
        kappa0 = kappa1 = 0.0
        t0 = ec
    cdef double t = joint_split(p, g, ec.x, ec.y)
    cdef Peak peak0, peak1
    if t > a.u and t < b.u:
        peak0 = arc_deviation(p, a.q, t0.x, t0.y, kappa0, g, a.u, t, 0.0)
        peak1 = arc_deviation(p, g, t1.x, t1.y, kappa1, b.q, t, b.u, 0.0)
    else:
        t = 0.5 * (a.u + b.u)
        peak0.value, peak1.value = INFINITY, INFINITY
    # A refused arc (not a polar graph over its piece, or no split inside): split the piece
    # in the middle.
    if not peak0.value < INFINITY:
        peak0.value, peak0.u = INFINITY, 0.5 * (a.u + b.u)
    if not peak1.value < INFINITY:
        peak1.value, peak1.u = INFINITY, 0.5 * (a.u + b.u)
    arc0.x0, arc0.y0, arc0.x1, arc0.y1 = a.q.x, a.q.y, g.x, g.y
    arc0.tx, arc0.ty, arc0.radius = a.e.x, a.e.y, 1.0 / kappa0 if kappa0 > 0.0 else INFINITY
    arc0.sweep = 2.0 * atan2(sin_half_a, cos_half_a)
    arc0.u0, arc0.u1, arc0.dev, arc0.u_dev = a.u, t, peak0.value, peak0.u
    arc1.x0, arc1.y0, arc1.x1, arc1.y1 = g.x, g.y, b.q.x, b.q.y
    arc1.tx, arc1.ty, arc1.radius = ec.x, ec.y, 1.0 / kappa1 if kappa1 > 0.0 else INFINITY
    arc1.sweep = 2.0 * atan2(sin_half_b, cos_half_b)
    arc1.u0, arc1.u1, arc1.dev, arc1.u_dev = t, b.u, peak1.value, peak1.u
    return peak0 if peak0.value >= peak1.value else peak1


cdef Status subdivide(
    const Piece* p, double tolerance, int max_arcs, vector[Arc]* arcs
) noexcept nogil:
    """``ApproxCubicSpiral`` (§5) over ``[0, 1]``: the kept biarcs' arcs, appended in order.

    Stops with ``SEGMENT_LIMIT`` as soon as the arcs kept plus two for each piece still
    pending exceed ``max_arcs``, and with ``STUCK`` when a piece is too short to split.
    """
    # The ends of the pieces not yet looked at, the leftmost piece's on top.
    cdef vector[End] ends
    ends.push_back(end_at(p, 1.0))
    ends.push_back(end_at(p, 0.0))
    cdef size_t kept = 0
    cdef End a, b
    cdef Arc arc0, arc1
    cdef Peak peak
    while ends.size() >= 2:
        a = ends.back()
        ends.pop_back()
        b = ends.back()
        peak = incentre_biarc(p, &a, &b, &arc0, &arc1)
        if peak.value > tolerance:
            if min(peak.u - a.u, b.u - peak.u) <= STUCK_ULPS * EPS * b.u:
                return STUCK
            ends.push_back(end_at(p, peak.u))
            ends.push_back(a)
            if 2 * (kept + ends.size() - 1) > <size_t>max_arcs:
                return SEGMENT_LIMIT
        else:
            arcs.push_back(arc0)
            arcs.push_back(arc1)
            kept += 1
    return OK


#: Pieces must have monotone curvature of one sign (cut at curvature extrema too): the
#: paper's theorems, on which the subdivision's convergence rests, need it.
MONOTONE_PIECES = True


def fit_many(
    frames, tolerances, int max_segments, double min_relative_tolerance, bint shared=False
):
    """Strategy ``subdivide`` for a batch of pieces (``fit/batch.pyx`` documents the table
    and results)."""
    return batch.run(frames, tolerances, max_segments, min_relative_tolerance, subdivide, shared)
