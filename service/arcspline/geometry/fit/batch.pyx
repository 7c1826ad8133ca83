# cython: language_level=3, boundscheck=False, wraparound=False, cdivision=True
"""The loop every strategy shares: check each tolerance, fit the curve piece in its local
frame, map its arcs to world coordinates, measure what rounding did, and gather the statistics
(docs/method.md §8 "Assembly").

Input, one row per piece (a spiral, or a piece of a path's segment): the frame table
(``FRAME_FIELDS``: the similarity that maps the local frame onto the world, the piece's stored
end point, what the tolerance floor needs, and the piece's coefficients in its local frame,
``curves/piece.pxd``) and the tolerances. Output of :func:`run`: ``(blocks, where, stats,
status, aux)`` — the segments of every piece, one row each (``FIELDS``), in a few tables
(``blocks``), piece ``i`` owning rows ``where[i, 1]:where[i, 2]`` of
``blocks[where[i, 0]]``; per piece its statistics (``STATS_FIELDS``), its ``Status``
(``STATUS``) and, for a failure, two numbers for its message (``UNPLACEABLE``: the worst
rounding error and the largest radius). A piece's rows depend on that piece alone, whatever
else is in the batch (but for a shared segment budget).
"""

from libc.float cimport DBL_EPSILON as EPS
from libc.math cimport INFINITY, NAN, atan2, fabs, fabsl, hypot, isfinite, sin, sqrtl
from libc.stdlib cimport free, malloc
from libcpp.vector cimport vector

import numpy as np

from arcspline.geometry.curves.piece cimport Piece, arc_length, point
from arcspline.geometry.deviation cimport line_deviation
from arcspline.geometry.fit.arcs cimport (
    BAD_TOLERANCE,
    OK,
    OVERFLOW,
    SEGMENT_LIMIT,
    STUCK,
    TOLERANCE_FLOOR,
    UNPLACEABLE,
    Arc,
    FitFn,
    Status,
)
from arcspline.geometry.maths.vec cimport Vec, vec

cdef extern from *:
    """
    /* World coordinates are B0 + a·R·p: each carries a rounding error of a few ulps of the
       largest coordinate. The kernels aim below the tolerance by this many ulps of the
       piece's coordinate scale (plus chord), so the guarantee holds for the numbers handed
       out; the smallest tolerance accepted is four of these margins. */
    #define ARCSPLINE_ROUNDING_MARGIN_ULPS 32.0
    /* An arc's centre and radius round by a few ulps of |C| + r; arcs for which this many
       ulps still fit the tolerance need no measurement of it. */
    #define ARCSPLINE_PLACEMENT_SCREEN_ULPS 64.0
    /* Below this sweep an arc is numerically flat: its centre and radius carry no
       information and a controller may read it as a full circle. It becomes its chord. */
    #define ARCSPLINE_FLAT_SWEEP_RAD 1e-10
    """
    const double ROUNDING_MARGIN_ULPS "ARCSPLINE_ROUNDING_MARGIN_ULPS"
    const double PLACEMENT_SCREEN_ULPS "ARCSPLINE_PLACEMENT_SCREEN_ULPS"
    const double FLAT_SWEEP_RAD "ARCSPLINE_FLAT_SWEEP_RAD"

FRAME_FIELDS = (
    "x0", "y0", "cos_phi", "sin_phi", "scale", "mirror", "end_x", "end_y", "chord",
    "coordinate_scale", "x1", "x2", "x3", "y1", "y2", "y3", "w1", "w2", "kind",
)
cdef enum:  # FrameField
    X0, Y0, COS_PHI, SIN_PHI, SCALE, MIRROR, END_X, END_Y, CHORD, COORDINATE_SCALE
    PX1, PX2, PX3, PY1, PY2, PY3, PW1, PW2, KIND
    FRAME_WIDTH

#: What a frame row's ``kind`` asks for: a fit by the strategy, or the piece itself as one
#: line (an input line) or one arc (a piece of an input circular arc), exactly.
PIECE_KINDS = {"fit": 0, "line": 1, "arc": 2}
cdef enum:  # PieceKind
    FIT_PIECE = 0
    LINE_PIECE = 1
    ARC_PIECE = 2

FIELDS = (
    "is_arc", "start_x", "start_y", "end_x", "end_y", "center_x", "center_y", "radius",
    "start_angle_rad", "sweep_rad", "length", "u_start", "u_end", "max_deviation",
    "u_at_max_deviation",
)
cdef enum:  # Field
    F_IS_ARC, F_START_X, F_START_Y, F_END_X, F_END_Y, F_CENTER_X, F_CENTER_Y, F_RADIUS
    F_START_ANGLE, F_SWEEP, F_LENGTH, F_U_START, F_U_END, F_MAX_DEV, F_U_AT_MAX
    WIDTH

STATS_FIELDS = (
    "arc_count", "line_count", "max_deviation", "u_at_max_deviation",
    "mean_segment_deviation", "spiral_length", "spline_length", "min_radius", "max_radius",
)
cdef enum:  # StatsField
    S_ARCS, S_LINES, S_MAX_DEV, S_U_AT_MAX, S_MEAN_DEV, S_SPIRAL_LENGTH, S_SPLINE_LENGTH
    S_MIN_RADIUS, S_MAX_RADIUS, STATS_WIDTH

STATUS = {
    "ok": OK,
    "segment_limit": SEGMENT_LIMIT,
    "stuck": STUCK,
    "overflow": OVERFLOW,
    "unplaceable": UNPLACEABLE,
    "tolerance_floor": TOLERANCE_FLOOR,
    "bad_tolerance": BAD_TOLERANCE,
}


cdef struct Frame:
    # The similarity from the local frame: p ↦ origin + scale·R(φ)·(p_x, mirror·p_y).
    Vec origin
    double cos_phi
    double sin_phi
    double scale
    double mirror
    Vec end       # the piece's stored end point, where u = 1 maps


cdef inline Vec world_vector(const Frame* f, double x, double y) noexcept nogil:
    y = f.mirror * y
    return vec(f.scale * (f.cos_phi * x - f.sin_phi * y), f.scale * (f.sin_phi * x + f.cos_phi * y))


cdef inline Vec world_point(const Frame* f, double x, double y) noexcept nogil:
    cdef Vec v = world_vector(f, x, y)
    return vec(f.origin.x + v.x, f.origin.y + v.y)


cdef inline double world_angle(const Frame* f, double x, double y) noexcept nogil:
    """World polar angle, in (−π, π], of the local direction ``(x, y)``."""
    y = f.mirror * y
    return atan2(f.sin_phi * x + f.cos_phi * y, f.cos_phi * x - f.sin_phi * y)


cdef inline double rounding_margin(double chord, double coordinate_scale) noexcept nogil:
    return ROUNDING_MARGIN_ULPS * EPS * (coordinate_scale + chord)


cdef inline double floor_of(
    double chord, double coordinate_scale, double min_relative_tolerance
) noexcept nogil:
    return max(min_relative_tolerance * chord, 4.0 * rounding_margin(chord, coordinate_scale))


def tolerance_floor(double chord, double coordinate_scale, double min_relative_tolerance):
    """The smallest tolerance accepted for a piece of this chord and coordinate scale: the
    larger of ``min_relative_tolerance × chord`` and four rounding margins, so that at least
    three quarters of the tolerance is left for the approximation itself."""
    return floor_of(chord, coordinate_scale, min_relative_tolerance)


cdef inline double placement_error(const double* row) noexcept nogil:
    """How far rounding has moved an arc, measured: the larger of ``|‖S − C‖ − r|`` at its
    start and end, in extended precision. Centre and radius are doubles, each off by ulps of
    its own size, which for the huge radii of nearly straight pieces can exceed a tight
    tolerance; the end points lie where the method put them, so the gap shows the error."""
    cdef long double cx = row[F_CENTER_X], cy = row[F_CENTER_Y], r = row[F_RADIUS]
    cdef long double dx = row[F_START_X] - cx, dy = row[F_START_Y] - cy
    cdef long double at_start = fabsl(sqrtl(dx * dx + dy * dy) - r)
    dx, dy = row[F_END_X] - cx, row[F_END_Y] - cy
    cdef long double at_end = fabsl(sqrtl(dx * dx + dy * dy) - r)
    return <double>(at_start if at_start > at_end else at_end)


cdef bint placed(
    const double* rows, size_t n, double tolerance, double screen, double* worst
) noexcept nogil:
    """Whether every arc whose screen fails (``PLACEMENT_SCREEN_ULPS`` of ``|C| + r`` do
    not fit the tolerance beside its deviation) fits it with its measured placement error;
    if not, ``worst`` is the largest placement error of all arcs."""
    cdef const double* row
    cdef size_t i
    cdef bint ok = True
    for i in range(n):
        row = rows + i * WIDTH
        if row[F_IS_ARC] != 0.0 and row[F_MAX_DEV] + screen * (
            max(fabs(row[F_CENTER_X]), fabs(row[F_CENTER_Y])) + row[F_RADIUS]
        ) > tolerance:
            ok = ok and row[F_MAX_DEV] + placement_error(row) <= tolerance
    if not ok:
        worst[0] = 0.0
        for i in range(n):
            row = rows + i * WIDTH
            if row[F_IS_ARC] != 0.0:
                worst[0] = max(worst[0], placement_error(row))
    return ok


cdef Status assemble(
    const Piece* p, const Frame* f, vector[Arc]* arcs, double tolerance, double* rows,
    double* stats, double* aux
) noexcept nogil:
    """Write one row per arc to ``rows`` (world coordinates, ``FIELDS``) and fill ``stats``.

    ``OVERFLOW`` when a number of a row is not finite, ``UNPLACEABLE`` when an arc's rounding
    leaves the tolerance (``aux``: the worst error, the largest radius); the caller drops the
    rows then. Consecutive rows share their joint's numbers exactly (one mapping per joint);
    ``u = 0`` maps to ``B0`` and ``u = 1`` to the stored ``B3``.
    """
    cdef size_t n = arcs.size(), i
    if n == 0:
        return OVERFLOW
    cdef double* row
    cdef const Arc* arc
    cdef Vec start = world_point(f, arcs.at(0).x0, arcs.at(0).y0), end, v
    cdef double sign, radius, dev, size
    cdef double screen = PLACEMENT_SCREEN_ULPS * EPS
    cdef double arc_count = 0.0, total_dev = 0.0, total_length = 0.0
    cdef double max_dev = -1.0, u_at_max = 0.0, min_radius = INFINITY, max_radius = -INFINITY
    cdef double finite = 0.0
    cdef bint screened = False
    for i in range(n):
        arc = &arcs.at(i)
        row = rows + i * WIDTH
        end = f.end if arc.u1 == 1.0 else world_point(f, arc.x1, arc.y1)
        row[F_START_X], row[F_START_Y], row[F_END_X], row[F_END_Y] = start.x, start.y, end.x, end.y
        row[F_U_START], row[F_U_END], row[F_U_AT_MAX] = arc.u0, arc.u1, arc.u_dev
        if fabs(arc.sweep) > FLAT_SWEEP_RAD:
            sign = 1.0 if arc.sweep > 0.0 else -1.0
            radius = f.scale * arc.radius
            # The centre is r·N from the start, N the left normal of the tangent.
            v = world_vector(f, -sign * arc.radius * arc.ty, sign * arc.radius * arc.tx)
            row[F_IS_ARC] = 1.0
            row[F_CENTER_X], row[F_CENTER_Y], row[F_RADIUS] = start.x + v.x, start.y + v.y, radius
            # The start seen from the centre: −sign·N.
            row[F_START_ANGLE] = world_angle(f, sign * arc.ty, -sign * arc.tx)
            row[F_SWEEP] = f.mirror * arc.sweep
            row[F_LENGTH] = radius * fabs(arc.sweep)
            dev = f.scale * arc.dev
            arc_count += 1.0
            min_radius = min(min_radius, radius)
            max_radius = max(max_radius, radius)
            finite += row[F_CENTER_X] + row[F_CENTER_Y] + radius
            size = max(fabs(row[F_CENTER_X]), fabs(row[F_CENTER_Y])) + radius
            screened = screened or dev + screen * size > tolerance
        else:
            # Numerically flat: its chord, within the arc's own deviation and the
            # distance to the chord's line (the chord and the arc differ by less than
            # their sagitta, length·FLAT_SWEEP_RAD/8).
            row[F_IS_ARC] = 0.0
            row[F_CENTER_X], row[F_CENTER_Y] = 0.5 * (start.x + end.x), 0.5 * (start.y + end.y)
            row[F_RADIUS], row[F_START_ANGLE], row[F_SWEEP] = INFINITY, 0.0, 0.0
            row[F_LENGTH] = hypot(end.x - start.x, end.y - start.y)
            dev = f.scale * max(
                line_deviation(p, vec(arc.x0, arc.y0), vec(arc.x1, arc.y1), arc.u0, arc.u1),
                arc.dev,
            )
        row[F_MAX_DEV] = dev
        if dev > max_dev:
            max_dev, u_at_max = dev, arc.u_dev
        total_dev += dev
        total_length += row[F_LENGTH]
        finite += start.x + start.y + end.x + end.y + dev
        start = end
    # One sum for the whole spline: finite when every term is (it could overflow only past
    # 1e300, far beyond the bounds on sizes and coordinates).
    if not isfinite(finite) or max_dev != max_dev:
        return OVERFLOW
    if screened and not placed(rows, n, tolerance, screen, aux):
        aux[1] = max_radius
        return UNPLACEABLE
    stats[S_ARCS], stats[S_LINES] = arc_count, <double>n - arc_count
    stats[S_MAX_DEV], stats[S_U_AT_MAX] = max_dev, u_at_max
    stats[S_MEAN_DEV] = total_dev / <double>n
    stats[S_SPIRAL_LENGTH] = f.scale * arc_length(p, 0.0, 1.0)
    stats[S_SPLINE_LENGTH] = total_length
    stats[S_MIN_RADIUS] = min_radius if arc_count > 0.0 else NAN
    stats[S_MAX_RADIUS] = max_radius if arc_count > 0.0 else NAN
    return OK


cdef inline Arc exact_arc(const Piece* p, int kind) noexcept nogil:
    """An input line or circular-arc piece as its one segment (deviation 0). In the local
    frame the piece leaves the origin along +x and turns left, so an arc's sweep is twice the
    angle of its end point ``E`` and its radius ``|E| / (2·sin(sweep/2))``."""
    cdef Vec e = point(p, 1.0)
    cdef Arc arc
    cdef double half = atan2(e.y, e.x) if kind == ARC_PIECE else 0.0
    arc.x0, arc.y0, arc.x1, arc.y1 = 0.0, 0.0, e.x, e.y
    arc.tx, arc.ty = 1.0, 0.0
    arc.sweep = 2.0 * half
    arc.radius = hypot(e.x, e.y) / (2.0 * sin(half)) if half > 0.0 else INFINITY
    arc.u0, arc.u1, arc.dev, arc.u_dev = 0.0, 1.0, 0.0, 0.0
    return arc


cdef class Block:
    """Rows of the segment table in memory the kernels wrote directly (no copy): a
    ``(rows, WIDTH)`` float64 buffer, which ``numpy.asarray`` wraps."""

    cdef double* data
    cdef Py_ssize_t shape[2]
    cdef Py_ssize_t strides[2]

    def __cinit__(self, Py_ssize_t rows):
        self.data = <double*>malloc(max(rows, 1) * WIDTH * sizeof(double))
        if self.data == NULL:
            raise MemoryError
        self.shape[0], self.shape[1] = rows, WIDTH
        self.strides[0], self.strides[1] = WIDTH * sizeof(double), sizeof(double)

    def __dealloc__(self):
        free(self.data)

    def __getbuffer__(self, Py_buffer* view, int flags):
        view.buf = self.data
        view.obj = self
        view.len = self.shape[0] * WIDTH * sizeof(double)
        view.readonly = 0
        view.itemsize = sizeof(double)
        view.format = "d"
        view.ndim = 2
        view.shape = self.shape
        view.strides = self.strides
        view.suboffsets = NULL
        view.internal = NULL

    def __releasebuffer__(self, Py_buffer* view):
        pass


#: Rows of the first block: enough for one piece of a few dozen arcs, or for a batch at
#: this many per piece (memory is only touched where rows are written). Later blocks double
#: up to ``MAX_BLOCK_ROWS`` (or hold one piece's rows, if more).
cdef enum:
    ROWS_PER_SPIRAL = 32
    MAX_BLOCK_ROWS = 1 << 16


cdef object run(
    frames, tolerances, int max_segments, double min_relative_tolerance, FitFn fit,
    bint shared=False
):
    """Fit every piece of ``frames`` (rows of ``FRAME_FIELDS``) within its tolerance with
    the strategy kernel ``fit``; see the module text for the results. ``max_segments`` holds
    for each piece alone, or, if ``shared``, for all of them together (the pieces of one
    path): a piece that would pass what the pieces before it left is refused with
    ``SEGMENT_LIMIT`` and so are all after it."""
    cdef const double[:, ::1] frame = frames
    cdef const double[::1] tol = tolerances
    cdef Py_ssize_t n = frame.shape[0], i
    if frame.shape[1] != FRAME_WIDTH or tol.shape[0] != n:
        raise ValueError(f"frames must be ({n}, {FRAME_WIDTH}) beside {n} tolerances")
    where_array = np.zeros((n, 3), dtype=np.int64)
    stats_array = np.full((n, STATS_WIDTH), np.nan)
    status_array = np.zeros(n, dtype=np.int32)
    aux_array = np.zeros((n, 2))
    cdef long long[:, ::1] where = where_array
    cdef double[:, ::1] stats = stats_array
    cdef int[::1] status = status_array
    cdef double[:, ::1] aux = aux_array
    blocks, filled = [], []
    cdef Block block = Block(min(ROWS_PER_SPIRAL * n, MAX_BLOCK_ROWS))
    blocks.append(block)
    cdef Py_ssize_t used = 0, capacity = block.shape[0]
    cdef vector[Arc] arcs
    cdef Frame f
    cdef Piece s
    cdef double t, chord, coordinates, margin
    cdef Status outcome
    cdef long long left = max_segments
    cdef int kind
    for i in range(n):
        if shared and left <= 0:
            status[i] = SEGMENT_LIMIT
            continue
        t = tol[i]
        chord, coordinates = frame[i, CHORD], frame[i, COORDINATE_SCALE]
        if not (isfinite(t) and t > 0.0):
            status[i] = BAD_TOLERANCE
            continue
        if t < floor_of(chord, coordinates, min_relative_tolerance):
            status[i] = TOLERANCE_FLOOR
            continue
        f.origin = vec(frame[i, X0], frame[i, Y0])
        f.cos_phi, f.sin_phi = frame[i, COS_PHI], frame[i, SIN_PHI]
        f.scale, f.mirror = frame[i, SCALE], frame[i, MIRROR]
        f.end = vec(frame[i, END_X], frame[i, END_Y])
        s.x[0], s.x[1], s.x[2], s.x[3] = 0.0, frame[i, PX1], frame[i, PX2], frame[i, PX3]
        s.y[0], s.y[1], s.y[2], s.y[3] = 0.0, frame[i, PY1], frame[i, PY2], frame[i, PY3]
        s.w[0], s.w[1], s.w[2] = 1.0, frame[i, PW1], frame[i, PW2]
        s.rational = s.w[1] != 0.0 or s.w[2] != 0.0
        margin = rounding_margin(chord, coordinates)
        arcs.clear()
        kind = <int>frame[i, KIND]
        if kind == FIT_PIECE:
            with nogil:
                outcome = fit(&s, (t - margin) / f.scale, left if shared else max_segments, &arcs)
        else:
            arcs.push_back(exact_arc(&s, kind))
            outcome = OK
        if outcome == OK and used + <Py_ssize_t>arcs.size() > capacity:
            capacity = max(<Py_ssize_t>arcs.size(), min(2 * capacity, MAX_BLOCK_ROWS))
            block = Block(capacity)
            blocks.append(block)
            filled.append(used)
            used = 0
        if outcome == OK:
            with nogil:
                outcome = assemble(
                    &s, &f, &arcs, t, block.data + used * WIDTH, &stats[i, 0], &aux[i, 0]
                )
        if outcome == OK:
            where[i, 0], where[i, 1] = len(blocks) - 1, used
            used += arcs.size()
            where[i, 2] = used
            left -= <long long>arcs.size()
        else:
            status[i] = outcome
    filled.append(used)
    # Only the rows written: the rest of a block is uninitialised memory.
    tables = [np.asarray(b)[:rows] for b, rows in zip(blocks, filled)]
    return tables, where_array, stats_array, status_array, aux_array


def frame_table(list frames):
    """The ``(n, len(FRAME_FIELDS))`` float64 table of ``n`` frame tuples (curves' ``frame``),
    read in C: a batch of thousands spends microseconds here, not milliseconds."""
    cdef Py_ssize_t n = len(frames), i, j
    table = np.empty((n, FRAME_WIDTH))
    cdef double[:, ::1] out = table
    cdef tuple row
    for i in range(n):
        row = <tuple?>frames[i]
        if len(row) != FRAME_WIDTH:
            raise ValueError(f"frame {i} has {len(row)} numbers, not {FRAME_WIDTH}")
        for j in range(FRAME_WIDTH):
            out[i, j] = <double>row[j]
    return table
