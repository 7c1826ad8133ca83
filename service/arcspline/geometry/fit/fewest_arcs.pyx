# cython: language_level=3, boundscheck=False, wraparound=False, cdivision=True
"""Strategy ``fewest-arcs``: greedy longest biarcs with the joint chosen freely, then a tail
merge (docs/fewest-arcs.md).

In its local frame the piece (the paper's spiral, or a piece of a path's segment) is walked
from ``u = 0``: from the current end ``A0 = Q(u0)`` the next biarc ends at the largest ``u1``
for which some member of Sabin's
family between ``(A0, T(u0))`` and ``(Q(u1), T(u1))`` (``sabin.pxd``, join parameter ``λ``) is
proven within the tolerance by the exact deviation (``deviation.pyx``). A step is found in
one of two ways:

* **Newton's step** (:func:`newton_step`), while the previous span fits ``NEWTON_REACH`` more
  times before the end: Newton's method on ``(log(u1 − u0), λ)`` for the biarc whose two
  arcs both deviate by just under the tolerance, every iterate measured exactly, with
  Broyden's update of a Jacobian carried along the walk;
* **the search** (:func:`search`) otherwise, or where Newton's method fails: candidates
  ``(u1, λ)`` on grids around the previous step are screened by sampled radial distances (a
  lower bound: it only discards), refined twice, and the best are proven.

Greedy longest pieces leave a short last biarc: where a step ends within one span of the
end, the rest of the spiral from that step's start is tried as three arcs (``triarc.pyx``),
and at the end the last two biarcs are. Only proven arcs are kept, so the tolerance holds as
for ``subdivide``; ``subdivide`` runs first, and its result is kept wherever the walk fails or
has more segments.
"""

from libc.math cimport INFINITY, NAN, ceil, cos, exp, isfinite, log, log2, sin
from libcpp.vector cimport vector

from arcspline.geometry.curves.piece cimport Piece, offset, point, tangent
from arcspline.geometry.deviation cimport Peak, arc_deviation, joint_split, sampled, split_guess
from arcspline.geometry.fit cimport batch
from arcspline.geometry.fit.arcs cimport OK, Arc, Status
from arcspline.geometry.fit.sabin cimport Chord, Sabin, chord, sabin_biarc
from arcspline.geometry.fit.subdivide cimport subdivide
from arcspline.geometry.fit.triarc cimport Triarc, best_triarc
from arcspline.geometry.maths.vec cimport Vec, vec

cdef extern from *:
    """
    /* Join parameters stay this far inside (0, 1). */
    #define ARCSPLINE_LAMBDA_MARGIN 1e-3
    /* The first piece's scan: its join parameters and the spread they stand for. */
    static const double ARCSPLINE_SCAN_LAMBDA[3] = {0.3, 0.5, 0.7};
    #define ARCSPLINE_SCAN_WIDTH 0.2
    /* A hinted round: spans 2^±0.4 of the previous one (8 points), join parameters within
       ±0.12 of the previous one (7 points). Along a spiral both change slowly: the paper's
       example at 1e-5 has spans within 10 % of the last one and λ within 0.01 of it. */
    #define ARCSPLINE_HINT_OCTAVES 0.4
    #define ARCSPLINE_HINT_LAMBDA 0.12
    /* Where neither the interpolated crossing nor the longest screened fit is proven: these
       fractions of the longest screened span. */
    static const double ARCSPLINE_LADDER[5] = {0.998, 0.994, 0.985, 0.96, 0.9};
    /* Screening aims at these fractions of the tolerance, in turn, until a step is proven. */
    static const double ARCSPLINE_SCREEN_FACTORS[5] = {0.999, 0.99, 0.95, 0.8, 0.5};
    /* A step ending within this many of its spans from the end tries the tail merge from
       its start; a step whose previous span fits this many times more before the end tries
       Newton's method first (nearer the end its iterates tend to pass the end). */
    #define ARCSPLINE_CLOSE_REACH 1.0
    #define ARCSPLINE_NEWTON_REACH 2.0
    /* Newton's step: both arcs aim at NEWTON_TARGET of the tolerance; a proven biarc whose
       larger deviation reaches NEWTON_ACCEPT of it ends the iteration; after the iterations
       the longest proven one is kept if it reaches NEWTON_FLOOR of it, else the search
       takes the step. Steps are capped in log(span) and in λ. */
    #define ARCSPLINE_NEWTON_TARGET 0.995
    #define ARCSPLINE_NEWTON_ACCEPT 0.97
    #define ARCSPLINE_NEWTON_FLOOR 0.9
    #define ARCSPLINE_NEWTON_MAX_LOG_STEP 0.5
    #define ARCSPLINE_NEWTON_MAX_LAMBDA_STEP 0.1
    /* The first Jacobian of the residuals log(dev_i / target) in (log span, λ): a deviation
       grows about as the span cubed, and λ moves deviation from one arc to the other
       (measured by finite differences on the paper's example and 200 random spirals:
       2.3–3.3, 11.9–13.5, 2.8–3.7, −12.1…−10.7). Broyden's update refines it. */
    static const double ARCSPLINE_NEWTON_JACOBIAN[4] = {3.0, 12.5, 3.2, -11.5};
    """
    const double LAMBDA_MARGIN "ARCSPLINE_LAMBDA_MARGIN"
    const double* SCAN_LAMBDA "ARCSPLINE_SCAN_LAMBDA"
    const double SCAN_WIDTH "ARCSPLINE_SCAN_WIDTH"
    const double HINT_OCTAVES "ARCSPLINE_HINT_OCTAVES"
    const double HINT_LAMBDA "ARCSPLINE_HINT_LAMBDA"
    const double* LADDER "ARCSPLINE_LADDER"
    const double* SCREEN_FACTORS "ARCSPLINE_SCREEN_FACTORS"
    const double CLOSE_REACH "ARCSPLINE_CLOSE_REACH"
    const double NEWTON_REACH "ARCSPLINE_NEWTON_REACH"
    const double NEWTON_TARGET "ARCSPLINE_NEWTON_TARGET"
    const double NEWTON_ACCEPT "ARCSPLINE_NEWTON_ACCEPT"
    const double NEWTON_FLOOR "ARCSPLINE_NEWTON_FLOOR"
    const double NEWTON_MAX_LOG_STEP "ARCSPLINE_NEWTON_MAX_LOG_STEP"
    const double NEWTON_MAX_LAMBDA_STEP "ARCSPLINE_NEWTON_MAX_LAMBDA_STEP"
    const double* NEWTON_JACOBIAN "ARCSPLINE_NEWTON_JACOBIAN"

cdef enum:
    # Screening samples per arc: in the refining rounds, and (coarser) in the first rounds,
    # which only bracket the longest piece.
    SAMPLES = 8
    COARSE_SAMPLES = 6
    # The first round without a hint: u1 − u0 = (1 − u0)·2^(−j/2), j < U_STEPS, against
    # LAMBDAS join parameters over (0, 1); a piece to the spiral's end against END_LAMBDAS.
    U_STEPS = 32
    LAMBDAS = 12
    SCAN_LAMBDAS = 3
    END_LAMBDAS = 24
    HINT_STEPS = 8
    HINT_LAMBDAS = 7
    # Refining rounds between the longest fit and the next value tried: u1 points (both
    # ends included), λ points.
    REFINE_ROUNDS = 2
    REFINE_POINTS = 6
    REFINE_LAMBDAS = 5
    LADDER_RUNGS = 5
    SCREEN_ROUNDS = 5
    NEWTON_ITERATIONS = 6
    MAX_GRID = U_STEPS + 1
    MAX_LAMBDAS = END_LAMBDAS


cdef struct Biarc:
    # A member of Sabin's family from A0 = Q(u0) to A1 = Q(u1).
    double u0
    double u1
    double lam
    double phi0    # directions at A0, at the joint G, at A1
    double psi
    double phi1
    Vec t0         # unit tangents at A0 and at G
    Vec t
    double kappa0
    double kappa1
    Vec a
    Vec g
    Vec b
    double split   # where the spiral crosses G's normal line (a guess when screening)
    bint ok


cdef struct Proof:
    # Exact deviations of a biarc's arcs and where they are reached.
    double d0
    double w0
    double d1
    double w1


cdef struct Round:
    # Candidates grid[i] × lams[j] (n_u × n_lam); the least screened deviation of each row
    # scanned.
    int n_u
    int n_lam
    double grid[MAX_GRID]
    double lams[MAX_LAMBDAS]
    double row_min[MAX_GRID]


cdef struct Top:
    # The longest fitting u1 of a round, the best λ there, and whether any fits.
    double u
    double lam
    bint ok
    int at


cdef inline Chord spiral_chord(const Piece* s, double u0, double u1) noexcept nogil:
    cdef Vec t0, t1
    cdef double phi0 = tangent(s, u0, &t0), phi1 = tangent(s, u1, &t1)
    return chord(point(s, u0), phi0, t0, offset(s, u0, u1), phi1, t1)


cdef inline Biarc biarc(
    const Piece* s, const Chord* c, double u0, double u1, double lam, bint exact
) noexcept nogil:
    """The member ``λ`` of the family from ``Q(u0)`` to ``Q(u1)`` (``c``, their chord);
    ``exact=False`` (screening) guesses the joint's split parameter."""
    cdef Sabin sb = sabin_biarc(c, lam)
    cdef Biarc b
    b.u0, b.u1, b.lam = u0, u1, lam
    b.phi0, b.psi, b.phi1, b.t0, b.t = c.phi0, sb.psi, c.phi1, c.t0, sb.t
    b.kappa0, b.kappa1, b.g = sb.kappa0, sb.kappa1, sb.g
    b.a, b.b = c.p0, vec(c.p0.x + c.d.x, c.p0.y + c.d.y)
    if exact:
        b.split = joint_split(s, b.g, b.t.x, b.t.y)
    else:
        b.split = split_guess(s, b.g, b.t.x, b.t.y, u0, u1, 0.5 * (u0 + u1))
    b.ok = sb.ok and u0 < b.split < u1
    return b


cdef inline double screen(const Piece* s, const Biarc* b, int samples, double bound) noexcept nogil:
    """Largest sampled radial distance of both arcs (a lower bound on the deviation);
    ``inf`` for an invalid biarc or a number that is not one. A biarc known to score at
    least ``bound`` is left as soon as it is known (the value is then at least ``bound``)."""
    if not b.ok:
        return INFINITY
    cdef double worst = sampled(s, b.a, b.t0, b.kappa0, b.u0, b.split, samples)
    if not worst < bound:
        return worst
    return max(worst, sampled(s, b.g, b.t, b.kappa1, b.split, b.u1, samples))


cdef inline Proof prove(
    const Piece* s, const Biarc* b, double tolerance, bint lazily
) noexcept nogil:
    """Both arcs' exact deviations (``inf`` for an invalid biarc); ``lazily``, the second arc
    is not measured (NaN) when the first is out of the tolerance."""
    cdef Proof p
    if not b.ok:
        p.d0, p.w0, p.d1, p.w1 = INFINITY, b.u0, INFINITY, b.split
        return p
    cdef Peak peak = arc_deviation(s, b.a, b.t0.x, b.t0.y, b.kappa0, b.g, b.u0, b.split,
                                   tolerance)
    p.d0, p.w0 = peak.value, peak.u
    if lazily and not p.d0 <= tolerance:
        p.d1, p.w1 = NAN, NAN
        return p
    peak = arc_deviation(s, b.g, b.t.x, b.t.y, b.kappa1, b.b, b.split, b.u1, tolerance)
    p.d1, p.w1 = peak.value, peak.u
    return p


cdef inline double clip(double x, double lo, double hi) noexcept nogil:
    """``x`` within ``[lo, hi]``; NaN stays NaN."""
    return x if x != x else min(max(x, lo), hi)


cdef inline double clamp_lambda(double lam) noexcept nogil:
    return clip(lam, LAMBDA_MARGIN, 1.0 - LAMBDA_MARGIN)


cdef inline double linspace(double a, double b, int n, int i) noexcept nogil:
    """``numpy.linspace(a, b, n)[i]``."""
    return b if i == n - 1 else a + i * ((b - a) / (n - 1))


cdef Top longest_fit(
    const Piece* s, double u0, Round* r, int samples, double target, bint exact_minima
) noexcept nogil:
    """The round's longest ``u1`` with a fitting ``λ`` (screened deviation ≤ ``target``; the
    first of equal ``u1``) and the ``λ`` of least deviation there; ``ok`` false if none fits.

    Rows are screened longest first, and the scan stops at the first row with a fit: shorter
    ones cannot change the answer. Within a row a candidate is left as soon as it cannot be
    the row's least (or, before a fit and unless ``exact_minima``, cannot fit), so the least
    deviation of the row that fits is exact, and with ``exact_minima`` so is every row's
    scanned before it (what :func:`crossing` needs of the row above)."""
    cdef int order[MAX_GRID]
    cdef int n = 0, i, j, k, k2, row
    # Indices by decreasing u1 (the first of equals first): an insertion sort of a few.
    for i in range(r.n_u):
        j = n
        while j > 0 and r.grid[order[j - 1]] < r.grid[i]:
            order[j] = order[j - 1]
            j -= 1
        order[j] = i
        n += 1
    cdef Top t
    t.at, t.ok, t.u, t.lam = -1, False, r.grid[0], r.lams[0]
    cdef Chord c
    cdef Biarc b
    cdef double least, value
    for i in range(r.n_u):
        r.row_min[i] = NAN
    for k in range(n):
        row = order[k]
        c = spiral_chord(s, u0, r.grid[row])
        least, j = INFINITY, 0
        # From the middle λ outwards (the least is seldom at the ends): a low bound early
        # leaves more candidates early. Equals go to the first λ, as in order.
        for k2 in range(r.n_lam):
            i = (r.n_lam - 1) // 2 + ((k2 + 1) // 2 if k2 % 2 else -(k2 // 2))
            b = biarc(s, &c, u0, r.grid[row], r.lams[i], False)
            value = screen(s, &b, samples, least if exact_minima or least <= target else target)
            if value < least or (value == least and i < j):
                least, j = value, i
        r.row_min[row] = least
        if least <= target:
            t.at, t.ok, t.u, t.lam = row, True, r.grid[row], r.lams[j]
            break
    return t


cdef double crossing(const Round* r, Top t, double target) noexcept nogil:
    """Where the screened deviation (best ``λ``) reaches ``target`` between the longest fit
    and the next grid value, by linear interpolation: a chord of the deviation's convex
    growth, so it errs short. ``t.u`` at the grid's end. (The round's grid ascends, and its
    rows were scanned with ``exact_minima``.)"""
    cdef int at = max(t.at, 0), nxt = min(at + 1, r.n_u - 1)
    cdef double d_top = r.row_min[at], d_next = r.row_min[nxt]
    cdef double x = (target - d_top) / (d_next - d_top)
    x = min(max(x, 0.0), 1.0)
    if not (isfinite(x) and nxt > at):
        x = 0.0
    return t.u + (r.grid[nxt] - t.u) * x


cdef bint prove_rungs(
    const Piece* s, double u0, double tolerance, const double* rungs, int count, double lam,
    Biarc* out, Proof* proof
) noexcept nogil:
    """The first of the piece ends ``rungs`` whose biarc of join parameter ``lam`` is proven
    within the tolerance (a repeated rung is not tried again)."""
    cdef Chord c
    cdef int i, j
    cdef bint seen
    for i in range(count):
        seen = False
        for j in range(i):
            seen = seen or rungs[j] == rungs[i]
        if seen:
            continue
        c = spiral_chord(s, u0, rungs[i])
        out[0] = biarc(s, &c, u0, rungs[i], lam, True)
        if not out.ok:
            continue
        proof[0] = prove(s, out, tolerance, True)
        if proof.d0 <= tolerance and proof.d1 <= tolerance:
            return True
    return False


cdef struct Hint:
    double span
    double lam


cdef inline void hinted_round(Round* r, double u0, Hint h) noexcept nogil:
    """``u1 = 1`` and spans ``2^±HINT_OCTAVES`` of the hint's, longest first; join
    parameters within ``±HINT_LAMBDA`` of its."""
    cdef int i
    r.n_u, r.n_lam = 1 + HINT_STEPS, HINT_LAMBDAS
    r.grid[0] = 1.0
    for i in range(HINT_STEPS):
        r.grid[1 + i] = min(
            u0 + h.span * 2.0 ** linspace(HINT_OCTAVES, -HINT_OCTAVES, HINT_STEPS, i), 1.0
        )
    for i in range(HINT_LAMBDAS):
        r.lams[i] = clamp_lambda(h.lam + HINT_LAMBDA * linspace(-1.0, 1.0, HINT_LAMBDAS, i))


cdef inline void full_grid(Round* r, double u0) noexcept nogil:
    cdef int i
    r.n_u = U_STEPS
    r.grid[0] = 1.0
    for i in range(1, U_STEPS):
        r.grid[i] = u0 + (1.0 - u0) * 2.0 ** (-i / 2.0)


cdef inline void first_scan(Round* r, double u0, double floor) noexcept nogil:
    """The geometric grid ``u0 + (1 − u0)·2^(−j/2)`` for the walk's first piece, whose
    longest biarc is known to reach ``floor`` (``subdivide``'s first biarc, a member of
    Sabin's family): it stops two octaves (a factor 64 in deviation) below it, at the cut."""
    cdef double span = 1.0 - u0, cut = u0 + (floor - u0) * 0.25
    cdef double need = ceil(2.0 * log2(span / (cut - u0))) + 1.0
    cdef int width = U_STEPS if not need < U_STEPS else <int>max(need, 1.0), i
    full_grid(r, u0)
    r.n_u = width
    if width < U_STEPS:
        r.grid[width] = cut
        r.n_u = width + 1
    for i in range(r.n_u):
        r.grid[i] = max(r.grid[i], cut)


cdef struct Search:
    # The search's state: the longest screened fit so far, its λ and how far its λ was
    # from its neighbours; every u1 screened.
    double u_top
    double lam_top
    double width
    bint has


cdef inline void take(const Piece* s, double u0, Search* state, Round* r, double target,
                      double width, vector[double]* tried) noexcept nogil:
    cdef Top t = longest_fit(s, u0, r, COARSE_SAMPLES, target, False)
    if t.ok and (not state.has or t.u > state.u_top):
        state.u_top, state.lam_top, state.has, state.width = t.u, t.lam, True, width
    cdef int i
    for i in range(r.n_u):
        tried.push_back(r.grid[i])


cdef inline bint reach_end(const Piece* s, double u0, Search* state, Round* r,
                           double target) noexcept nogil:
    cdef Top t = longest_fit(s, u0, r, COARSE_SAMPLES, target, False)
    if t.ok:
        state.u_top, state.lam_top, state.has = 1.0, t.lam, True
    return t.ok


cdef bint search(
    const Piece* s, double u0, double tolerance, double target, Hint hint, double floor,
    Biarc* out, Proof* proof
) noexcept nogil:
    """From ``u0``, the proven biarc reaching the largest ``u1`` found with screening aimed at
    ``target``: a first round around the previous step's span and ``λ`` (``hint``; the first
    step scans a geometric grid, cut at ``floor``), two refining rounds, then the proof of the
    interpolated crossing, the longest screened fit and a ladder of shorter pieces."""
    cdef Round r
    cdef Search state
    state.u_top, state.lam_top, state.width, state.has = 0.0, 0.5, 1.0 / LAMBDAS, False
    cdef vector[double] tried
    cdef double span = 1.0 - u0
    cdef bint hinted = 0.0 < hint.span < span, scanned = False
    cdef int i
    # The spiral's end is worth a finer scan of λ: reaching it ends the walk.
    r.n_u, r.n_lam, r.grid[0] = 1, END_LAMBDAS, 1.0
    for i in range(END_LAMBDAS):
        r.lams[i] = (i + 0.5) / END_LAMBDAS
    if hint.span > 0.0 and (not hinted or u0 + hint.span * 2.0 ** HINT_OCTAVES >= 1.0):
        reach_end(s, u0, &state, &r, target)
    elif hint.span <= 0.0:
        reach_end(s, u0, &state, &r, target)
        scanned = True
    cdef bint scan = not hinted and not state.has
    if scan:
        # No hint: a geometric grid with a few join parameters; its longest fit's bracket
        # then serves as the hint.
        if scanned:
            first_scan(&r, u0, floor)
        else:
            full_grid(&r, u0)
        r.n_lam = SCAN_LAMBDAS
        for i in range(SCAN_LAMBDAS):
            r.lams[i] = SCAN_LAMBDA[i]
        take(s, u0, &state, &r, target, SCAN_WIDTH, &tried)
        hint.span = (state.u_top - u0) * 2.0 ** 0.25 if state.has else 0.0
        hint.lam = state.lam_top
        hinted = state.has and state.u_top < 1.0
        state.has = state.has and state.u_top >= 1.0
    else:
        hinted = hinted and not state.has
    cdef double nearest = min(u0 + hint.span * 2.0 ** HINT_OCTAVES, 1.0)
    if hinted:
        hinted_round(&r, u0, hint)
        take(s, u0, &state, &r, target, 2.0 * HINT_LAMBDA / (HINT_LAMBDAS - 1), &tried)
    # Retry on the full grid where nothing fits or the hinted round's longest span fits
    # (unless that round reached the spiral's end, which closes the bracket).
    if hinted and not scan and (
        not state.has or (state.u_top == nearest and u0 + hint.span * 2.0 ** HINT_OCTAVES < 1.0)
    ):
        full_grid(&r, u0)
        r.n_lam = LAMBDAS
        for i in range(LAMBDAS):
            r.lams[i] = (i + 0.5) / LAMBDAS
        take(s, u0, &state, &r, target, 1.0 / LAMBDAS, &tried)

    cdef bint refining = state.has and state.u_top < 1.0
    cdef double u_star = state.u_top, above
    cdef Top t
    cdef int _round
    for _round in range(REFINE_ROUNDS):
        if not refining:
            break
        # Between the longest fit and the next value above it among all tried.
        above = INFINITY
        for i in range(<int>tried.size()):
            if tried[i] > state.u_top:
                above = min(above, tried[i])
        if not isfinite(above):
            above = 1.0
        r.n_u, r.n_lam = REFINE_POINTS, REFINE_LAMBDAS
        for i in range(REFINE_POINTS):
            r.grid[i] = state.u_top + (above - state.u_top) * linspace(0.0, 1.0, REFINE_POINTS, i)
        for i in range(REFINE_LAMBDAS):
            r.lams[i] = clamp_lambda(
                state.lam_top + state.width * linspace(-1.0, 1.0, REFINE_LAMBDAS, i)
            )
        t = longest_fit(s, u0, &r, SAMPLES, target, True)
        if t.ok:
            state.u_top, state.lam_top = t.u, t.lam
            u_star = crossing(&r, t, target)
        for i in range(r.n_u):
            tried.push_back(r.grid[i])
        refining = t.ok and t.u < 1.0
        state.width *= 2.0 / (REFINE_LAMBDAS - 1)

    # The screen slightly underestimates; rather than search again with a lower target, the
    # proof tries the crossing, the longest fit and a ladder of slightly shorter pieces.
    if not state.has:
        return False
    cdef double rungs[LADDER_RUNGS + 2]
    rungs[0], rungs[1] = u_star, state.u_top
    rungs[2] = u0 + (state.u_top - u0) * LADDER[0]
    if prove_rungs(s, u0, tolerance, rungs, 3, state.lam_top, out, proof):
        return True
    for i in range(1, LADDER_RUNGS):
        rungs[i - 1] = u0 + (state.u_top - u0) * LADDER[i]
    return prove_rungs(s, u0, tolerance, rungs, LADDER_RUNGS - 1, state.lam_top, out, proof)


cdef inline bint equations(
    const Piece* s, double u0, double tolerance, double log_span, double lam, Biarc* b,
    Proof* p, double* f0, double* f1
) noexcept nogil:
    """The biarc at ``(log(u1 − u0), λ)``, its exact deviations and the residuals
    ``log(dev / (NEWTON_TARGET·tol))`` of both arcs; whether both are finite."""
    cdef double u1 = u0 + exp(log_span)
    cdef Chord c = spiral_chord(s, u0, u1)
    b[0] = biarc(s, &c, u0, u1, lam, True)
    p[0] = prove(s, b, tolerance, False)
    cdef double aim = NEWTON_TARGET * tolerance
    f0[0], f1[0] = log(p.d0 / aim), log(p.d1 / aim)
    return isfinite(f0[0]) and isfinite(f1[0])


cdef bint newton_step(
    const Piece* s, double u0, double tolerance, Hint hint, double* jac, Biarc* out,
    Proof* proof
) noexcept nogil:
    """From ``u0``, the biarc whose two arcs both deviate by ``NEWTON_TARGET·tol``, by
    Newton's method on ``x = (log(u1 − u0), λ)`` from the previous step ``hint``, with
    Broyden's "good" update of the Jacobian ``jac`` (C.G. Broyden, *A class of methods for
    solving nonlinear simultaneous equations*, Math. Comp. 19 (1965)), which the walk carries
    from step to step. Every iterate is proven exactly; the longest proven one is kept if it
    reaches ``NEWTON_FLOOR`` of the tolerance. (About two exact evaluations a step on the
    paper's example at 1e-5.)"""
    cdef double x0 = log(hint.span), x1 = hint.lam, f0, f1, g0, g1
    cdef double s0, s1, det, r0, r1, norm2, worst
    cdef Biarc b
    cdef Proof p
    cdef bint finite = equations(s, u0, tolerance, x0, x1, &b, &p, &f0, &f1), proven
    cdef double best_u1 = -INFINITY
    cdef int iteration
    for iteration in range(NEWTON_ITERATIONS):
        proven = b.ok and p.d0 <= tolerance and p.d1 <= tolerance
        if proven and b.u1 > best_u1:
            out[0], proof[0], best_u1 = b, p, b.u1
        worst = max(p.d0, p.d1)
        if (proven and worst >= NEWTON_ACCEPT * tolerance) or not finite:
            break
        if iteration == NEWTON_ITERATIONS - 1:
            break
        det = jac[0] * jac[3] - jac[1] * jac[2]
        # Clipped before the test: an infinite step becomes the largest, NaN stops.
        s0 = clip(-(jac[3] * f0 - jac[1] * f1) / det, -NEWTON_MAX_LOG_STEP, NEWTON_MAX_LOG_STEP)
        s1 = clip(-(jac[0] * f1 - jac[2] * f0) / det, -NEWTON_MAX_LAMBDA_STEP,
                  NEWTON_MAX_LAMBDA_STEP)
        if not (isfinite(s0) and isfinite(s1)) or not u0 + exp(x0 + s0) < 1.0:
            break
        x0, x1 = x0 + s0, clamp_lambda(x1 + s1)
        finite = equations(s, u0, tolerance, x0, x1, &b, &p, &g0, &g1)
        # Broyden: J += (Δf − J·Δx)·Δxᵀ / (Δx·Δx), where both changes are finite.
        r0 = (g0 - f0) - (jac[0] * s0 + jac[1] * s1)
        r1 = (g1 - f1) - (jac[2] * s0 + jac[3] * s1)
        norm2 = s0 * s0 + s1 * s1
        if isfinite(r0) and isfinite(r1) and norm2 > 0.0:
            jac[0] += r0 * s0 / norm2
            jac[1] += r0 * s1 / norm2
            jac[2] += r1 * s0 / norm2
            jac[3] += r1 * s1 / norm2
        f0, f1 = g0, g1
    return isfinite(best_u1) and max(proof.d0, proof.d1) >= NEWTON_FLOOR * tolerance


cdef struct Joint:
    # A joint of the chain: its point, the chain's direction there, and where the spiral
    # crosses its normal line.
    double x
    double y
    double phi
    double s


cdef struct Link:
    # An arc of the chain: its curvature, exact deviation and where it is reached.
    double kappa
    double dev
    double u_dev


cdef cppclass Walk:
    # The walk's chain and state (docs/fewest-arcs.md §2).
    vector[Joint] joints
    vector[Link] pieces
    double u0
    Hint hint
    int max_arcs
    int last_tried
    bint closed
    bint failed


cdef void record(Walk* w, const Biarc* b, const Proof* p) noexcept nogil:
    """Append a proven biarc to the chain; the walk fails past ``max_arcs`` or without
    progress."""
    cdef Joint j
    cdef Link piece
    j.x, j.y, j.phi, j.s = b.g.x, b.g.y, b.psi, b.split
    w.joints.push_back(j)
    j.x, j.y, j.phi, j.s = b.b.x, b.b.y, b.phi1, b.u1
    w.joints.push_back(j)
    piece.kappa, piece.dev, piece.u_dev = b.kappa0, p.d0, p.w0
    w.pieces.push_back(piece)
    piece.kappa, piece.dev, piece.u_dev = b.kappa1, p.d1, p.w1
    w.pieces.push_back(piece)
    w.hint.span, w.hint.lam, w.u0 = b.u1 - b.u0, b.lam, b.u1
    cdef int extra = 2 if b.u1 < 1.0 else 0
    if <int>w.pieces.size() + extra > w.max_arcs or not b.u1 > w.joints[w.joints.size() - 3].s:
        w.failed = True


cdef void close(const Piece* s, Walk* w, int keep, double tolerance) noexcept nogil:
    """Replace the chain from its first ``keep`` arcs on by a proven triarc from that joint
    to the spiral's end, if one is found."""
    w.last_tried = keep
    cdef Triarc t
    if w.closed or not best_triarc(s, w.joints[keep].s, tolerance, &t):
        return
    w.joints.resize(keep)
    w.pieces.resize(keep)
    cdef Joint j
    cdef Link piece
    cdef int i
    for i in range(4):
        j.x, j.y, j.phi, j.s = t.x[i], t.y[i], t.phi[i], t.s[i]
        w.joints.push_back(j)
    for i in range(3):
        piece.kappa, piece.dev, piece.u_dev = t.kappa[i], t.dev[i], t.u_dev[i]
        w.pieces.push_back(piece)
    w.u0, w.closed, w.failed = 1.0, True, False


cdef bint walks_on(const Piece* s, Walk* w, double tolerance) noexcept nogil:
    """After a step: where it ends within ``CLOSE_REACH`` of its span from the end, the
    tail merge is tried from its start. Whether the walk goes on."""
    if w.failed or w.u0 >= 1.0:
        return False
    if w.u0 + w.hint.span * CLOSE_REACH >= 1.0:
        close(s, w, <int>w.pieces.size() - 2, tolerance)
    return not w.closed


cdef bint walk(
    const Piece* s, double tolerance, int max_arcs, double first_span, Walk* w
) noexcept nogil:
    """Greedy longest proven biarcs over ``[0, 1]`` into ``w``, then the tail merge; False
    where the walk fails or would need more than ``max_arcs`` arcs."""
    cdef Joint origin
    origin.x, origin.y, origin.phi, origin.s = 0.0, 0.0, 0.0, 0.0
    w.joints.push_back(origin)
    w.u0, w.hint.span, w.hint.lam = 0.0, 0.0, 0.5
    w.max_arcs, w.last_tried, w.closed, w.failed = max_arcs, -1, False, False
    cdef double jac[4]
    cdef int i
    for i in range(4):
        jac[i] = NEWTON_JACOBIAN[i]
    cdef Biarc b
    cdef Proof p
    cdef bint stepped, found
    while True:
        # Far from the end, Newton's method from the previous step, step after step.
        stepped = False
        while w.hint.span > 0.0 and w.u0 + w.hint.span * NEWTON_REACH < 1.0:
            stepped = newton_step(s, w.u0, tolerance, w.hint, jac, &b, &p)
            if stepped:
                record(w, &b, &p)
            if not stepped or w.failed:
                break
        if stepped and not walks_on(s, w, tolerance):
            break
        found = False
        for i in range(SCREEN_ROUNDS):
            if search(s, w.u0, tolerance, SCREEN_FACTORS[i] * tolerance, w.hint, first_span,
                      &b, &p):
                record(w, &b, &p)
                found = True
                break
        if not found:
            w.failed = True
            break
        if not walks_on(s, w, tolerance):
            break
    # The merge of the last two biarcs, unless it was tried.
    cdef int keep = <int>w.pieces.size() - 4
    if not w.failed and not w.closed and keep >= 0 and keep != w.last_tried:
        close(s, w, keep, tolerance)
    return not w.failed


cdef Status fewest(
    const Piece* s, double tolerance, int max_arcs, vector[Arc]* arcs
) noexcept nogil:
    """``subdivide``, then the walk: its chain replaces ``subdivide``'s arcs when it has no
    more of them. (Two segments are the least possible: one arc matching both end tangents
    needs a chord that bisects the turn θ, while the spiral's chord turns at most 0.75·θ/2.)
    """
    cdef Status status = subdivide(s, tolerance, max_arcs, arcs)
    cdef size_t n = arcs.size()
    if status != OK or n <= 2:
        return status
    # Subdivide's first biarc is a member of Sabin's family: some biarc reaches that far.
    cdef Walk w
    if not walk(s, tolerance, min(max_arcs, <int>n), arcs.at(1).u1, &w):
        return OK
    if w.pieces.size() > n:
        return OK
    arcs.clear()
    cdef Arc arc
    cdef const Joint* j0
    cdef const Joint* j1
    cdef size_t i
    for i in range(w.pieces.size()):
        j0, j1 = &w.joints[i], &w.joints[i + 1]
        arc.x0, arc.y0, arc.x1, arc.y1 = j0.x, j0.y, j1.x, j1.y
        arc.tx, arc.ty = cos(j0.phi), sin(j0.phi)
        arc.radius = 1.0 / abs(w.pieces[i].kappa)
        arc.sweep = j1.phi - j0.phi
        arc.u0, arc.u1 = j0.s, j1.s
        arc.dev, arc.u_dev = w.pieces[i].dev, w.pieces[i].u_dev
        arcs.push_back(arc)
    return OK


#: Pieces need not have monotone curvature: the walk's arcs are proven by the general
#: certificate alone, and fewer cuts leave it free to place its joints (docs/fewest-arcs.md §4).
MONOTONE_PIECES = False


def fit_many(
    frames, tolerances, int max_segments, double min_relative_tolerance, bint shared=False
):
    """Strategy ``fewest-arcs`` for a batch of pieces (``fit/batch.pyx`` documents the table
    and results)."""
    return batch.run(frames, tolerances, max_segments, min_relative_tolerance, fewest, shared)
