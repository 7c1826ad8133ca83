"""An independent oracle for the geometry core's guarantees.

It shares no code with ``arcspline.geometry``: it reads only a spiral's four control points and
the public fields of a result (the segments in path order and the statistics), and measures
everything by its own computation:

* the cubic Bézier in Bernstein form, ``Q(u) = Σ C(3,i)·uⁱ·(1−u)³⁻ⁱ·Bᵢ``, and its derivatives;
* the exact distance from a point to an arc (centre ``C``, radius ``r``, end points, turning
  sense): ``|‖P − C‖ − r|`` when the point's polar angle about ``C`` lies within the arc's
  sweep, otherwise the distance to the nearer end point; and to a line segment;
* the two-sided distance between spiral and arc spline by dense sampling, every sampled
  maximum refined by golden-section search; distances to the spiral are exact foot points
  (Newton on ``(Q(u) − P)·Q'(u) = 0`` started from a global coarse search), not chords;
* G1 continuity and end conditions, each arc's internal consistency, and the statistics;
* the control points of the paper's five parameters (:func:`paper_control_points`), in
  50-digit decimal arithmetic with θ in radians by its own Taylor series: the core's
  floating-point formula (``cos(radians θ)``, which near 90° loses the relative accuracy of
  ``cos θ``) is never used, so a test built on it cannot share its error.

Arithmetic that can cancel (the distance to an arc of huge radius) runs in ``np.longdouble``
(64-bit significand on x86-64) in a frame whose origin is the spiral's first control point.
Arcs are taken to turn less than π, as every arc of the method does (each turns less than the
spiral's θ < 90°); one that does not is reported by :func:`arc_violations`.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from decimal import Decimal, localcontext
from typing import Any

import numpy as np
import numpy.typing as npt

LD = np.longdouble
EPS = float(np.finfo(np.float64).eps)
Array = npt.NDArray[Any]

#: G1: unit tangents on either side of a joint agree to this angle, plus rounding slack.
ANGLE_TOL_RAD = 1e-9
#: G1: joined end points agree to this fraction of the chord, plus rounding slack.
GAP_RTOL = 1e-12
#: Reported and measured deviations agree to this relative accuracy (plus rounding slack).
DEVIATION_RTOL = 1e-3
#: Rounding slack, in units of ``EPS × coordinate scale`` (the spacing of float64 there).
ROUNDING_ULPS = 64.0


# -- vectors ---------------------------------------------------------------------------


def _cross(a: Array, b: Array) -> Array:
    return a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]


def _dot(a: Array, b: Array) -> Array:
    return a[..., 0] * b[..., 0] + a[..., 1] * b[..., 1]


def _norm(a: Array) -> Array:
    return np.hypot(a[..., 0], a[..., 1])


def _rot90(a: Array) -> Array:
    return np.stack([-a[..., 1], a[..., 0]], axis=-1)


def _angle_between(a: Array, b: Array) -> Array:
    """Unsigned angle between two vectors, ``atan2(|a×b|, a·b)`` (accurate near 0)."""
    return np.arctan2(np.abs(_cross(a, b)), _dot(a, b))


# -- the paper's spiral from its parameters, exactly -------------------------------------

#: Working precision of :func:`paper_control_points`, in decimal digits: 50 survive the
#: cancellation of ``cos θ`` near 90° (its Taylor terms reach ~1.6 while it can be ~1e-16).
DECIMAL_DIGITS = 70
#: π to 80 digits.
PI = Decimal("3.1415926535897932384626433832795028841971693993751058209749445923078164062862")


def _cos_sin(x: Decimal) -> tuple[Decimal, Decimal]:
    """``cos x`` and ``sin x`` by their Taylor series, ``0 ≤ x ≤ 2`` (all terms kept until
    they drop below the working precision)."""
    cos, sin, term, k = Decimal(0), Decimal(0), Decimal(1), 0
    limit = Decimal(10) ** -(DECIMAL_DIGITS + 5)
    while abs(term) > limit or k < 4:
        if k % 4 == 0:
            cos += term
        elif k % 4 == 1:
            sin += term
        elif k % 4 == 2:
            cos -= term
        else:
            sin -= term
        k += 1
        term = term * x / k
    return cos, sin


def paper_control_points(
    start: Sequence[float], start_tangent: Sequence[float], turn_angle_deg: float, c: float
) -> Array:
    """The four control points of docs/method.md §1 for the parameters exactly as given
    (each float taken at its exact binary value), rounded to float64 only at the end::

        a = 25·tan θ / (54·|c|·cos θ),  b = 5·tan θ / (9·|c|),
        B1 = B0 + a·T0,  B2 = B1 + a·T0,  B3 = B2 + b·T1  (T1: T0 turned by θ, sign of c).
    """
    with localcontext() as ctx:
        ctx.prec = DECIMAL_DIGITS
        theta = Decimal(turn_angle_deg) * PI / 180
        cos, sin = _cos_sin(theta)
        sigma = 1 if c > 0 else -1
        tx, ty = Decimal(start_tangent[0]), Decimal(start_tangent[1])
        norm = (tx * tx + ty * ty).sqrt()
        tx, ty = tx / norm, ty / norm
        a = 25 * sin / (54 * abs(Decimal(c)) * cos * cos)
        b = 5 * sin / (9 * abs(Decimal(c)) * cos)
        ux, uy = cos * tx - sigma * sin * ty, sigma * sin * tx + cos * ty
        x0, y0 = Decimal(start[0]), Decimal(start[1])
        points = [
            (x0, y0),
            (x0 + a * tx, y0 + a * ty),
            (x0 + 2 * a * tx, y0 + 2 * a * ty),
            (x0 + 2 * a * tx + b * ux, y0 + 2 * a * ty + b * uy),
        ]
        return np.array([[float(x), float(y)] for x, y in points], dtype=np.float64)


def paper_end_tangent(
    start_tangent: Sequence[float], turn_angle_deg: float, c: float
) -> tuple[float, float]:
    """``T1``, the unit end tangent of the paper's spiral, in the same exact arithmetic."""
    with localcontext() as ctx:
        ctx.prec = DECIMAL_DIGITS
        cos, sin = _cos_sin(Decimal(turn_angle_deg) * PI / 180)
        sigma = 1 if c > 0 else -1
        tx, ty = Decimal(start_tangent[0]), Decimal(start_tangent[1])
        norm = (tx * tx + ty * ty).sqrt()
        tx, ty = tx / norm, ty / norm
        return float(cos * tx - sigma * sin * ty), float(sigma * sin * tx + cos * ty)


# -- the Bézier curve ------------------------------------------------------------------


def bezier_point(cp: Array, u: Array | float) -> Array:
    """``Q(u) = (1−u)³B0 + 3u(1−u)²B1 + 3u²(1−u)B2 + u³B3``; shape ``(..., 2)``."""
    cp = np.asarray(cp)
    w = np.asarray(u, dtype=cp.dtype)[..., None]
    v = 1 - w
    return v**3 * cp[0] + 3 * w * v**2 * cp[1] + 3 * w**2 * v * cp[2] + w**3 * cp[3]


def bezier_deriv(cp: Array, u: Array | float) -> Array:
    """``Q'(u) = 3[(1−u)²(B1−B0) + 2u(1−u)(B2−B1) + u²(B3−B2)]``."""
    cp = np.asarray(cp)
    d = cp[1:] - cp[:-1]
    w = np.asarray(u, dtype=cp.dtype)[..., None]
    v = 1 - w
    return 3 * (v**2 * d[0] + 2 * w * v * d[1] + w**2 * d[2])


def bezier_deriv2(cp: Array, u: Array | float) -> Array:
    """``Q''(u) = 6[(1−u)(B2 − 2B1 + B0) + u(B3 − 2B2 + B1)]``."""
    cp = np.asarray(cp)
    dd = cp[2:] - 2 * cp[1:-1] + cp[:-2]
    w = np.asarray(u, dtype=cp.dtype)[..., None]
    return 6 * ((1 - w) * dd[0] + w * dd[1])


def signed_curvature(cp: Array, u: Array | float) -> Array:
    """``κ = Q'×Q'' / ‖Q'‖³`` (positive turning left)."""
    d1, d2 = bezier_deriv(cp, u), bezier_deriv2(cp, u)
    result: Array = _cross(d1, d2) / _norm(d1) ** 3
    return result


def arc_length(cp: Array, u0: float = 0.0, u1: float = 1.0, n: int = 1 << 14) -> float:
    """Length of ``Q`` on ``[u0, u1]``: inscribed polylines of n and n/2 chords, Richardson.

    The polyline's error is ``c/n² + O(n⁻⁴)``, so ``(4·L(n) − L(n/2)) / 3`` is exact to
    ``O(n⁻⁴)`` (about 1e-17 relative for n = 16 384 on these smooth curves).
    """
    pts = bezier_point(np.asarray(cp, dtype=LD), np.linspace(u0, u1, n + 1).astype(LD))
    fine = np.sum(_norm(np.diff(pts, axis=0)))
    coarse = np.sum(_norm(np.diff(pts[::2], axis=0)))
    return float((4 * fine - coarse) / 3)


def chord(cp: Array) -> float:
    """``‖B3 − B0‖``: the spiral's size, the reference for relative tolerances."""
    cp = np.asarray(cp, dtype=np.float64)
    return float(np.hypot(*(cp[3] - cp[0])))


def coordinate_scale(cp: Array) -> float:
    """Largest coordinate magnitude of the control points (where rounding happens)."""
    return float(np.max(np.abs(np.asarray(cp, dtype=np.float64))))


def emitted_scale(segment: Any) -> float:
    """Largest number that defines a segment: its coordinates and, for an arc, its radius."""
    values = [*segment.start, *segment.end]
    if segment.type == "arc":
        values += [*segment.center, segment.radius]
    return float(np.max(np.abs(values)))


def rounding_slack(cp: Array) -> float:
    """``64·eps·coordinate scale``: what rounding alone can move a point by."""
    return ROUNDING_ULPS * EPS * coordinate_scale(cp)


# -- distance to the spiral ------------------------------------------------------------


def curve_grid(cp: Array, n: int = 257) -> Array:
    """``n`` parameters spread evenly in arc length plus turning along ``Q``.

    Uniform ``u`` is badly uneven near θ → 90°, where the speed falls from ``3a`` to ``3b =
    3.6a·cos θ`` and nearly all the turning happens within ``1 − u ~ cos θ``. A fine grid,
    graded geometrically towards both ends, is mapped through the cumulative measure
    ``s(u)/L + φ(u)/θ`` (length share plus turning share) and sampled evenly in it, so no
    coarse cell holds more than about ``2/n`` of the length or of the turning.
    """
    cp64 = np.asarray(cp, dtype=np.float64)
    graded = np.logspace(-15.0, 0.0, 1025)
    fine = np.unique(np.concatenate([np.linspace(0.0, 1.0, 4097), graded, 1.0 - graded]))
    fine = fine[(fine >= 0.0) & (fine <= 1.0)]
    q = bezier_point(cp64, fine)
    d = bezier_deriv(cp64, fine)
    length = np.concatenate([[0.0], np.cumsum(_norm(np.diff(q, axis=0)))])
    turn = np.abs(np.unwrap(np.arctan2(d[:, 1], d[:, 0])) - np.arctan2(d[0, 1], d[0, 0]))
    share = np.zeros_like(fine)
    for part in (length, turn):
        if part[-1] > 0:
            share = share + part / part[-1]
    if not share[-1] > 0:
        return np.linspace(0.0, 1.0, n)
    share = np.maximum.accumulate(share)
    grid: Array = np.unique(np.interp(np.linspace(0.0, share[-1], n), share, fine))
    return grid


def distance_to_curve(
    cp: Array, points: Array, grid: Array | None = None, starts: int = 2
) -> tuple[Array, Array]:
    """Exact distance from each point to ``Q([0, 1])`` and the foot parameter ``u``.

    A global coarse search over ``grid`` (default :func:`curve_grid`) picks the ``starts``
    nearest samples; from each, safeguarded Newton on ``g(u) = (Q(u) − P)·Q'(u)`` within
    the neighbouring cells (bisection when a step leaves the bracket) finds a foot; the
    nearest foot wins, its distance evaluated in long double. The answer is never above the
    nearest sample's, so it is an upper bound in the worst case and exact whenever the
    nearest foot lies beside one of the starting samples. ``cp`` and ``points`` share the
    caller's frame.
    """
    cp_ld = np.asarray(cp, dtype=LD)
    pts_ld = np.asarray(points, dtype=LD).reshape(-1, 2)
    cp64, pts64 = cp_ld.astype(np.float64), pts_ld.astype(np.float64)
    grid = curve_grid(cp64) if grid is None else np.asarray(grid, dtype=np.float64)
    k = len(grid)
    starts = min(starts, k)
    qg = bezier_point(cp64, grid)
    nearest = np.empty((len(pts64), starts), dtype=np.intp)
    chunk = max(1, 400_000 // k)
    for b in range(0, len(pts64), chunk):
        d2 = np.sum((pts64[b : b + chunk, None, :] - qg[None, :, :]) ** 2, axis=-1)
        nearest[b : b + chunk] = np.argpartition(d2, starts - 1, axis=1)[:, :starts]
    best_d = np.full(len(pts64), np.inf, dtype=LD)
    best_u = np.zeros(len(pts64))
    for j in range(starts):
        at = nearest[:, j]
        lo, hi, u = grid[np.maximum(at - 1, 0)], grid[np.minimum(at + 1, k - 1)], grid[at]
        for _ in range(16):
            r = bezier_point(cp64, u) - pts64
            d1 = bezier_deriv(cp64, u)
            g = _dot(r, d1)
            gp = _dot(d1, d1) + _dot(r, bezier_deriv2(cp64, u))
            lo = np.where(g < 0, u, lo)
            hi = np.where(g > 0, u, hi)
            ok = gp > 0
            step = u - g / np.where(ok, gp, 1.0)
            new = np.where(ok & (step >= lo) & (step <= hi), step, 0.5 * (lo + hi))
            if np.array_equal(new, u):
                break
            u = new
        for cand in (grid[at], u):
            dist = _norm(bezier_point(cp_ld, cand) - pts_ld)
            better = dist < best_d
            best_d = np.where(better, dist, best_d)
            best_u = np.where(better, cand, best_u)
    shape = np.shape(points)[:-1]
    return best_d.reshape(shape), best_u.reshape(shape)


# -- the segments ----------------------------------------------------------------------


@dataclass(frozen=True)
class Pieces:
    """An arc spline's segments as long-double arrays in the oracle's frame.

    Built only from public segment fields. Lines carry ``center = start``, ``radius = 1``
    and ``sense = 0`` (never used). ``sweep`` is the signed angle from ``start`` to ``end``
    about ``center`` computed here (short way, in (−π, π]), not the reported one.
    """

    is_arc: Array
    start: Array
    end: Array
    center: Array
    radius: Array
    sense: Array
    sweep: Array
    u_start: Array
    u_end: Array

    @classmethod
    def of(cls, segments: Sequence[Any], origin: Array) -> Pieces:
        o = np.asarray(origin, dtype=LD)
        is_arc = np.array([s.type == "arc" for s in segments], dtype=bool)
        start = np.array([s.start for s in segments], dtype=np.float64).astype(LD) - o
        end = np.array([s.end for s in segments], dtype=np.float64).astype(LD) - o
        # A line's centre is a harmless stand-in one unit from its start (never used).
        center = (
            np.array(
                [s.center if s.type == "arc" else (s.start[0], s.start[1] + 1.0) for s in segments],
                dtype=np.float64,
            ).astype(LD)
            - o
        )
        radius = np.array([s.radius if s.type == "arc" else 1.0 for s in segments]).astype(LD)
        sense = np.array(
            [(1.0 if s.direction == "ccw" else -1.0) if s.type == "arc" else 0.0 for s in segments]
        ).astype(LD)
        vs, ve = start - center, end - center
        sweep = np.where(is_arc, np.arctan2(_cross(vs, ve), _dot(vs, ve)), 0)
        return cls(
            is_arc=is_arc,
            start=start,
            end=end,
            center=center,
            radius=radius,
            sense=sense,
            sweep=sweep,
            u_start=np.array([s.u_start for s in segments], dtype=np.float64),
            u_end=np.array([s.u_end for s in segments], dtype=np.float64),
        )

    def __len__(self) -> int:
        return len(self.is_arc)

    def take(self, idx: Array) -> Pieces:
        """The pieces at ``idx`` (any shape), for element-wise or broadcast evaluation."""
        return Pieces(**{f: getattr(self, f)[idx] for f in self.__dataclass_fields__})

    def distance(self, points: Array) -> Array:
        """Distance from ``points[k]`` to piece ``k`` (shapes broadcast)."""
        return _piece_distance(
            points, self.is_arc, self.start, self.end, self.center, self.radius, self.sense
        )

    def point_at(self, s: Array) -> Array:
        """The point at fraction ``s`` of each piece (arcs by angle, exactly on radius r)."""
        s = np.asarray(s, dtype=LD)
        vs = self.start - self.center
        k = self.radius / _norm(vs)
        ang = s * self.sweep
        c, si = np.cos(ang), np.sin(ang)
        rot = np.stack([vs[..., 0] * c - vs[..., 1] * si, vs[..., 0] * si + vs[..., 1] * c], -1)
        arc = self.center + k[..., None] * rot
        line = self.start + s[..., None] * (self.end - self.start)
        return np.where(self.is_arc[..., None], arc, line)

    def tangent_at_start(self) -> Array:
        return self._tangent(self.start)

    def tangent_at_end(self) -> Array:
        return self._tangent(self.end)

    def _tangent(self, at: Array) -> Array:
        # A zero-length line has no direction: NaN, which every check reports as a failure.
        with np.errstate(divide="ignore", invalid="ignore"):
            radial = at - self.center
            arc = self.sense[..., None] * _rot90(radial) / _norm(radial)[..., None]
            chord_ = self.end - self.start
            line = chord_ / _norm(chord_)[..., None]
        return np.where(self.is_arc[..., None], arc, line)


def _piece_distance(
    p: Array, is_arc: Array, s: Array, e: Array, c: Array, r: Array, sense: Array
) -> Array:
    v = p - c
    # Within the sector iff P is on the turning side of ray C→S and not past ray C→E
    # (valid for sweeps below π); P = C counts as inside and is at distance r.
    inside = (_cross(s - c, v) * sense >= 0) & (_cross(v, e - c) * sense >= 0)
    radial = np.abs(_norm(v) - r)
    ends = np.minimum(_norm(p - s), _norm(p - e))
    arc = np.where(inside, radial, ends)
    seg = e - s
    len2 = _dot(seg, seg)
    t = np.clip(_dot(p - s, seg) / np.where(len2 > 0, len2, 1), 0, 1)
    line = _norm(p - s - t[..., None] * seg)
    return np.where(is_arc, arc, line)


def point_arc_distance(
    points: Array, center: Array, radius: float, start: Array, end: Array, ccw: bool
) -> Array:
    """Exact distance from points to the arc from ``start`` to ``end`` about ``center``."""
    ld = lambda a: np.asarray(a, dtype=LD)  # noqa: E731
    return _piece_distance(
        ld(points), np.True_, ld(start), ld(end), ld(center), ld(radius), ld(1 if ccw else -1)
    )


def point_line_distance(points: Array, start: Array, end: Array) -> Array:
    """Exact distance from points to the segment ``start``–``end``."""
    ld = lambda a: np.asarray(a, dtype=LD)  # noqa: E731
    return _piece_distance(ld(points), np.False_, ld(start), ld(end), ld(start), ld(1), ld(0))


# -- two-sided distance ----------------------------------------------------------------


def _golden_max(
    f: Callable[[Array], Array], lo: Array, hi: Array, iterations: int = 32
) -> tuple[Array, Array]:
    """Element-wise golden-section search for the maximum of ``f`` on ``[lo, hi]``."""
    r = (math.sqrt(5.0) - 1.0) / 2.0
    a, b = np.asarray(lo, dtype=np.float64), np.asarray(hi, dtype=np.float64)
    x1, x2 = b - r * (b - a), a + r * (b - a)
    f1, f2 = f(x1), f(x2)
    for _ in range(iterations):
        left = f1 >= f2
        a, b = np.where(left, a, x1), np.where(left, x2, b)
        new = np.where(left, b - r * (b - a), a + r * (b - a))
        fn = f(new)
        x1, x2 = np.where(left, new, x2), np.where(left, x1, new)
        f1, f2 = np.where(left, fn, f2), np.where(left, f1, fn)
    pick = f1 >= f2
    return np.where(pick, x1, x2), np.where(pick, f1, f2)


@dataclass(frozen=True)
class Deviation:
    """The two-sided distance between a spiral and an arc spline, as the oracle measures it.

    ``spiral_to_spline``: largest distance from a spiral point ``Q(u)`` to the segments whose
    reported ``u`` range contains ``u`` or neighbours it (an upper bound of the distance to
    the whole spline). ``global_spiral_to_spline``: the same against *all* segments on a
    coarser uniform sample, using no reported ``u`` range. ``spline_to_spiral``: largest
    distance from a point of the spline to the whole spiral. ``segment_deviation[i]``: the
    largest distance from the spiral piece ``[u_start, u_end]`` of segment ``i`` to that
    segment, reached at ``segment_u_at_max[i]`` (what the core reports per segment).
    """

    spiral_to_spline: float
    u_spiral_to_spline: float
    global_spiral_to_spline: float
    u_global_spiral_to_spline: float
    spline_to_spiral: float
    segment_spline_to_spiral: int
    point_spline_to_spiral: tuple[float, float]
    segment_deviation: tuple[float, ...]
    segment_u_at_max: tuple[float, ...]

    @property
    def max(self) -> float:
        """The two-sided maximum distance."""
        return max(self.spiral_to_spline, self.global_spiral_to_spline, self.spline_to_spiral)


def measure(
    cp: Array, segments: Sequence[Any], samples: int = 30_000, pairs: int = 400_000
) -> Deviation:
    """Measure the two-sided distance between ``Q`` (control points ``cp``) and ``segments``.

    ``samples`` is the budget of spiral points for the per-segment pass (at least 17 per
    segment); the spline side takes an eighth of it (at least 17 per segment), the global
    pass about ``pairs`` point–segment pairs (at least 257 points). Every sampled
    maximum is refined by golden-section search, so the result is exact to ~1e-10 relative.
    """
    cp64 = np.asarray(cp, dtype=np.float64)
    origin = cp64[0].astype(LD)
    cpr = cp64.astype(LD) - origin
    pieces = Pieces.of(segments, origin)
    n = len(pieces)
    idx = np.arange(n)

    def own(i: Array, u: Array) -> Array:
        return pieces.take(i).distance(bezier_point(cpr, u))

    def window(i: Array, u: Array) -> Array:
        q = bezier_point(cpr, u)
        d = pieces.take(i).distance(q)
        for j in (np.maximum(i - 1, 0), np.minimum(i + 1, n - 1)):
            d = np.minimum(d, pieces.take(j).distance(q))
        return d

    # Spiral side, per segment: own segment and the window around it.
    m = int(np.clip(samples // max(n, 1), 17, 2049))
    frac = np.linspace(0.0, 1.0, m)
    us, ue = pieces.u_start, pieces.u_end
    grid = us[:, None] + (ue - us)[:, None] * frac[None, :]
    rows = np.repeat(idx[:, None], m, axis=1)
    q = bezier_point(cpr, grid)
    d_own = pieces.take(rows).distance(q)
    d_win = d_own
    for j in (np.maximum(rows - 1, 0), np.minimum(rows + 1, n - 1)):
        d_win = np.minimum(d_win, pieces.take(j).distance(q))
    seg_u, seg_dev = _refined_max(own, grid, d_own, us, ue)
    win_u, win_dev = _refined_max(window, grid, d_win, us, ue)
    k = int(np.argmax(win_dev))

    # Spiral side, globally: an even sample (plus every reported break) against all.
    g = int(np.clip(pairs // max(n, 1), 257, 4_097))
    ug = np.unique(np.concatenate([curve_grid(cp64, g), us, ue]))
    ug = ug[(ug >= 0.0) & (ug <= 1.0)]
    dg = np.empty(len(ug), dtype=LD)
    chunk = max(1, 200_000 // max(n, 1))
    every = pieces.take(idx[None, :])
    for b in range(0, len(ug), chunk):
        q = bezier_point(cpr, ug[b : b + chunk])[:, None, :]
        dg[b : b + chunk] = np.min(every.distance(q), axis=1)
    kg = int(np.argmax(dg))

    # Spline side: points of each segment against the whole spiral.
    m2 = int(np.clip(samples // (8 * max(n, 1)), 17, 257))
    sgrid = np.broadcast_to(np.linspace(0.0, 1.0, m2), (n, m2))
    coarse = curve_grid(cp64)

    def to_spiral(i: Array, s: Array) -> Array:
        return distance_to_curve(cpr, pieces.take(i).point_at(s), coarse)[0]

    sampled = to_spiral(rows[:, :m2], sgrid)
    s_at, s_dev = _refined_max(to_spiral, sgrid, sampled, np.zeros(n), np.ones(n))
    ks = int(np.argmax(s_dev))
    worst = pieces.take(np.array(ks)).point_at(np.array(s_at[ks])) + origin

    return Deviation(
        spiral_to_spline=float(win_dev[k]),
        u_spiral_to_spline=float(win_u[k]),
        global_spiral_to_spline=float(dg[kg]),
        u_global_spiral_to_spline=float(ug[kg]),
        spline_to_spiral=float(s_dev[ks]),
        segment_spline_to_spiral=ks,
        point_spline_to_spiral=(float(worst[0]), float(worst[1])),
        segment_deviation=tuple(float(x) for x in seg_dev),
        segment_u_at_max=tuple(float(x) for x in seg_u),
    )


def _refined_max(
    f: Callable[[Array, Array], Array], grid: Array, values: Array, lo: Array, hi: Array
) -> tuple[Array, Array]:
    """Per row ``r``: the maximum of ``values = f(r, grid)`` refined by golden section on
    the cells either side of it (never below the sampled value)."""
    j = np.argmax(values, axis=1)
    n, m = grid.shape
    r = np.arange(n)
    a = np.maximum(grid[r, np.maximum(j - 1, 0)], lo)
    b = np.minimum(grid[r, np.minimum(j + 1, m - 1)], hi)
    x, fx = _golden_max(lambda x: f(r, x), a, b)
    sampled = values[r, j]
    better = fx > sampled
    return np.where(better, x, grid[r, j]), np.where(better, fx, sampled)


def deviation_at(cp: Array, segment: Any, u: float) -> float:
    """Distance from ``Q(u)`` to one segment."""
    cp64 = np.asarray(cp, dtype=np.float64)
    origin = cp64[0].astype(LD)
    pieces = Pieces.of([segment], origin)
    return float(pieces.distance(bezier_point(cp64.astype(LD) - origin, np.array([u])))[0])


# -- continuity and end conditions -----------------------------------------------------


@dataclass(frozen=True)
class Continuity:
    """Gaps and tangent angles at the spline's ends and joints, with their allowed bounds.

    Gap bound: ``1e-12·chord + 64·eps·scale``. Angle bound at a piece: ``1e-9 rad`` plus the
    rounding of a direction taken from points ``ρ`` apart (``64·eps·scale/ρ``, ``ρ`` the
    radius of an arc or the length of a line); at the spiral's ends, plus the same for the
    control-point leg that gives the spiral's tangent.
    """

    start_gap: float
    end_gap: float
    start_angle_rad: float
    end_angle_rad: float
    joint_gap: tuple[float, ...]
    joint_angle_rad: tuple[float, ...]
    gap_bound: float
    start_angle_bound: float
    end_angle_bound: float
    joint_angle_bound: tuple[float, ...]

    def violations(self) -> list[str]:
        out = []
        if not self.start_gap <= self.gap_bound:
            out.append(
                f"first segment starts {self.start_gap:.3g} from Q(0) (allowed "
                f"{self.gap_bound:.3g})"
            )
        if not self.end_gap <= self.gap_bound:
            out.append(
                f"last segment ends {self.end_gap:.3g} from Q(1) (allowed {self.gap_bound:.3g})"
            )
        if not self.start_angle_rad <= self.start_angle_bound:
            out.append(
                f"start tangent off by {self.start_angle_rad:.3g} rad (allowed "
                f"{self.start_angle_bound:.3g})"
            )
        if not self.end_angle_rad <= self.end_angle_bound:
            out.append(
                f"end tangent off by {self.end_angle_rad:.3g} rad (allowed "
                f"{self.end_angle_bound:.3g})"
            )
        for i, (gap, ang, bound) in enumerate(
            zip(self.joint_gap, self.joint_angle_rad, self.joint_angle_bound, strict=True)
        ):
            if not gap <= self.gap_bound:
                out.append(
                    f"joint {i}/{i + 1}: end points {gap:.3g} apart (allowed {self.gap_bound:.3g})"
                )
            if not ang <= bound:
                out.append(f"joint {i}/{i + 1}: tangents {ang:.3g} rad apart (allowed {bound:.3g})")
        return out


def continuity(cp: Array, segments: Sequence[Any]) -> Continuity:
    """End points and unit tangents of ``segments`` against ``Q`` and each other.

    The spiral's end tangents are ``B1 − B0`` and ``B3 − B2``; an arc's tangent at a point
    is its radius vector turned by 90° in its sense; a line's is its chord.
    """
    cp64 = np.asarray(cp, dtype=np.float64)
    origin = cp64[0].astype(LD)
    cpr = cp64.astype(LD) - origin
    pieces = Pieces.of(segments, origin)
    scale = coordinate_scale(cp64)
    for s in segments:
        scale = max(scale, float(np.max(np.abs([*s.start, *s.end]))))
    rounding = ROUNDING_ULPS * EPS * scale
    rho = np.where(pieces.is_arc, pieces.radius, _norm(pieces.end - pieces.start))
    rho = np.where(rho > 0, rho, np.inf).astype(np.float64)
    slack = ANGLE_TOL_RAD + rounding / rho
    t_start, t_end = pieces.tangent_at_start(), pieces.tangent_at_end()
    return Continuity(
        start_gap=float(_norm(pieces.start[0] - cpr[0])),
        end_gap=float(_norm(pieces.end[-1] - cpr[3])),
        start_angle_rad=float(_angle_between(t_start[0], cpr[1] - cpr[0])),
        end_angle_rad=float(_angle_between(t_end[-1], cpr[3] - cpr[2])),
        joint_gap=tuple(float(x) for x in _norm(pieces.end[:-1] - pieces.start[1:])),
        joint_angle_rad=tuple(float(x) for x in _angle_between(t_end[:-1], t_start[1:])),
        gap_bound=GAP_RTOL * chord(cp64) + rounding,
        # The spiral's own end tangents come from rounded control points too.
        start_angle_bound=float(slack[0]) + rounding / float(_norm(cpr[1] - cpr[0])),
        end_angle_bound=float(slack[-1]) + rounding / float(_norm(cpr[3] - cpr[2])),
        joint_angle_bound=tuple(float(x) for x in slack[:-1] + slack[1:]),
    )


# -- each segment on its own -----------------------------------------------------------


def _wrap(angle: float) -> float:
    return (angle + math.pi) % (2 * math.pi) - math.pi


def arc_violations(segments: Sequence[Any]) -> list[str]:
    """Each segment's internal consistency.

    Arcs: ``radius > 0``; ``‖start − C‖ = ‖end − C‖ = radius``; ``start_angle_rad`` is the
    polar angle of ``start``; ``sweep_rad`` is the signed angle from start to end, turns
    less than π and agrees with ``direction``; ``length = radius·|sweep|``. Lines:
    ``length = ‖end − start‖``. Slack: 64 ulps of the largest coordinate or radius.
    """
    out = []
    for i, s in enumerate(segments):
        start = np.array(s.start, dtype=LD)
        end = np.array(s.end, dtype=LD)
        if s.type != "arc":
            span = float(_norm(end - start))
            scale = float(np.max(np.abs([*s.start, *s.end])))
            if not abs(s.length - span) <= 1e-12 * span + ROUNDING_ULPS * EPS * scale:
                out.append(f"line {i}: length {s.length!r} but |end − start| = {span!r}")
            continue
        center = np.array(s.center, dtype=LD)
        r = float(s.radius)
        if not (r > 0 and math.isfinite(r)):
            out.append(f"arc {i}: radius {r!r} is not finite and positive")
            continue
        scale = max(float(np.max(np.abs([*s.start, *s.end, *s.center]))), r)
        tol = ROUNDING_ULPS * EPS * scale
        vs, ve = start - center, end - center
        for name, v in (("start", vs), ("end", ve)):
            gap = float(_norm(v)) - r
            if not abs(gap) <= tol:
                out.append(f"arc {i}: |{name} − centre| − radius = {gap:.3g} (allowed {tol:.3g})")
        angle_tol = 1e-12 + tol / r
        polar = float(np.arctan2(vs[1], vs[0]))
        if not abs(_wrap(s.start_angle_rad - polar)) <= angle_tol:
            out.append(
                f"arc {i}: start_angle_rad {s.start_angle_rad!r} but the polar angle "
                f"of start is {polar!r}"
            )
        sweep = float(np.arctan2(_cross(vs, ve), _dot(vs, ve)))
        if not abs(s.sweep_rad - sweep) <= angle_tol:
            out.append(f"arc {i}: sweep_rad {s.sweep_rad!r} but start→end turns {sweep!r}")
        sense = 1.0 if s.direction == "ccw" else -1.0
        if s.direction not in ("ccw", "cw") or s.sweep_rad * sense <= 0:
            out.append(f"arc {i}: direction {s.direction!r} disagrees with sweep {s.sweep_rad!r}")
        if sweep * sense < -angle_tol:
            out.append(
                f"arc {i}: end lies behind start for a {s.direction} arc (the arc "
                f"would turn more than π)"
            )
        expected = r * abs(sweep)
        if not abs(s.length - expected) <= 1e-12 * expected + tol:
            out.append(f"arc {i}: length {s.length!r} but radius·|sweep| = {expected!r}")
    return out


# -- statistics ------------------------------------------------------------------------


def stats_violations(cp: Array, spline: Any, tolerance: float) -> list[str]:
    """The reported statistics against the segments and the oracle's own arc length."""
    out: list[str] = []
    segs = spline.segments
    st = spline.stats

    def close(a: float, b: float, rtol: float = 1e-12, atol: float = 0.0) -> bool:
        return abs(a - b) <= rtol * max(abs(a), abs(b)) + atol

    if len(spline) != len(segs) or len(segs) == 0:
        out.append(f"len(spline) = {len(spline)}, {len(segs)} segments")
    if spline.tolerance != tolerance:
        out.append(f"spline.tolerance {spline.tolerance!r} != requested {tolerance!r}")
    arcs = [s for s in segs if s.type == "arc"]
    if (st.arc_count, st.line_count) != (len(arcs), len(segs) - len(arcs)):
        out.append(
            f"arc_count/line_count {st.arc_count}/{st.line_count} but the segments "
            f"hold {len(arcs)} arcs and {len(segs) - len(arcs)} lines"
        )
    if st.segment_count != len(segs):
        out.append(f"segment_count {st.segment_count} != {len(segs)}")
    us = [s.u_start for s in segs]
    ue = [s.u_end for s in segs]
    if us[:1] != [0.0] or ue[-1:] != [1.0]:
        out.append(f"u ranges start at {us[:1]} and end at {ue[-1:]}, not 0 and 1")
    for i in range(len(segs)):
        if not us[i] < ue[i]:
            out.append(f"segment {i}: u range [{us[i]!r}, {ue[i]!r}] is empty or reversed")
        if i + 1 < len(segs) and ue[i] != us[i + 1]:
            out.append(f"segments {i}/{i + 1}: u ranges do not tile ({ue[i]!r} != {us[i + 1]!r})")
        if not us[i] <= segs[i].u_at_max_deviation <= ue[i]:
            out.append(
                f"segment {i}: u_at_max_deviation {segs[i].u_at_max_deviation!r} outside its range"
            )
    devs = [s.max_deviation for s in segs]
    if not all(math.isfinite(d) and d >= 0 for d in devs):
        out.append("a per-segment max_deviation is negative or not finite")
    else:
        worst = int(np.argmax(devs))
        if st.max_deviation != devs[worst]:
            out.append(
                f"stats.max_deviation {st.max_deviation!r} != largest segment's {devs[worst]!r}"
            )
        elif (
            st.u_at_max_deviation != segs[worst].u_at_max_deviation
            and devs.count(st.max_deviation) == 1
        ):
            out.append(
                f"stats.u_at_max_deviation {st.u_at_max_deviation!r} != segment "
                f"{worst}'s {segs[worst].u_at_max_deviation!r}"
            )
        if not close(st.deviation_ratio, st.max_deviation / tolerance):
            out.append(
                f"deviation_ratio {st.deviation_ratio!r} != max/tolerance "
                f"{st.max_deviation / tolerance!r}"
            )
        if not close(st.mean_segment_deviation, math.fsum(devs) / len(devs), atol=1e-300):
            out.append(
                f"mean_segment_deviation {st.mean_segment_deviation!r} != "
                f"{math.fsum(devs) / len(devs)!r}"
            )
    total = math.fsum(s.length for s in segs)
    if not close(st.spline_length, total, 1e-12):
        out.append(f"spline_length {st.spline_length!r} != sum of lengths {total!r}")
    # The oracle's length is that of the rounded control points: allow their rounding.
    length = arc_length(cp)
    if not close(st.spiral_length, length, 1e-9, rounding_slack(cp)):
        out.append(f"spiral_length {st.spiral_length!r} but the oracle measures {length!r}")
    radii = [s.radius for s in arcs]
    expect = (min(radii), max(radii)) if radii else (None, None)
    if (st.min_radius, st.max_radius) != expect:
        out.append(f"min/max radius {st.min_radius!r}/{st.max_radius!r} != {expect!r}")
    return out


def deviation_violations(cp: Array, spline: Any, tolerance: float, dev: Deviation) -> list[str]:
    """The measured deviation against the tolerance and against what the spline reports.

    The two-sided maximum must be ≤ ``tolerance·(1 + 1e-9) + 64·eps·scale`` (``scale`` the
    spiral's coordinate scale) and agree with ``stats.max_deviation`` to 1e-3 relative; each
    segment's reported maximum must agree with the oracle's, as must the distance at its
    reported ``u``.
    """
    out: list[str] = []
    segs = spline.segments
    slack = rounding_slack(cp)
    bound = tolerance * (1 + 1e-9) + slack
    if not dev.max <= bound:
        out.append(
            f"measured max distance {dev.max!r} exceeds tolerance {tolerance!r} "
            f"(bound with rounding slack {bound!r})"
        )
    # Agreement allows for the rounding of the emitted numbers themselves: an arc given by a
    # centre and radius of size R is only defined to ~eps·R, whatever the core computed.
    seg_slack = [max(slack, ROUNDING_ULPS * EPS * emitted_scale(s)) for s in segs]
    reported = spline.stats.max_deviation
    if not abs(dev.max - reported) <= DEVIATION_RTOL * reported + max(seg_slack):
        out.append(f"measured max distance {dev.max!r} but stats.max_deviation {reported!r}")
    for i, s in enumerate(segs):
        mine = dev.segment_deviation[i]
        agree = DEVIATION_RTOL * s.max_deviation + seg_slack[i]
        if not abs(mine - s.max_deviation) <= agree:
            out.append(
                f"segment {i} (u {s.u_start:.9g}..{s.u_end:.9g}): max deviation "
                f"measured {mine!r} at u={dev.segment_u_at_max[i]!r}, reported "
                f"{s.max_deviation!r} at u={s.u_at_max_deviation!r}"
            )
            continue
        there = deviation_at(cp, s, s.u_at_max_deviation)
        if not abs(there - s.max_deviation) <= agree:
            out.append(
                f"segment {i}: at the reported u={s.u_at_max_deviation!r} the distance "
                f"is {there!r}, not the reported {s.max_deviation!r}"
            )
    return out


# -- everything at once ----------------------------------------------------------------


@dataclass(frozen=True)
class Verdict:
    """Every guarantee checked for one spiral and its arc spline."""

    tolerance: float
    deviation: Deviation
    continuity: Continuity
    violations: list[str] = field(default_factory=list)

    def describe(self) -> str:
        d = self.deviation
        head = (
            f"tolerance {self.tolerance:.6g}: measured two-sided max {d.max:.9g} "
            f"(spiral→spline {d.spiral_to_spline:.9g} at u={d.u_spiral_to_spline:.9g}; "
            f"spline→spiral {d.spline_to_spiral:.9g} on segment {d.segment_spline_to_spiral} "
            f"at {d.point_spline_to_spiral}; global {d.global_spiral_to_spline:.9g} at "
            f"u={d.u_global_spiral_to_spline:.9g})"
        )
        return "\n".join([head, *self.violations])


def check(cp: Array, spline: Any, tolerance: float, samples: int = 30_000) -> Verdict:
    """Check every guarantee of ``spline`` as an approximation of ``Q`` within ``tolerance``.

    * ends and end tangents match the spiral's, consecutive segments are G1;
    * each segment is internally consistent, the statistics match the segments;
    * the measured deviation is within the tolerance and as reported
      (:func:`deviation_violations`).
    """
    segs = spline.segments
    out: list[str] = []
    dev = measure(cp, segs, samples=samples)
    cont = continuity(cp, segs)
    out += cont.violations()
    out += arc_violations(segs)
    out += stats_violations(cp, spline, tolerance)
    out += deviation_violations(cp, spline, tolerance, dev)
    return Verdict(tolerance=tolerance, deviation=dev, continuity=cont, violations=out)
