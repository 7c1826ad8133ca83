# cython: language_level=3
"""Sabin's family of biarcs between two points with given tangents (docs/fewest-arcs.md §1).

From ``P0`` (direction ``φ0``) to ``P1 = P0 + D`` (direction ``φ1``) the biarcs form a
one-parameter family: their joints lie on a circle through both ends (M.A. Sabin, *The use of
piecewise forms for the numerical representation of shape*, 1977). With ``χ`` the chord's
direction, the joint's tangent ``ψ`` ranges over ``(2χ − φ1, 2χ − φ0)`` (the incentre biarc
is ``ψ = χ``) and is taken as ``χ − β + λ(α + β)``, ``λ ∈ (0, 1)``, ``α = χ − φ0``,
``β = φ1 − χ``. Each arc's chord runs along the mean of its end directions,
``h0 = (φ0 + ψ)/2`` and ``h1 = (ψ + φ1)/2``, so the chord lengths solve
``D = L0·e(h0) + L1·e(h1)``; the joint is ``G = P0 + L0·e(h0)`` and the curvatures are
``κ0 = 2·sin(h0 − φ0)/L0``, ``κ1 = 2·sin(φ1 − h1)/L1``. The sines and cosines of ``ψ = 2h0 − φ0``
and of the half turns follow from those of ``h0``, ``h1``, ``φ0`` and ``φ1`` by the angle-sum
formulas: two ``sincos`` per member.
"""

from libc.math cimport atan2, cos, isfinite, sin

from arcspline.geometry.maths.vec cimport Vec, vec


cdef struct Chord:
    # What every member of one family shares: the ends and their directions.
    Vec p0
    Vec d        # P1 − P0
    double phi0
    double phi1
    Vec t0       # (cos φ0, sin φ0)
    Vec t1       # (cos φ1, sin φ1)
    double chi   # the direction of d
    double den   # sin((φ1 − φ0)/2)


cdef struct Sabin:
    double psi      # the direction at the joint
    Vec t           # (cos ψ, sin ψ)
    double kappa0   # the arcs' signed curvatures
    double kappa1
    Vec g           # the joint
    bint ok         # a biarc: both chords positive, the curvatures finite


cdef inline Chord chord(Vec p0, double phi0, Vec t0, Vec d, double phi1, Vec t1) noexcept nogil:
    """The family from ``p0`` (direction ``φ0``, unit tangent ``t0``) to ``p0 + d``
    (``φ1``, ``t1``)."""
    cdef Chord c
    c.p0, c.d, c.phi0, c.phi1, c.t0, c.t1 = p0, d, phi0, phi1, t0, t1
    c.chi = atan2(d.y, d.x)
    c.den = sin(0.5 * (phi1 - phi0))
    return c


cdef inline Sabin sabin_biarc(const Chord* c, double lam) noexcept nogil:
    """The member of join parameter ``λ``."""
    cdef Sabin b
    cdef double alpha = c.chi - c.phi0, beta = c.phi1 - c.chi
    b.psi = c.chi - beta + lam * (alpha + beta)
    cdef double h0 = 0.5 * (c.phi0 + b.psi), h1 = 0.5 * (b.psi + c.phi1)
    cdef double c0 = cos(h0), s0 = sin(h0), c1 = cos(h1), s1 = sin(h1)
    cdef double len0 = (c.d.x * s1 - c.d.y * c1) / c.den
    cdef double len1 = (c0 * c.d.y - s0 * c.d.x) / c.den
    # sin(h0 − φ0) and sin(φ1 − h1); ψ = 2h0 − φ0.
    b.kappa0 = 2.0 * (s0 * c.t0.x - c0 * c.t0.y) / len0
    b.kappa1 = 2.0 * (c.t1.y * c1 - c.t1.x * s1) / len1
    cdef double cos2 = c0 * c0 - s0 * s0, sin2 = 2.0 * s0 * c0
    b.t = vec(cos2 * c.t0.x + sin2 * c.t0.y, sin2 * c.t0.x - cos2 * c.t0.y)
    b.g = vec(c.p0.x + len0 * c0, c.p0.y + len0 * s0)
    b.ok = (
        c.den > 0.0 and len0 > 0.0 and len1 > 0.0 and isfinite(b.kappa0) and isfinite(b.kappa1)
    )
    return b
