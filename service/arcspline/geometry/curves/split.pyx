# cython: language_level=3, boundscheck=False, wraparound=False, cdivision=True
"""A path's segments cut into pieces the kernels fit (docs/method.md §11 "General curves").

Each smooth segment is cut where the Walton–Meek theorems need it (monotone curvature of one
sign, a bounded turn): a Bézier curve at its inflections and cusps (roots of ``B'×B''``), its
curvature extrema (roots of ``(B'×B''')·|B'|² − 3(B'×B'')(B'·B'')``, a quintic for a cubic) and
wherever its tangent has turned by ``MAX_TURN_RAD`` since the last cut; an elliptical arc at its
vertices. Each piece becomes one row of the frame table (``fit/batch.pyx``): the similarity
to its local frame (start at the origin, leaving along +x, turning left, chord 1) and its
coefficients there (``curves/piece.pxd``). Cut points are computed once, so consecutive
pieces share their end points bit for bit; a segment's first and last piece start and end at
its own stored end points.

The cuts serve the fitting, not the guarantee: every arc's deviation is certified on its piece
whatever the piece (``deviation.pyx``).
"""

from libc.float cimport DBL_EPSILON
from libc.math cimport M_PI, atan2, ceil, cos, fabs, hypot, sin, tan
from libcpp.vector cimport vector

import numpy as np

from arcspline.geometry.fit.batch import FRAME_FIELDS, PIECE_KINDS
from arcspline.geometry.maths.poly cimport MAX_COEFFS, add_product, roots_in
from arcspline.geometry.maths.vec cimport Vec, cross, dot, norm, vec

SEGMENT_FIELDS = (
    "kind", "x0", "y0", "x1", "y1", "x2", "y2", "x3", "y3", "cx", "cy", "rx", "ry",
    "rotation_rad", "start_angle_rad", "sweep_rad", "coordinate_scale",
)
cdef enum:  # SegmentField
    KIND, X0, Y0, X1, Y1, X2, Y2, X3, Y3, CX, CY, RX, RY, ROTATION, START_ANGLE, SWEEP
    COORDINATES, SEGMENT_WIDTH

#: Segment kinds of the segment table.
SEGMENT_KINDS = {"line": 0, "quadratic": 1, "cubic": 2, "arc": 3, "elliptical_arc": 4}
cdef enum:  # SegmentKind
    LINE = 0
    QUADRATIC = 1
    CUBIC = 2
    CIRCULAR = 3
    ELLIPTICAL = 4

#: Per piece: its segment, the segment parameters ``t0``, ``t1`` it spans, and, for a piece
#: of an arc, half the angle it spans (the local parameter ``u`` maps to ``t`` through it;
#: 0 for a linear map).
PIECE_FIELDS = ("segment", "t0", "t1", "half_angle_rad")

cdef extern from *:
    """
    /* A piece's tangent turns by at most this much (the paper's spirals turn by less than a
       right angle). */
    #define ARCSPLINE_MAX_TURN_RAD (0.5 * M_PI)
    /* Cut points closer than this (in t) to an end or to each other are merged. */
    #define ARCSPLINE_CUT_SEPARATION 1e-9
    /* Cuts whose points are closer than this (of the curve's size) are one cut. */
    #define ARCSPLINE_CLUSTER_CHORD 1e-12
    /* Curvature extrema closer than this (in t) to an inflection or cusp are not cut. */
    #define ARCSPLINE_CUSP_SEPARATION 1e-6
    /* Vertices of an ellipse closer than this (rad) to an end of its arc are not cut. */
    #define ARCSPLINE_CUT_ANGLE 1e-9
    /* A Bézier curve whose B'×B'' is below this fraction of |B'|·|B''| is straight. */
    #define ARCSPLINE_STRAIGHT_RTOL 1e-13
    """
    const double MAX_TURN_RAD "ARCSPLINE_MAX_TURN_RAD"
    const double CUT_SEPARATION "ARCSPLINE_CUT_SEPARATION"
    const double CUSP_SEPARATION "ARCSPLINE_CUSP_SEPARATION"
    const double CLUSTER_CHORD "ARCSPLINE_CLUSTER_CHORD"
    const double CUT_ANGLE "ARCSPLINE_CUT_ANGLE"
    const double STRAIGHT_RTOL "ARCSPLINE_STRAIGHT_RTOL"

cdef enum:
    FRAME_WIDTH = 19
    TURN_SAMPLES = 16
    MAX_CUTS = 64

assert len(FRAME_FIELDS) == FRAME_WIDTH
cdef int FIT = PIECE_KINDS["fit"], LINE_PIECE = PIECE_KINDS["line"], ARC = PIECE_KINDS["arc"]


cdef struct Row:
    double frame[FRAME_WIDTH]
    double segment
    double t0
    double t1
    double half_angle


cdef struct Bezier:
    # B(t) = p0 + c1·t + c2·t² + c3·t³ (world), its end point as stored, and B'(1) and
    # B''(1)/2 from the control points (exactly 0 where the last two coincide).
    Vec p0
    Vec c1
    Vec c2
    Vec c3
    Vec end
    Vec e1
    Vec e2


cdef inline Vec bezier_point(const Bezier* b, double t) noexcept nogil:
    if t == 0.0:
        return b.p0
    if t == 1.0:
        return b.end
    return vec(b.p0.x + t * (b.c1.x + t * (b.c2.x + t * b.c3.x)),
               b.p0.y + t * (b.c1.y + t * (b.c2.y + t * b.c3.y)))


cdef inline Vec bezier_derivative(const Bezier* b, double t) noexcept nogil:
    """``B'(t)``, expanded about the nearer end: its error is then relative to the distance
    from that end, and a speed that vanishes at an end (coincident control points) stays
    accurate beside it."""
    cdef double s
    if t <= 0.5:
        return vec(b.c1.x + t * (2.0 * b.c2.x + 3.0 * t * b.c3.x),
                   b.c1.y + t * (2.0 * b.c2.y + 3.0 * t * b.c3.y))
    s = t - 1.0
    return vec(b.e1.x + s * (2.0 * b.e2.x + 3.0 * s * b.c3.x),
               b.e1.y + s * (2.0 * b.e2.y + 3.0 * s * b.c3.y))


cdef inline Vec bezier_half_second(const Bezier* b, double t) noexcept nogil:
    """``B''(t)/2``, expanded about the nearer end."""
    if t <= 0.5:
        return vec(b.c2.x + 3.0 * t * b.c3.x, b.c2.y + 3.0 * t * b.c3.y)
    return vec(b.e2.x + 3.0 * (t - 1.0) * b.c3.x, b.e2.y + 3.0 * (t - 1.0) * b.c3.y)


cdef inline Vec bezier_direction(const Bezier* b, double t, double side) noexcept nogil:
    """The tangent direction at ``t`` seen from the side ``side`` (+1 after, −1 before):
    ``B'``, or where it vanishes (to rounding) ``±B''``, or ``B'''``."""
    cdef Vec d = bezier_derivative(b, t)
    # Zero to rounding (a cusp or turning point): its sign is noise.
    cdef double noise = 64.0 * DBL_EPSILON * (norm(b.c1) + 2.0 * norm(b.c2) + 3.0 * norm(b.c3))
    if norm(d) > noise:
        return d
    d = bezier_half_second(b, t)
    d = vec(side * d.x, side * d.y)
    if d.x != 0.0 or d.y != 0.0:
        return d
    return b.c3


cdef inline double turn_between(const Bezier* b, double ta, double tb) noexcept nogil:
    """The signed angle the tangent turns through over ``[ta, tb]`` (sampled and unwrapped:
    between cuts it turns monotonically)."""
    cdef Vec prev = bezier_direction(b, ta, 1.0), d
    cdef double total = 0.0
    cdef int i
    for i in range(1, TURN_SAMPLES + 1):
        d = bezier_direction(
            b, ta + (tb - ta) * i / TURN_SAMPLES, -1.0 if i == TURN_SAMPLES else 1.0
        )
        total += atan2(cross(prev, d), dot(prev, d))
        prev = d
    return total


cdef inline void set_frame(
    Row* row, Vec origin, Vec end, Vec direction, double mirror, double coordinates,
    Vec a1, Vec a2, Vec a3, double w1, double w2, int kind
) noexcept nogil:
    """The frame row of a piece from ``origin`` to ``end`` leaving along ``direction``, with
    world coefficient vectors ``a1..a3`` (of ``X − origin·W``) and weights ``w1, w2``."""
    cdef double n = norm(direction)
    cdef double c = direction.x / n, s = direction.y / n
    cdef double chord = hypot(end.x - origin.x, end.y - origin.y)
    cdef double* f = row.frame
    f[0], f[1], f[2], f[3], f[4], f[5] = origin.x, origin.y, c, s, chord, mirror
    f[6], f[7], f[8], f[9] = end.x, end.y, chord, coordinates
    # Local = mirror_y(R(−φ)·v) / chord.
    f[10] = (c * a1.x + s * a1.y) / chord
    f[11] = (c * a2.x + s * a2.y) / chord
    f[12] = (c * a3.x + s * a3.y) / chord
    f[13] = mirror * (c * a1.y - s * a1.x) / chord
    f[14] = mirror * (c * a2.y - s * a2.x) / chord
    f[15] = mirror * (c * a3.y - s * a3.x) / chord
    f[16], f[17], f[18] = w1, w2, <double>kind


cdef inline void stop_at_end(Row* row) noexcept nogil:
    """Make the local speed at ``u = 1`` exactly 0, as it is (a cusp, coincident last control
    points): the frame's rounding, of the coordinates' size, would otherwise leave a speed of
    noise there whose direction is arbitrary. ``x1`` takes up the difference, or ``x2`` where
    the piece also starts at rest (``x1 = 0``); the change is within that rounding."""
    cdef double* f = row.frame
    cdef int k
    for k in range(2):  # x, then y: coefficients at f[10 + 3k .. 12 + 3k]
        if f[10 + 3 * k] != 0.0:
            f[10 + 3 * k] = -(2.0 * f[11 + 3 * k] + 3.0 * f[12 + 3 * k])
        else:
            f[11 + 3 * k] = -1.5 * f[12 + 3 * k]


cdef int bezier_cuts(const Bezier* b, bint extrema, double* cuts) noexcept nogil:
    """The sorted cut parameters in ``(0, 1)`` of a curved Bézier segment; their number."""
    cdef double d[3][2]
    cdef double dd[2][2]
    d[0][0], d[0][1] = b.c1.x, b.c1.y
    d[1][0], d[1][1] = 2.0 * b.c2.x, 2.0 * b.c2.y
    d[2][0], d[2][1] = 3.0 * b.c3.x, 3.0 * b.c3.y
    dd[0][0], dd[0][1] = 2.0 * b.c2.x, 2.0 * b.c2.y
    dd[1][0], dd[1][1] = 6.0 * b.c3.x, 6.0 * b.c3.y
    cdef double inflect[MAX_COEFFS]
    cdef double dot_dd[MAX_COEFFS]
    cdef double speed2[MAX_COEFFS]
    cdef double cross_ddd[MAX_COEFFS]
    cdef double curvature[MAX_COEFFS]
    cdef int i, j
    for i in range(MAX_COEFFS):
        inflect[i] = dot_dd[i] = speed2[i] = cross_ddd[i] = curvature[i] = 0.0
    for i in range(3):
        for j in range(2):
            inflect[i + j] += d[i][0] * dd[j][1] - d[i][1] * dd[j][0]
            dot_dd[i + j] += d[i][0] * dd[j][0] + d[i][1] * dd[j][1]
        for j in range(3):
            speed2[i + j] += d[i][0] * d[j][0] + d[i][1] * d[j][1]
        cross_ddd[i] = d[i][0] * dd[1][1] - d[i][1] * dd[1][0]
    # κ' ∝ (B'×B''')·|B'|² − 3·(B'×B'')·(B'·B'')
    add_product(1.0, cross_ddd, 2, speed2, 4, curvature)
    add_product(-3.0, inflect, 2, dot_dd, 3, curvature)
    cdef double found[MAX_COEFFS * 2]
    cdef double peaks[MAX_COEFFS]
    cdef int n = roots_in(inflect, 2, 0.0, 1.0, found), inflections = n, p, q
    cdef bint near
    if extrema:
        # A curvature extremum this close to an inflection or cusp is the singularity's
        # rounding (curvature is unbounded at a cusp), not a cut of its own.
        for p in range(roots_in(curvature, 6, 0.0, 1.0, peaks)):
            near = False
            for q in range(inflections):
                near = near or fabs(peaks[p] - found[q]) < CUSP_SEPARATION
            if not near:
                found[n] = peaks[p]
                n += 1
    # Sort (a handful) and merge near repeats.
    cdef double x
    for i in range(1, n):
        x = found[i]
        j = i - 1
        while j >= 0 and found[j] > x:
            found[j + 1] = found[j]
            j -= 1
        found[j + 1] = x
    cdef int count = 0
    cdef double last = 0.0
    for i in range(n):
        if found[i] - last > CUT_SEPARATION and 1.0 - found[i] > CUT_SEPARATION:
            cuts[count] = found[i]
            last = found[i]
            count += 1
    return count


cdef int turn_cuts(
    const Bezier* b, double ta, double tb, double max_turn, double* cuts
) noexcept nogil:
    """Cuts inside ``(ta, tb)`` where the tangent has turned by equal parts of at most
    ``MAX_TURN_RAD``: roots of ``B'(t)×d_j`` with ``B'·d_j > 0``, ``d_j`` the target
    directions; their number."""
    cdef double turn = turn_between(b, ta, tb)
    cdef int parts = <int>ceil(fabs(turn) / max_turn), j, k, n, count = 0
    if parts <= 1:
        return 0
    parts = min(parts, 8)
    cdef Vec d0 = bezier_direction(b, ta, 1.0), dj, at
    cdef double phi0 = atan2(d0.y, d0.x), phi, last = ta
    cdef double c[MAX_COEFFS]
    cdef double found[MAX_COEFFS]
    for j in range(1, parts):
        phi = phi0 + turn * j / parts
        dj = vec(cos(phi), sin(phi))
        # B'(t)×d_j, a quadratic
        c[0] = b.c1.x * dj.y - b.c1.y * dj.x
        c[1] = 2.0 * (b.c2.x * dj.y - b.c2.y * dj.x)
        c[2] = 3.0 * (b.c3.x * dj.y - b.c3.y * dj.x)
        n = roots_in(c, 2, last, tb, found)
        for k in range(n):
            at = bezier_derivative(b, found[k])
            if (dot(at, dj) > 0.0 and found[k] - last > CUT_SEPARATION
                    and tb - found[k] > CUT_SEPARATION):
                cuts[count] = found[k]
                last = found[k]
                count += 1
                break
    return count


cdef int merge_clusters(const Bezier* unit, double* ts, int n) noexcept nogil:
    """Cuts whose points lie within ``CLUSTER_CHORD`` (of the curve's size) of each other
    become one: the member where the speed is least — at a cusp, the roots of ``B'×B''`` and
    of the curvature's derivative come in clusters around it. The ends stay the ends. The
    new number of entries of ``ts`` (ascending, ``ts[0] = 0``, ``ts[n − 1] = 1``)."""
    cdef int i = 1, m = 1, j, best
    cdef Vec p, q
    while i < n - 1:
        j, best = i, i
        p = bezier_point(unit, ts[i])
        while j + 1 < n:
            q = bezier_point(unit, ts[j + 1])
            if hypot(q.x - p.x, q.y - p.y) > CLUSTER_CHORD:
                break
            j += 1
            if j < n - 1 and norm(bezier_derivative(unit, ts[j])) < norm(
                bezier_derivative(unit, ts[best])
            ):
                best = j
            p = q
        q = bezier_point(unit, ts[m - 1])
        p = bezier_point(unit, ts[best])
        if j < n - 1 and hypot(q.x - p.x, q.y - p.y) > CLUSTER_CHORD:
            ts[m] = ts[best]  # a cluster clear of the end before it and of the last end
            m += 1
        i = j + 1
    ts[m] = 1.0
    return m + 1


cdef void bezier_pieces(
    const Bezier* b, int segment, double coordinates, bint extrema, double max_turn,
    vector[Row]* rows
) noexcept nogil:
    cdef double ts[MAX_CUTS + 2]
    cdef double cuts[MAX_CUTS]
    cdef double more[8]
    cdef int n = 0, i, k, m
    cdef double size = max(max(norm(b.c1), norm(b.c2)), norm(b.c3))
    if size == 0.0:
        return  # a single point: nothing to cut
    # The cuts are found on the curve scaled to size 1 (they do not change with scale, and
    # the curvature polynomial, of degree 5 in the coordinates, would overflow or underflow
    # for coordinates far from 1).
    cdef Bezier unit
    unit.p0 = vec(0.0, 0.0)
    unit.c1 = vec(b.c1.x / size, b.c1.y / size)
    unit.c2 = vec(b.c2.x / size, b.c2.y / size)
    unit.c3 = vec(b.c3.x / size, b.c3.y / size)
    unit.end = vec((b.end.x - b.p0.x) / size, (b.end.y - b.p0.y) / size)
    unit.e1 = vec(b.e1.x / size, b.e1.y / size)
    unit.e2 = vec(b.e2.x / size, b.e2.y / size)
    # Straight: |B'×B''| negligible against |B'|·|B''| everywhere. Cut where it turns back.
    cdef double span_d = norm(unit.c1) + 2.0 * norm(unit.c2) + 3.0 * norm(unit.c3)
    cdef double span_dd = 2.0 * norm(unit.c2) + 6.0 * norm(unit.c3)
    cdef double bend = (fabs(cross(unit.c1, unit.c2)) + fabs(cross(unit.c1, unit.c3))
                        + fabs(cross(unit.c2, unit.c3)))
    cdef bint straight = bend <= STRAIGHT_RTOL * span_d * span_dd
    cdef double c[MAX_COEFFS]
    cdef Vec axis
    ts[0] = 0.0
    n = 1
    if straight:
        axis = unit.end
        if axis.x == 0.0 and axis.y == 0.0:
            axis = unit.c1 if norm(unit.c1) > 0.0 else (unit.c2 if norm(unit.c2) > 0.0 else unit.c3)
        c[0] = dot(unit.c1, axis)
        c[1] = 2.0 * dot(unit.c2, axis)
        c[2] = 3.0 * dot(unit.c3, axis)
        m = roots_in(c, 2, 0.0, 1.0, cuts)
        for i in range(m):
            if cuts[i] - ts[n - 1] > CUT_SEPARATION and 1.0 - cuts[i] > CUT_SEPARATION:
                ts[n] = cuts[i]
                n += 1
    else:
        m = bezier_cuts(&unit, extrema, cuts)
        for i in range(m + 1):
            k = turn_cuts(&unit, ts[n - 1], cuts[i] if i < m else 1.0, max_turn, more)
            for j in range(k):
                if n < MAX_CUTS:
                    ts[n] = more[j]
                    n += 1
            if i < m and n < MAX_CUTS:
                ts[n] = cuts[i]
                n += 1
    ts[n] = 1.0
    n += 1
    n = merge_clusters(&unit, ts, n)
    cdef Vec start = b.p0, end, a1, a2, a3, d1, d2
    cdef double ta, tb, h, turn, mirror
    cdef double noise = 64.0 * DBL_EPSILON * size * span_d
    cdef Row row
    for i in range(n - 1):
        ta, tb = ts[i], ts[i + 1]
        end = bezier_point(b, tb)
        h = tb - ta
        d1 = bezier_derivative(b, ta)
        if norm(d1) <= noise:
            d1 = vec(0.0, 0.0)  # cut at a cusp or turning point: the speed there is 0
        a1 = vec(h * d1.x, h * d1.y)
        d2 = bezier_half_second(b, ta)
        a2 = vec(h * h * d2.x, h * h * d2.y)
        a3 = vec(h * h * h * b.c3.x, h * h * h * b.c3.y)
        if end.x == start.x and end.y == start.y:
            continue  # nothing to fit: a piece that ends where it starts (a point)
        turn = 0.0 if straight else turn_between(b, ta, tb)
        mirror = -1.0 if turn < 0.0 else 1.0
        set_frame(&row, start, end, bezier_direction(b, ta, 1.0), mirror, coordinates,
                  a1, a2, a3, 0.0, 0.0, FIT)
        if norm(bezier_derivative(b, tb)) <= noise:
            stop_at_end(&row)
        row.segment, row.t0, row.t1, row.half_angle = segment, ta, tb, 0.0
        rows.push_back(row)
        start = end


cdef void conic_pieces(
    const double* seg, int segment, bint circular, vector[Row]* rows
) noexcept nogil:
    """An elliptical (or circular) arc cut at its vertices (or into quarter turns), each piece
    a rational quadratic: with ``φ`` running over ``[φa, φb]``, ``h = (φb − φa)/2`` and
    ``m = (φa + φb)/2``, the control point ``P1 = E(m)/cos h`` (about the centre) with weight
    ``cos h`` gives the arc exactly; ``u`` maps to ``φ = m + 2·atan(tan(h/2)·(2u − 1))``."""
    cdef double rot = seg[ROTATION], a0 = seg[START_ANGLE], sweep = seg[SWEEP]
    cdef Vec ax = vec(seg[RX] * cos(rot), seg[RX] * sin(rot))
    cdef Vec bx = vec(-seg[RY] * sin(rot), seg[RY] * cos(rot))
    cdef Vec centre = vec(seg[CX], seg[CY])
    cdef double phis[8]
    cdef int n = 0, i, parts
    cdef double q, first, last_phi = a0 + sweep, direction = 1.0 if sweep > 0.0 else -1.0
    phis[0] = a0
    n = 1
    if circular:
        parts = <int>ceil(fabs(sweep) / MAX_TURN_RAD - 1e-12)
        for i in range(1, parts):
            phis[n] = a0 + sweep * i / parts
            n += 1
    else:
        # Vertices: multiples of π/2 strictly inside.
        q = a0 / (0.5 * M_PI)
        first = ceil(q) if direction > 0.0 else ceil(q) - 1.0
        while n < 7:
            phis[n] = first * 0.5 * M_PI
            if direction * (last_phi - phis[n]) <= CUT_ANGLE:
                break
            if direction * (phis[n] - a0) > CUT_ANGLE:
                n += 1  # a vertex within a hair of the start is the start
            first += direction
    phis[n] = last_phi
    n += 1
    cdef Vec start = vec(seg[X0], seg[Y0]), end, p1, p2, tangent
    cdef double pa, pb, h, m, w1, sh, ch, sm, cm, t
    cdef Row row
    for i in range(n - 1):
        pa, pb = phis[i], phis[i + 1]
        h, m = 0.5 * (pb - pa), 0.5 * (pa + pb)
        sh, ch, sm, cm = sin(h), cos(h), sin(m), cos(m)
        if i == n - 2:
            end = vec(seg[X3], seg[Y3])
        else:
            end = vec(centre.x + ax.x * cos(pb) + bx.x * sin(pb),
                      centre.y + ax.y * cos(pb) + bx.y * sin(pb))
        # P1 − P0 = sin h·(A·(cos m·tan h − sin m) + B·(sin m·tan h + cos m))
        t = tan(h)
        p1 = vec(sh * (ax.x * (cm * t - sm) + bx.x * (sm * t + cm)),
                 sh * (ax.y * (cm * t - sm) + bx.y * (sm * t + cm)))
        # P2 − P0 = 2 sin h·(−A sin m + B cos m)
        p2 = vec(2.0 * sh * (-ax.x * sm + bx.x * cm), 2.0 * sh * (-ax.y * sm + bx.y * cm))
        w1 = ch
        tangent = vec(direction * (-ax.x * sin(pa) + bx.x * cos(pa)),
                      direction * (-ax.y * sin(pa) + bx.y * cos(pa)))
        set_frame(&row, start, end, tangent, direction, seg[COORDINATES],
                  vec(2.0 * w1 * p1.x, 2.0 * w1 * p1.y),
                  vec(p2.x - 2.0 * w1 * p1.x, p2.y - 2.0 * w1 * p1.y), vec(0.0, 0.0),
                  2.0 * (w1 - 1.0), 2.0 - 2.0 * w1, ARC if circular else FIT)
        row.segment = segment
        # The segment's own ends exactly: (φ − a0)/sweep need not round to 0 and 1 there.
        row.t0 = 0.0 if i == 0 else (pa - a0) / sweep
        row.t1 = 1.0 if i == n - 2 else (pb - a0) / sweep
        row.half_angle = fabs(h)
        rows.push_back(row)
        start = end


def split(
    segments, long long max_pieces, bint extrema=True, double max_turn_rad=0.5 * M_PI
):
    """The frame table and piece table (``PIECE_FIELDS``) of the segments (rows of
    ``SEGMENT_FIELDS``), in order; ``None`` in place of both if there would be more than
    ``max_pieces`` pieces."""
    cdef const double[:, ::1] table = segments
    if table.shape[1] != SEGMENT_WIDTH:
        raise ValueError(f"segments must have {SEGMENT_WIDTH} columns")
    cdef vector[Row] rows
    cdef Py_ssize_t i
    cdef const double* seg
    cdef Bezier b
    cdef int kind
    cdef Row row
    cdef Vec start, end
    with nogil:
        for i in range(table.shape[0]):
            seg = &table[i, 0]
            kind = <int>seg[KIND]
            start, end = vec(seg[X0], seg[Y0]), vec(seg[X3], seg[Y3])
            if kind == LINE:
                if start.x != end.x or start.y != end.y:
                    set_frame(&row, start, end, vec(end.x - start.x, end.y - start.y), 1.0,
                              seg[COORDINATES], vec(end.x - start.x, end.y - start.y),
                              vec(0.0, 0.0), vec(0.0, 0.0), 0.0, 0.0, LINE_PIECE)
                    row.segment, row.t0, row.t1, row.half_angle = i, 0.0, 1.0, 0.0
                    rows.push_back(row)
            elif kind == QUADRATIC or kind == CUBIC:
                b.p0, b.end = start, end
                if kind == QUADRATIC:
                    b.c1 = vec(2.0 * (seg[X1] - start.x), 2.0 * (seg[Y1] - start.y))
                    b.c2 = vec(start.x - 2.0 * seg[X1] + end.x, start.y - 2.0 * seg[Y1] + end.y)
                    b.c3 = vec(0.0, 0.0)
                    b.e1 = vec(2.0 * (end.x - seg[X1]), 2.0 * (end.y - seg[Y1]))
                    b.e2 = b.c2
                else:
                    b.c1 = vec(3.0 * (seg[X1] - start.x), 3.0 * (seg[Y1] - start.y))
                    b.c2 = vec(3.0 * (seg[X2] - 2.0 * seg[X1] + start.x),
                               3.0 * (seg[Y2] - 2.0 * seg[Y1] + start.y))
                    b.c3 = vec(end.x - 3.0 * seg[X2] + 3.0 * seg[X1] - start.x,
                               end.y - 3.0 * seg[Y2] + 3.0 * seg[Y1] - start.y)
                    b.e1 = vec(3.0 * (end.x - seg[X2]), 3.0 * (end.y - seg[Y2]))
                    b.e2 = vec(3.0 * (end.x - 2.0 * seg[X2] + seg[X1]),
                               3.0 * (end.y - 2.0 * seg[Y2] + seg[Y1]))
                bezier_pieces(&b, i, seg[COORDINATES], extrema, max_turn_rad, &rows)
            elif kind == CIRCULAR or kind == ELLIPTICAL:
                if seg[SWEEP] != 0.0:
                    conic_pieces(seg, i, kind == CIRCULAR, &rows)
            if <long long>rows.size() > max_pieces:
                break
    if <long long>rows.size() > max_pieces:
        return None, None
    cdef Py_ssize_t m = rows.size(), j
    frames = np.empty((m, FRAME_WIDTH))
    pieces = np.empty((m, 4))
    cdef double[:, ::1] f = frames
    cdef double[:, ::1] p = pieces
    for i in range(m):
        for j in range(FRAME_WIDTH):
            f[i, j] = rows[i].frame[j]
        p[i, 0], p[i, 1], p[i, 2], p[i, 3] = (
            rows[i].segment, rows[i].t0, rows[i].t1, rows[i].half_angle
        )
    return frames, pieces
