"""The baseline: Walton & Meek's method written plainly, one spiral at a time.

This is what a careful reader of ``docs/method.md`` writes first: pure Python floats, the
formulas in the order it gives them (tangent intersection ``V``, incentre,
``r = ‖P − A‖² / (2·(P − A)·N)``), bisection then Newton for Theorem 1's ``t`` and
Theorem 2's quartic roots, and the recursion of §5. It exists so that benchmarks measure the
core against the same algorithm in the same run; the tests do not use it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

Vec = tuple[float, float]


def _add(p: Vec, q: Vec) -> Vec:
    return (p[0] + q[0], p[1] + q[1])


def _sub(p: Vec, q: Vec) -> Vec:
    return (p[0] - q[0], p[1] - q[1])


def _mul(s: float, p: Vec) -> Vec:
    return (s * p[0], s * p[1])


def _dot(p: Vec, q: Vec) -> float:
    return p[0] * q[0] + p[1] * q[1]


def _cross(p: Vec, q: Vec) -> float:
    return p[0] * q[1] - p[1] * q[0]


def _norm(p: Vec) -> float:
    return math.hypot(p[0], p[1])


def _unit(p: Vec) -> Vec:
    return _mul(1.0 / _norm(p), p)


def _normal(t: Vec) -> Vec:
    return (-t[1], t[0])


@dataclass(frozen=True)
class PlainArc:
    start: Vec
    end: Vec
    center: Vec
    radius: float


@dataclass(frozen=True)
class PlainSpiral:
    b: tuple[Vec, Vec, Vec, Vec]
    a: float
    bb: float
    t0: Vec
    t1: Vec

    def eval(self, u: float) -> Vec:
        s = 1.0 - u
        w = (s * s * s, 3.0 * s * s * u, 3.0 * s * u * u, u * u * u)
        return (
            sum(wi * p[0] for wi, p in zip(w, self.b, strict=True)),
            sum(wi * p[1] for wi, p in zip(w, self.b, strict=True)),
        )

    def deriv(self, u: float) -> Vec:
        k = _sub(_mul(self.bb, self.t1), _mul(self.a, self.t0))
        return _add(_mul(3.0 * self.a, self.t0), _mul(3.0 * u * u, k))


def make_spiral(start: Vec, tangent: Vec, turn_angle_deg: float, curvature: float) -> PlainSpiral:
    th = math.radians(turn_angle_deg)
    c = abs(curvature)
    a = 25.0 * math.tan(th) / (54.0 * c * math.cos(th))
    bb = 5.0 * math.tan(th) / (9.0 * c)
    t0 = _unit(tangent)
    phi = th if curvature > 0 else -th
    t1 = (
        t0[0] * math.cos(phi) - t0[1] * math.sin(phi),
        t0[0] * math.sin(phi) + t0[1] * math.cos(phi),
    )
    b1 = _add(start, _mul(a, t0))
    b2 = _add(b1, _mul(a, t0))
    b3 = _add(b2, _mul(bb, t1))
    return PlainSpiral((start, b1, b2, b3), a, bb, t0, t1)


def _root(f, df, lo: float, hi: float) -> float:
    """Bisection to a narrow bracket, then Newton (docs/method.md §3–§4)."""
    flo = f(lo)
    for _ in range(20):
        mid = 0.5 * (lo + hi)
        fm = f(mid)
        if (fm < 0) == (flo < 0):
            lo, flo = mid, fm
        else:
            hi = mid
    x = 0.5 * (lo + hi)
    for _ in range(50):
        step = f(x) / df(x)
        x -= step
        if abs(step) <= 1e-15 * max(1.0, abs(x)):
            break
    return x


def _circle(a: Vec, t: Vec, p: Vec) -> tuple[Vec, float]:
    n = _normal(t)
    d = _sub(p, a)
    r = _dot(d, d) / (2.0 * _dot(d, n))
    return _add(a, _mul(r, n)), r


def _alphas(sp: PlainSpiral, c: Vec) -> tuple[float, float, float, float]:
    """Theorem 2's α1..α4 for the circle centred at ``c``."""
    k = _sub(_mul(sp.bb, sp.t1), _mul(sp.a, sp.t0))
    t0t1 = _dot(sp.t0, sp.t1)
    return (
        3.0 * sp.a * sp.a,
        _dot(k, _sub(sp.b[0], c)),
        4.0 * sp.a * (sp.bb * t0t1 - sp.a),
        sp.a * sp.a - 2.0 * sp.a * sp.bb * t0t1 + sp.bb * sp.bb,
    )


def _q(al: tuple[float, float, float, float], ui: float, u: float) -> float:
    sym4 = u**4 + u**3 * ui + u * u * ui * ui + u * ui**3 + ui**4
    return al[0] + al[1] * (u + ui) + al[2] * (u * u + u * ui + ui * ui) + al[3] * sym4


def _dq(al: tuple[float, float, float, float], ui: float, u: float) -> float:
    dsym4 = 4 * u**3 + 3 * u * u * ui + 2 * u * ui * ui + ui**3
    return al[1] + al[2] * (2 * u + ui) + al[3] * dsym4


def _biarc(sp: PlainSpiral, u0: float, u1: float) -> tuple[list[PlainArc], float, float]:
    a0, a1 = sp.eval(u0), sp.eval(u1)
    ta0, ta1 = _unit(sp.deriv(u0)), _unit(sp.deriv(u1))
    lam = _cross(_sub(a1, a0), ta1) / _cross(ta0, ta1)
    v = _add(a0, _mul(lam, ta0))
    la, lb, lc = _norm(_sub(v, a1)), _norm(_sub(a1, a0)), _norm(_sub(a0, v))
    per = la + lb + lc
    g = _mul(1.0 / per, _add(_add(_mul(la, a0), _mul(lb, v)), _mul(lc, a1)))
    c0, r0 = _circle(a0, ta0, g)
    c1, r1 = _circle(a1, ta1, g)
    h = _unit(_sub(a1, a0))
    t = _root(lambda u: _dot(_sub(sp.eval(u), g), h), lambda u: _dot(sp.deriv(u), h), u0, u1)
    best, u_best = _norm(_sub(sp.eval(t), g)), t
    for c, r, ui, lo, hi in ((c0, r0, u0, u0, t), (c1, r1, u1, t, u1)):
        coef = _alphas(sp, c)
        if _q(coef, ui, lo) * _q(coef, ui, hi) < 0:
            root = _root(
                lambda u, coef=coef, ui=ui: _q(coef, ui, u),
                lambda u, coef=coef, ui=ui: _dq(coef, ui, u),
                lo,
                hi,
            )
            e = abs(_norm(_sub(sp.eval(root), c)) - abs(r))
            if e > best:
                best, u_best = e, root
    arcs = [PlainArc(a0, g, c0, abs(r0)), PlainArc(g, a1, c1, abs(r1))]
    return arcs, best, u_best


def plain_approximate(
    start: Vec, start_tangent: Vec, turn_angle_deg: float, end_curvature: float, tolerance: float
) -> list[PlainArc]:
    """The arcs of Walton & Meek's subdivision (§5), recursively, for one spiral."""
    sp = make_spiral(start, start_tangent, turn_angle_deg, end_curvature)
    out: list[PlainArc] = []

    def recurse(u0: float, u1: float) -> None:
        arcs, delta, u_d = _biarc(sp, u0, u1)
        if delta <= tolerance:
            out.extend(arcs)
        else:
            recurse(u0, u_d)
            recurse(u_d, u1)

    recurse(0.0, 1.0)
    return out
