# cython: language_level=3, boundscheck=False, wraparound=False, cdivision=True
"""``fewest-arcs``' tail merge: the rest of the spiral from ``Q(u_a)`` as three arcs whose
first joint lies off the spiral (docs/fewest-arcs.md §3 "Tail merge").

Greedy longest biarcs leave a short last biarc; the last two biarcs span about one and a half
biarcs' worth of spiral, which three arcs can often cover. The triarc from ``A = Q(u_a)``
(direction ``φ_a``) to ``B = Q(1)`` (``φ_1``) has three free parameters:

* its first joint ``J1 = Q(v) + δ·N(v)``, anywhere in the ±tolerance band; arc 0 is the arc
  tangent to ``φ_a`` at ``A`` through ``J1``, arriving with direction ``ψ1 = 2χ0 − φ_a``
  (``χ0`` the direction of ``J1 − A``);
* the join parameter ``λ`` of Sabin's biarc from ``(J1, ψ1)`` to ``(B, φ_1)``.

A grid and a pattern search minimise the sampled deviation (a lower bound, screening only);
the winner is kept only if ``arc_deviation`` proves all three arcs within the tolerance.
"""

from libc.math cimport INFINITY, atan2

from arcspline.geometry.curves.piece cimport Piece, offset, point, tangent, unit_tangent
from arcspline.geometry.deviation cimport Peak, arc_deviation, joint_split, sampled, split_guess
from arcspline.geometry.fit.sabin cimport Chord, Sabin, chord, sabin_biarc
from arcspline.geometry.maths.vec cimport Vec, vec

cdef extern from *:
    """
    /* The first grid: joints at these fractions of the span from u_a, on the spiral (delta
       = 0: on 200 random spirals 79 of the 81 proven triarcs started from such a point of a
       delta in {-tol, 0, tol} grid), against join parameters. */
    static const double ARCSPLINE_TAIL_V[6] = {0.15, 0.26, 0.37, 0.48, 0.59, 0.7};
    static const double ARCSPLINE_TAIL_LAMBDA[7] = {
        0.05, 0.2, 0.35, 0.5, 0.65, 0.8, 0.95};
    /* The pattern search's moves along each axis, in units of its widths. */
    static const double ARCSPLINE_TAIL_MOVE[4] = {
        -1.0, -0.33333333333333337, 0.33333333333333326, 1.0};
    """
    const double* TAIL_V "ARCSPLINE_TAIL_V"
    const double* TAIL_LAMBDA "ARCSPLINE_TAIL_LAMBDA"
    const double* TAIL_MOVE "ARCSPLINE_TAIL_MOVE"

cdef enum:
    GRID_V = 6
    GRID_LAMBDA = 7
    MOVES = 4
    ROUNDS = 8
    # Screening samples per arc: on the first grid (which only picks the search's start),
    # and in the pattern search.
    COARSE_SAMPLES = 5
    SAMPLES = 8

cdef extern from *:
    """
    /* Each round shrinks the moves by this factor. A candidate screened below GOOD times the
       tolerance stops the search (the proof follows); one above HOPELESS times it after the
       first grid is given up, the bound decaying towards 1 by HOPELESS_DECAY a round (on 400
       random spirals every triarc proven started below 1.9 times the tolerance). */
    #define ARCSPLINE_SHRINK 0.55
    #define ARCSPLINE_GOOD 0.97
    #define ARCSPLINE_HOPELESS 2.5
    #define ARCSPLINE_HOPELESS_DECAY 0.6
    /* The winner's screened deviation must be at most this fraction of the tolerance. */
    #define ARCSPLINE_PROVE_BELOW 0.999
    """
    const double SHRINK "ARCSPLINE_SHRINK"
    const double GOOD "ARCSPLINE_GOOD"
    const double HOPELESS "ARCSPLINE_HOPELESS"
    const double HOPELESS_DECAY "ARCSPLINE_HOPELESS_DECAY"
    const double PROVE_BELOW "ARCSPLINE_PROVE_BELOW"


cdef struct Ends:
    # What every candidate of one tail shares: its ends and their directions.
    double ua
    Vec a
    Vec b
    double phi_a
    double phi_b
    Vec ta        # the unit tangents there
    Vec tb


cdef inline Ends ends_of(const Piece* s, double ua) noexcept nogil:
    cdef Ends e
    e.ua, e.a, e.b = ua, point(s, ua), point(s, 1.0)
    e.phi_a, e.phi_b = tangent(s, ua, &e.ta), tangent(s, 1.0, &e.tb)
    return e


cdef struct Lead:
    # Arc 0 of a candidate: from A to the first joint J1 = Q(v) + δ·N(v), tangent at A.
    Vec j
    Vec t1        # the unit tangent at J1
    double psi1   # its direction
    double kappa0
    Vec d         # B − J1


cdef inline Lead lead(const Piece* s, const Ends* e, double v, double delta) noexcept nogil:
    cdef Vec tv = unit_tangent(s, v)
    cdef double nx = -tv.y, ny = tv.x
    cdef Vec o = offset(s, e.ua, v)
    cdef double cx = o.x + delta * nx, cy = o.y + delta * ny  # J1 − A
    cdef double square = cx * cx + cy * cy
    # Arc 0 turns by 2(χ0 − φ_a), χ0 the direction of J1 − A: κ0 = 2·sin(χ0 − φ_a)/|J1 − A|
    # and ψ1 = 2χ0 − φ_a, from the cosine and sine of χ0 and of 2χ0.
    cdef Lead arc0
    arc0.kappa0 = 2.0 * (cy * e.ta.x - cx * e.ta.y) / square
    cdef double cos2 = (cx * cx - cy * cy) / square, sin2 = 2.0 * cx * cy / square
    arc0.t1 = vec(cos2 * e.ta.x + sin2 * e.ta.y, sin2 * e.ta.x - cos2 * e.ta.y)
    arc0.psi1 = 2.0 * atan2(cy, cx) - e.phi_a
    arc0.j = vec(e.a.x + cx, e.a.y + cy)
    arc0.d = offset(s, v, 1.0)
    arc0.d.x, arc0.d.y = arc0.d.x - delta * nx, arc0.d.y - delta * ny
    return arc0


cdef inline Sabin trail(const Ends* e, const Lead* arc0, double lam) noexcept nogil:
    """Arcs 1 and 2: Sabin's biarc from ``(J1, ψ1)`` to ``(B, φ_b)``."""
    cdef Chord c = chord(arc0.j, arc0.psi1, arc0.t1, arc0.d, e.phi_b, e.tb)
    return sabin_biarc(&c, lam)


cdef bint triarc(
    const Piece* s, const Ends* e, double v, double delta, double lam, Triarc* t,
    Vec* directions
) noexcept nogil:
    """The triarc of the parameters ``(v, δ, λ)`` into ``t`` (with its arcs' unit start
    tangents), its joints' split parameters exact; whether it is valid."""
    cdef Lead first = lead(s, e, v, delta)
    cdef Sabin b = trail(e, &first, lam)
    directions[0], directions[1], directions[2] = e.ta, first.t1, b.t
    cdef double split1 = joint_split(s, first.j, first.t1.x, first.t1.y)
    cdef double split2 = joint_split(s, b.g, b.t.x, b.t.y)
    t.x[0], t.x[1], t.x[2], t.x[3] = e.a.x, first.j.x, b.g.x, e.b.x
    t.y[0], t.y[1], t.y[2], t.y[3] = e.a.y, first.j.y, b.g.y, e.b.y
    t.phi[0], t.phi[1], t.phi[2], t.phi[3] = e.phi_a, first.psi1, b.psi, e.phi_b
    t.s[0], t.s[1], t.s[2], t.s[3] = e.ua, split1, split2, 1.0
    t.kappa[0], t.kappa[1], t.kappa[2] = first.kappa0, b.kappa0, b.kappa1
    return b.ok and e.ua < split1 < split2 < 1.0


cdef struct Screen:
    # A candidate's first joint (v, δ) screened: what arc 0 needs, and its score, which do
    # not depend on λ (the candidates of one first joint share them).
    double v
    Lead lead
    double split1
    double worst


cdef inline Screen screen_lead(const Piece* s, const Ends* e, double v, double delta,
                               int samples) noexcept nogil:
    """Arc 0 of the candidates with first joint ``(v, δ)``: its largest sampled radial
    distance (``inf`` if invalid), the joint's split parameter guessed by Newton steps."""
    cdef Screen c
    c.v, c.lead = v, lead(s, e, v, delta)
    c.split1 = split_guess(s, c.lead.j, c.lead.t1.x, c.lead.t1.y, e.ua, 1.0, v)
    if e.ua < c.split1:
        c.worst = sampled(s, e.a, e.ta, c.lead.kappa0, e.ua, c.split1, samples)
    else:
        c.worst = INFINITY
    return c


cdef double screened(
    const Piece* s, const Ends* e, const Screen* c, double lam, int samples, double bound
) noexcept nogil:
    """Largest sampled radial distance of the candidate ``(v, δ, λ)`` whose arc 0 is ``c``
    (a lower bound on its deviation); ``inf`` if invalid or not a number. A candidate known
    to score at least ``bound`` is left as soon as it is known (the value returned is then
    at least ``bound``, not its score)."""
    if not c.worst < bound:
        return c.worst
    cdef Sabin b = trail(e, &c.lead, lam)
    cdef double split2 = split_guess(s, b.g, b.t.x, b.t.y, e.ua, 1.0, 0.5 * (e.ua + 1.0))
    if not (b.ok and c.split1 < split2):
        return INFINITY
    cdef double worst = max(c.worst, sampled(s, c.lead.j, c.lead.t1, b.kappa0, c.split1,
                                             split2, samples))
    if not worst < bound:
        return worst
    return max(worst, sampled(s, b.g, b.t, b.kappa1, split2, 1.0, samples))


cdef bint proven(
    const Piece* s, const Ends* e, const double* centre, double tolerance, Triarc* out
) noexcept nogil:
    """Whether the candidate ``centre = (v, δ, λ)`` is a triarc whose three arcs are
    proven within the tolerance (their deviations into ``out``)."""
    cdef Vec directions[3]
    if not triarc(s, e, centre[0], centre[1], centre[2], out, directions):
        return False
    cdef Peak peak
    cdef int i
    for i in range(3):
        peak = arc_deviation(
            s, vec(out.x[i], out.y[i]), directions[i].x, directions[i].y, out.kappa[i],
            vec(out.x[i + 1], out.y[i + 1]), out.s[i], out.s[i + 1], tolerance
        )
        if not peak.value <= tolerance:
            return False
        out.dev[i], out.u_dev[i] = peak.value, peak.u
    return True


cdef bint best_triarc(const Piece* s, double ua, double tolerance, Triarc* out) noexcept nogil:
    """A triarc over ``[u_a, 1]`` proven within ``tolerance`` into ``out``, if one is found.

    The search proves its best candidate whenever a better one screens within
    ``PROVE_BELOW`` of the tolerance, and stops at the first proven one: the proof, not the
    screen, decides, and a proven triarc closes the chain whichever it is.
    """
    cdef Ends e = ends_of(s, ua)
    cdef double span = 1.0 - ua
    cdef double best = INFINITY, score
    cdef double centre[3]
    cdef double trial[3]
    cdef int _round, jv, jd, jl
    centre[0], centre[1], centre[2] = ua + span * TAIL_V[0], 0.0, TAIL_LAMBDA[0]
    cdef Screen lead0
    for jv in range(GRID_V):
        lead0 = screen_lead(s, &e, ua + span * TAIL_V[jv], 0.0, COARSE_SAMPLES)
        for jl in range(GRID_LAMBDA):
            score = screened(s, &e, &lead0, TAIL_LAMBDA[jl], COARSE_SAMPLES, best)
            if score < best:
                best = score
                centre[0], centre[1], centre[2] = lead0.v, 0.0, TAIL_LAMBDA[jl]
    if best <= PROVE_BELOW * tolerance and proven(s, &e, centre, tolerance, out):
        return True
    cdef double width[3]
    width[0], width[1], width[2] = span * 0.07, tolerance * 0.5, 0.1
    cdef double decay = 1.0, lo = ua + 1e-9 * span, hi = 1.0 - 1e-9 * span
    cdef double round_best
    cdef double round_centre[3]
    round_centre[0], round_centre[1], round_centre[2] = centre[0], centre[1], centre[2]
    for _round in range(ROUNDS):
        # Refine only a candidate still above the target and not hopeless.
        if not GOOD * tolerance < best < (1.0 + (HOPELESS - 1.0) * decay) * tolerance:
            break
        decay *= HOPELESS_DECAY
        # Only a candidate better than the best so far can change anything.
        round_best = best
        for jv in range(MOVES):
            trial[0] = min(max(centre[0] + width[0] * TAIL_MOVE[jv], lo), hi)
            for jd in range(MOVES):
                trial[1] = centre[1] + width[1] * TAIL_MOVE[jd]
                lead0 = screen_lead(s, &e, trial[0], trial[1], SAMPLES)
                for jl in range(MOVES):
                    trial[2] = centre[2] + width[2] * TAIL_MOVE[jl]
                    score = screened(s, &e, &lead0, trial[2], SAMPLES, round_best)
                    if score < round_best:
                        round_best = score
                        round_centre[0] = trial[0]
                        round_centre[1] = trial[1]
                        round_centre[2] = trial[2]
        if round_best < best:
            best = round_best
            centre[0], centre[1] = round_centre[0], round_centre[1]
            centre[2] = round_centre[2]
            if best <= PROVE_BELOW * tolerance and proven(s, &e, centre, tolerance, out):
                return True
        width[0] *= SHRINK
        width[1] *= SHRINK
        width[2] *= SHRINK
    return False
