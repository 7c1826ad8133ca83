"""An independent oracle for arc-spline approximations of whole paths.

It shares no code with ``arcspline``. It reads source segments only through the public field
names of the value types in ``arcspline.geometry.curves.segments`` (``Line``, ``Quadratic``,
``Cubic``, ``CircularArc``, ``EllipticalArc``, ``Subpath``, ``Path``; duck-typed, so importing
this module never imports ``arcspline``), and the approximation only as the service's JSON
output: per subpath a list of dicts (``type``, ``start``, ``end``, for arcs ``center``,
``radius``, ``direction``, ``start_angle_rad``, ``sweep_rad``; all ``source_segment``,
``u_start``, ``u_end``, ``max_deviation``). Everything is measured by its own computation:

* each source segment as a parametric curve ``S(t)``, ``t ∈ [0, 1]``: a Bézier of degree
  ``n`` (a line is degree 1) ``S(t) = Σ C(n,i)·tⁱ·(1−t)ⁿ⁻ⁱ·Pᵢ``; a circular arc
  ``C + r·(cos φ, sin φ)`` and an elliptical arc ``C + R(ρ)·(rx·cos φ, ry·sin φ)`` with
  ``φ = φ₀ + t·Δφ``; with first and second derivatives, in ``np.longdouble``;
* the exact distance from a point to an output arc (``|‖P − C‖ − r|`` when the polar angle of
  ``P`` about ``C`` lies within the arc's sweep, else the distance to the nearer end point; any
  sweep up to 2π) and to an output line segment (clamped projection);
* the distance from a point to a source piece ``S([u0, u1])`` as a true foot point: a global
  coarse search over samples even in arc length plus turning, then safeguarded Newton on
  ``g(t) = (S(t) − P)·S'(t) = 0`` (bisection when a step leaves the bracket);
* two-sided (Hausdorff) distances by dense sampling on both sides, every sampled local maximum
  refined by golden-section search (:func:`measure_piece`, :func:`union_hausdorff`);
* a certified bound with python-flint (:func:`certified_arc_deviation`,
  :func:`certified_line_deviation`): the Bézier's coordinates as exact rationals, the critical
  points as the certified real roots of an exact polynomial, the distance evaluated in ball
  arithmetic;
* the chain's end conditions, continuity, G1 where the source is smooth, the tiling of the
  source parameter ranges and each arc's internal consistency (:func:`check_path`).

Long double is the 64-bit-significand x87 format on x86-64: distances to arcs of huge radius
(``‖P − C‖ − r`` cancels) keep about 11 more bits than float64, far below the rounding slack
of 64 ulps of float64 at the coordinate scale that every check allows.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field, replace
from functools import cached_property
from typing import TYPE_CHECKING, Any

import numpy as np
import numpy.typing as npt
from flint import arb, ctx, fmpq, fmpq_poly

if TYPE_CHECKING:
    from arcspline.geometry.curves.segments import Path, Segment, Subpath

LD = np.longdouble
EPS = float(np.finfo(np.float64).eps)
Array = npt.NDArray[Any]
PI_LD = 4 * np.arctan(LD(1))
TWO_PI_LD = 2 * PI_LD

#: Rounding slack, in units of ``EPS × coordinate scale`` (the spacing of float64 there).
ROUNDING_ULPS = 64.0
#: G1: unit tangents either side of a joint agree to this angle (plus rounding slack); a
#: source joint whose tangents agree to it counts as smooth.
ANGLE_TOL_RAD = 1e-9
#: A reported ``max_deviation`` may exceed the measured one by this fraction (plus slack).
DEVIATION_RTOL = 1e-3
#: Samples on each side of a piece for :func:`measure_piece`.
SAMPLES = 2049
#: Samples of a source piece in the coarse search that starts each foot-point Newton.
FOOT_GRID = 257
#: Sampled local maxima refined by golden section, largest first.
REFINED_PEAKS = 12
#: Golden-section iterations: the bracket (two sample cells) shrinks by 0.618³² ≈ 2e-7.
GOLDEN_ITERATIONS = 32

# -- vectors ---------------------------------------------------------------------------


def _dot(a: Array, b: Array) -> Array:
    return a[..., 0] * b[..., 0] + a[..., 1] * b[..., 1]


def _cross(a: Array, b: Array) -> Array:
    return a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]


def _norm(a: Array) -> Array:
    return np.hypot(a[..., 0], a[..., 1])


def _angle_between(a: Array, b: Array) -> float:
    """Unsigned angle between two vectors, ``atan2(|a×b|, a·b)`` (accurate near 0); NaN when
    either vector is zero or not finite."""
    a, b = np.asarray(a, dtype=LD), np.asarray(b, dtype=LD)
    if not (np.all(np.isfinite(a)) and np.all(np.isfinite(b))):
        return math.nan
    if not (_norm(a) > 0 and _norm(b) > 0):
        return math.nan
    return float(np.arctan2(np.abs(_cross(a, b)), _dot(a, b)))


def _ld(a: Any) -> Array:
    return np.asarray(a, dtype=LD)


def rounding_slack(scale: float) -> float:
    """``64·eps·scale``: what rounding alone can move a point at coordinate scale ``scale``."""
    return ROUNDING_ULPS * EPS * scale


# -- the source segments ---------------------------------------------------------------


def _bernstein(cp: Array, t: Array) -> Array:
    """``Σ C(n,i)·tⁱ·(1−t)ⁿ⁻ⁱ·Pᵢ`` for control points ``cp`` (``(n+1, 2)``); zero if empty."""
    w = t[..., None]
    out = np.zeros((*np.shape(t), 2), dtype=cp.dtype)
    v = 1 - w
    n = len(cp) - 1
    for i, p in enumerate(cp):
        out = out + float(math.comb(n, i)) * w**i * v ** (n - i) * p
    return out


def _segment_kind(segment: Any) -> str:
    """``"bezier"`` (Line, Quadratic, Cubic) or ``"ellipse"`` (CircularArc, EllipticalArc), by
    the value type's field names."""
    fields = getattr(segment, "_fields", ())
    if "rx" in fields or "radius" in fields:
        return "ellipse"
    return "bezier"


@dataclass(frozen=True, eq=False)
class SourceCurve:
    """One source segment as a parametric curve ``S(t)``, ``t ∈ [0, 1]``, in long double
    (:attr:`fast`: the same in float64, for searches whose result is re-evaluated).

    Béziers (a ``Line`` is degree 1): control points ``cp``; ``S' = n·Σ B(n−1)·ΔPᵢ``,
    ``S'' = n(n−1)·Σ B(n−2)·Δ²Pᵢ``. Arcs (a ``CircularArc`` is an ellipse with ``rx = ry =
    r`` and no rotation): ``S(t) = C + R(ρ)·(rx cos φ, ry sin φ)``, ``φ = φ₀ + tΔφ``,
    ``S' = Δφ·R(ρ)·(−rx sin φ, ry cos φ)``, ``S'' = −Δφ²·R(ρ)·(rx cos φ, ry sin φ)``.
    ``start`` and ``end`` are the stored end points; ``scale`` the largest number that
    defines the segment (coordinates, and for arcs ``|C| + max(rx, ry)``).
    """

    kind: str
    cp: Array
    center: Array
    rx: Any
    ry: Any
    rotation: Any
    angle0: Any
    sweep: Any
    start: Array
    end: Array
    scale: float

    @classmethod
    def of(cls, segment: Segment) -> SourceCurve:
        kind = _segment_kind(segment)
        start, end = _ld(segment.start), _ld(segment.end)
        zero = LD(0)
        if kind == "bezier":
            fields = segment._fields
            names = [f for f in ("start", "control", "control1", "control2", "end") if f in fields]
            cp = _ld([getattr(segment, f) for f in names])
            scale = float(np.max(np.abs(cp.astype(np.float64))))
            return cls(kind, cp, _ld([0, 0]), zero, zero, zero, zero, zero, start, end, scale)
        center = _ld(segment.center)
        if "rx" in segment._fields:
            rx, ry, rot = LD(segment.rx), LD(segment.ry), LD(segment.rotation_rad)
        else:
            rx = ry = LD(segment.radius)
            rot = zero
        scale = max(
            float(np.max(np.abs(np.concatenate([start, end]).astype(np.float64)))),
            float(np.max(np.abs(center.astype(np.float64)))) + float(max(abs(rx), abs(ry))),
        )
        return cls(
            kind,
            _ld(np.zeros((0, 2))),
            center,
            rx,
            ry,
            rot,
            LD(segment.start_angle_rad),
            LD(segment.sweep_rad),
            start,
            end,
            scale,
        )

    @cached_property
    def fast(self) -> SourceCurve:
        """The same curve in float64."""
        f64 = np.float64
        return replace(
            self,
            cp=self.cp.astype(f64),
            center=self.center.astype(f64),
            rx=f64(self.rx),
            ry=f64(self.ry),
            rotation=f64(self.rotation),
            angle0=f64(self.angle0),
            sweep=f64(self.sweep),
        )

    def _param(self, t: Any) -> Array:
        return np.asarray(t, dtype=self.center.dtype)

    def _rotate(self, x: Array, y: Array) -> Array:
        c, s = np.cos(self.rotation), np.sin(self.rotation)
        return np.stack([c * x - s * y, s * x + c * y], axis=-1)

    def point(self, t: Any) -> Array:
        """``S(t)``, shape ``(*t.shape, 2)``."""
        t = self._param(t)
        if self.kind == "bezier":
            return _bernstein(self.cp, t)
        phi = self.angle0 + t * self.sweep
        return self.center + self._rotate(self.rx * np.cos(phi), self.ry * np.sin(phi))

    def derivatives(self, t: Any) -> tuple[Array, Array, Array]:
        """``(S(t), S'(t), S''(t))`` at once (one cos/sin for the arcs)."""
        t = self._param(t)
        if self.kind == "bezier":
            return self.point(t), self.deriv(t), self.deriv2(t)
        phi = self.angle0 + t * self.sweep
        x, y = self.rx * np.cos(phi), self.ry * np.sin(phi)
        p = self._rotate(x, y)
        v = self._rotate(-self.rx * np.sin(phi), self.ry * np.cos(phi))
        return self.center + p, self.sweep * v, -(self.sweep**2) * p

    def deriv(self, t: Any) -> Array:
        """``S'(t)``."""
        t = self._param(t)
        if self.kind == "bezier":
            n = len(self.cp) - 1
            return n * _bernstein(np.diff(self.cp, axis=0), t)
        phi = self.angle0 + t * self.sweep
        return self.sweep * self._rotate(-self.rx * np.sin(phi), self.ry * np.cos(phi))

    def deriv2(self, t: Any) -> Array:
        """``S''(t)``."""
        t = self._param(t)
        if self.kind == "bezier":
            n = len(self.cp) - 1
            return n * (n - 1) * _bernstein(np.diff(self.cp, n=2, axis=0), t)
        phi = self.angle0 + t * self.sweep
        return -(self.sweep**2) * self._rotate(self.rx * np.cos(phi), self.ry * np.sin(phi))

    def tangent(self, t: float) -> Array:
        """Direction of travel at ``t`` (not normalised). At a Bézier's ends a zero first leg
        falls back to the next control point that differs (``P_k − P₀`` at 0, ``Pₙ − P_{n−k}``
        at 1), the limit of ``S'(t)/‖S'(t)‖``."""
        if self.kind == "bezier" and t in (0.0, 1.0):
            cp = self.cp
            n = len(cp) - 1
            for k in range(1, n + 1):
                v = cp[k] - cp[0] if t == 0.0 else cp[n] - cp[n - k]
                if _norm(v) > 0:
                    return v
            return _ld([0, 0])
        return self.deriv(_ld(t))

    def smooth_at(self, t: float) -> bool:
        """Whether the curve has a tangent at interior ``t`` (a Bézier cusp, ``S'(t) ≈ 0``
        relative to ``n·`` its largest control leg, has none)."""
        if self.kind != "bezier":
            return True
        legs = np.max(_norm(np.diff(self.cp, axis=0))) if len(self.cp) > 1 else LD(0)
        speed = _norm(self.deriv(_ld(t)))
        return bool(speed > 1e-12 * (len(self.cp) - 1) * legs)

    @cached_property
    def speed_scale(self) -> float:
        """A bound on ``‖S'(t)‖``: ``n·`` the longest control leg of a Bézier, ``|Δφ|·max(rx,
        ry)`` for an arc (the scale of the rounding noise in a computed ``S'``)."""
        if self.kind == "bezier":
            n = len(self.cp) - 1
            legs = np.max(_norm(np.diff(self.cp, axis=0))) if n > 0 else LD(0)
            return float(n * legs)
        return float(abs(self.sweep) * max(abs(self.rx), abs(self.ry)))

    @property
    def degenerate(self) -> bool:
        """A single point (every control point equal, or a zero-sized arc)."""
        if self.kind == "bezier":
            return bool(np.all(self.cp == self.cp[0]))
        return bool(self.sweep == 0 or (self.rx == 0 and self.ry == 0))

    @cached_property
    def bbox(self) -> tuple[Array, Array]:
        """A box holding the whole curve: the control points' (convex hull property), or the
        arc's centre ± max(rx, ry)."""
        if self.kind == "bezier":
            return np.min(self.cp, axis=0), np.max(self.cp, axis=0)
        r = max(abs(self.rx), abs(self.ry))
        return self.center - r, self.center + r

    @cached_property
    def full_samples(self) -> Samples:
        """:func:`coarse_samples` over ``[0, 1]``."""
        return coarse_samples(self, 0.0, 1.0)


def even_grid(src: SourceCurve, u0: float, u1: float, n: int) -> Array:
    """About ``n`` parameters in ``[u0, u1]`` (both ends included) spread evenly in arc length
    plus turning: a fine uniform grid of ``8n`` is mapped through the cumulative measure
    ``s(t)/L + ψ(t)/Ψ`` (length share plus turning share) and sampled evenly in it, so no cell
    holds more than about ``2/n`` of the length or of the turning."""
    if not u1 > u0:
        return np.array([u0], dtype=np.float64)
    fine = np.linspace(u0, u1, 8 * n + 1)
    q, d, _ = src.fast.derivatives(fine)
    length = np.concatenate([[0.0], np.cumsum(_norm(np.diff(q, axis=0)))])
    heading = np.unwrap(np.arctan2(d[:, 1], d[:, 0]))
    turn = np.concatenate([[0.0], np.cumsum(np.abs(np.diff(heading)))])
    share = np.zeros_like(fine)
    for part in (length, turn):
        if part[-1] > 0 and math.isfinite(part[-1]):
            share = share + part / part[-1]
    if not share[-1] > 0:
        return np.linspace(u0, u1, n)
    grid = np.interp(np.linspace(0.0, share[-1], n), share, fine)
    grid[0], grid[-1] = u0, u1
    return np.unique(grid)


@dataclass(frozen=True)
class Samples:
    """Parameters ``t`` of a source piece with ``S(t)`` and ``S'(t)`` in float64 (for the
    coarse search and the brackets of each foot-point Newton) and ``S(t)`` in long double."""

    t: Array
    q: Array
    d1: Array
    t_ld: Array
    q_ld: Array


def coarse_samples(src: SourceCurve, u0: float, u1: float, n: int = FOOT_GRID) -> Samples:
    """:func:`even_grid` of ``n`` over ``[u0, u1]`` and its points."""
    t = even_grid(src, u0, u1, n)
    q, d1, _ = src.fast.derivatives(t)
    t_ld = t.astype(LD)
    return Samples(t, q, d1, t_ld, src.point(t_ld))


def foot_distance(
    src: SourceCurve,
    points: Array,
    u0: float = 0.0,
    u1: float = 1.0,
    samples: Samples | None = None,
    starts: int = 2,
) -> tuple[Array, Array]:
    """Distance from each point to the source piece ``S([u0, u1])`` and its foot parameter.

    A global coarse search over ``samples`` (default :func:`coarse_samples` of the piece)
    picks as starts the ``starts`` nearest *local minima* of the sampled distance along the
    piece (one per branch of the curve that passes near the point), not merely the nearest
    samples: where the grid is dense (it crowds at a turning point or a tight bend, being
    even in turning too) the nearest few samples can all lie on one branch while the true
    foot lies on another one a cell away. Where ``g(t) = (S(t) − P)·S'(t)`` changes sign over
    the two cells beside a start, safeguarded Newton (:func:`_newton_foot`) finds the foot
    there; elsewhere the nearest point of those cells is one of their ends, a sample no nearer
    than the start. The nearest candidate (samples included) wins, its distance evaluated in
    long double. The search runs in float64: at a foot the distance is stationary in ``t``, so
    an error ``δ`` in ``t`` moves it by ``O(δ²)``. Every candidate is a point of the curve, so
    the result is never below the true distance; it is never above the nearest sample's (the
    global minimum is a local one), and exact whenever the nearest foot lies beside a start.
    """
    pts = _ld(points).reshape(-1, 2)
    if samples is None:
        samples = src.full_samples if (u0, u1) == (0.0, 1.0) else coarse_samples(src, u0, u1)
    grid, qg = samples.t, samples.q
    k = len(grid)
    starts = min(starts, k)
    pts64 = pts.astype(np.float64)
    speed_noise = ROUNDING_ULPS * EPS * src.speed_scale
    nearest = np.empty((len(pts), starts), dtype=np.intp)
    chunk = max(1, 500_000 // k)
    for b in range(0, len(pts), chunk):
        px, py = pts64[b : b + chunk, 0, None], pts64[b : b + chunk, 1, None]
        d2 = (px - qg[None, :, 0]) ** 2 + (py - qg[None, :, 1]) ** 2
        if k > 1:  # keep only the local minima along the piece (ends: one neighbour)
            inner = np.ones(d2.shape, dtype=bool)
            inner[:, 1:] &= d2[:, 1:] <= d2[:, :-1]
            inner[:, :-1] &= d2[:, :-1] <= d2[:, 1:]
            d2 = np.where(inner, d2, np.inf)
        rows = np.arange(len(d2))
        for j in range(starts):  # the nearest local minimum, the next nearest, ...
            nearest[b : b + chunk, j] = at = np.argmin(d2, axis=1)
            d2[rows, at] = np.inf
    best_d = np.full(len(pts), np.inf, dtype=LD)
    best_t = np.zeros(len(pts), dtype=np.float64)
    for j in range(starts):
        at = nearest[:, j]
        dist = _norm(samples.q_ld[at] - pts)
        better = dist < best_d
        best_d = np.where(better, dist, best_d)
        best_t = np.where(better, grid[at], best_t)
        i_lo, i_hi = np.maximum(at - 1, 0), np.minimum(at + 1, k - 1)
        r_lo, r_hi = qg[i_lo] - pts64, qg[i_hi] - pts64
        g_lo, g_hi = _dot(r_lo, samples.d1[i_lo]), _dot(r_hi, samples.d1[i_hi])
        # Where S' vanishes (a piece cut at a cusp or a turning point ends there), its
        # computed value is rounding noise and so is the sign of g: a g within that noise
        # brackets too (Newton then only searches a cell that may hold no foot).
        live = np.flatnonzero(
            (g_lo <= _norm(r_lo) * speed_noise) & (g_hi >= -_norm(r_hi) * speed_noise)
        )
        if not len(live):
            continue
        p = pts64[live]
        t = _newton_foot(src.fast, p, grid[i_lo[live]], grid[i_hi[live]], grid[at[live]])
        dist = _norm(src.point(t.astype(LD)) - pts[live])
        better = dist < best_d[live]
        best_d[live] = np.where(better, dist, best_d[live])
        best_t[live] = np.where(better, t, best_t[live])
    shape = np.shape(points)[:-1]
    return best_d.reshape(shape), best_t.reshape(shape)


def _newton_foot(src: SourceCurve, pts: Array, lo: Array, hi: Array, t: Array) -> Array:
    """Safeguarded Newton on ``g(t) = (S(t) − P)·S'(t)`` in ``[lo, hi]`` (``g(lo) ≤ 0 ≤
    g(hi)``): ``t ← t − g/g'`` with ``g' = ‖S'‖² + (S − P)·S''``, bisection when the step
    leaves the bracket or ``g' ≤ 0``; the bracket shrinks on the sign of ``g``. A root with
    ``g' ≤ 0`` (where ``S' = 0``, a local maximum of the distance) is bisected away from, not
    kept. Stops when no step moves more than ``4·eps``."""
    for _ in range(60):
        p, d1, d2 = src.derivatives(t)
        r = p - pts
        g = _dot(r, d1)
        gp = _dot(d1, d1) + _dot(r, d2)
        lo = np.where(g < 0, t, lo)
        hi = np.where(g > 0, t, hi)
        ok = gp > 0
        step = t - g / np.where(ok, gp, 1)
        new = np.where(ok & (step >= lo) & (step <= hi), step, (lo + hi) / 2)
        # Stop on a root only if it is a foot (a minimum of the distance, g' > 0): at a piece
        # cut where S' = 0 exactly, g = 0 too but the distance is largest there.
        new = np.where((g == 0) & ok, t, new)
        moved = float(np.max(np.abs(new - t)))
        t = new
        if moved <= 4 * EPS:
            break
    return t


# -- the output segments ---------------------------------------------------------------


def _wrap(angle: float) -> float:
    """``angle`` reduced to ``[−π, π)``."""
    return (angle + math.pi) % (2 * math.pi) - math.pi


def geometric_sweep(start: Any, end: Any, center: Any, ccw: bool, hint: float) -> Any:
    """The signed angle an arc turns from ``start`` to ``end`` about ``center`` in its sense:
    ``m = σ·((σ(θₑ − θₛ)) mod 2π)``, ``σ = ±1``; of ``m`` and ``m ∓ 2π`` the one nearest
    ``hint`` (the reported sweep), which only settles the 2π ambiguity (a full circle, or an
    end rounded just behind its start)."""
    c = _ld(center)
    vs, ve = _ld(start) - c, _ld(end) - c
    sense = LD(1 if ccw else -1)
    turn = np.arctan2(ve[1], ve[0]) - np.arctan2(vs[1], vs[0])
    m = sense * np.mod(sense * turn, TWO_PI_LD)
    options = [m, m - sense * TWO_PI_LD, m + sense * TWO_PI_LD]
    return min(options, key=lambda s: abs(float(s) - hint))


@dataclass(frozen=True, eq=False)
class Outputs:
    """Output segments as long-double arrays (one entry per segment, any shape).

    An arc is the set of points at radius ``r`` from ``C`` whose polar angle runs from
    ``angle0`` (the polar angle of the emitted start) through ``sweep`` (from
    :func:`geometric_sweep`). A line is ``start + s·(end − start)``; its arc fields are
    harmless stand-ins (``center = start``, ``radius = 1``, ``sense = sweep = 0``).
    """

    is_arc: Array
    start: Array
    end: Array
    center: Array
    radius: Array
    sense: Array
    angle0: Array
    sweep: Array

    @classmethod
    def of(cls, segments: Sequence[Mapping[str, Any]]) -> Outputs:
        is_arc, start, end, center, radius, sense, angle0, sweep = ([] for _ in range(8))
        for s in segments:
            arc = s["type"] == "arc"
            p0, p1 = _ld(s["start"]), _ld(s["end"])
            c = _ld(s["center"]) if arc else p0
            ccw = arc and s["direction"] == "ccw"
            is_arc.append(arc)
            start.append(p0)
            end.append(p1)
            center.append(c)
            radius.append(LD(s["radius"]) if arc else LD(1))
            sense.append(LD(0 if not arc else (1 if ccw else -1)))
            v = p0 - c
            angle0.append(np.arctan2(v[1], v[0]) if arc else LD(0))
            sweep.append(geometric_sweep(p0, p1, c, ccw, float(s["sweep_rad"])) if arc else LD(0))
        return cls(
            np.array(is_arc, dtype=bool),
            _ld(start).reshape(-1, 2),
            _ld(end).reshape(-1, 2),
            _ld(center).reshape(-1, 2),
            _ld(radius),
            _ld(sense),
            _ld(angle0),
            _ld(sweep),
        )

    def __len__(self) -> int:
        return len(self.is_arc)

    def take(self, idx: Any) -> Outputs:
        """The segments at ``idx`` (any shape), for element-wise or broadcast evaluation."""
        return Outputs(**{f: getattr(self, f)[idx] for f in self.__dataclass_fields__})

    def _arc_point(self, angle: Array) -> Array:
        return self.center + self.radius[..., None] * np.stack(
            [np.cos(angle), np.sin(angle)], axis=-1
        )

    def distance(self, points: Array) -> Array:
        """Exact distance from ``points[k]`` to segment ``k`` (shapes broadcast)."""
        return _segment_distance(
            _ld(points),
            self.is_arc,
            self.start,
            self.end,
            self.center,
            self.radius,
            self.sense,
            self.angle0,
            self.sweep,
        )

    def point_at(self, s: Any) -> Array:
        """The point at fraction ``s`` of each segment (arcs by angle, exactly on radius r)."""
        s = _ld(s)
        arc = self._arc_point(self.angle0 + s * self.sweep)
        line = self.start + s[..., None] * (self.end - self.start)
        return np.where(self.is_arc[..., None], arc, line)

    def tangent_at(self, s: float) -> Array:
        """Unit direction of travel at fraction ``s``: an arc's ``σ·(−sin θ, cos θ)``, a
        line's chord (NaN for a zero-length line, which every check then reports)."""
        ang = self.angle0 + LD(s) * self.sweep
        arc = self.sense[..., None] * np.stack([-np.sin(ang), np.cos(ang)], axis=-1)
        chord = self.end - self.start
        length = _norm(chord)
        with np.errstate(divide="ignore", invalid="ignore"):
            line = chord / length[..., None]
        return np.where(self.is_arc[..., None], arc, line)

    def size(self) -> Array:
        """The length over which a direction is rounded: an arc's radius, a line's length."""
        return np.where(self.is_arc, self.radius, _norm(self.end - self.start))


def _segment_distance(
    p: Array,
    is_arc: Array,
    s: Array,
    e: Array,
    c: Array,
    r: Array,
    sense: Array,
    angle0: Array,
    sweep: Array,
) -> Array:
    v = p - c
    polar = np.arctan2(v[..., 1], v[..., 0])
    # Fraction of the turn from the start, in the arc's sense: inside iff within |sweep|.
    phi = np.mod(sense * (polar - angle0), TWO_PI_LD)
    inside = phi <= np.abs(sweep)
    radial = np.abs(_norm(v) - r)
    a1 = angle0 + sweep
    arc_s = c + r[..., None] * np.stack([np.cos(angle0), np.sin(angle0)], axis=-1)
    arc_e = c + r[..., None] * np.stack([np.cos(a1), np.sin(a1)], axis=-1)
    ends = np.minimum(_norm(p - arc_s), _norm(p - arc_e))
    arc = np.where(inside, radial, ends)
    seg = e - s
    len2 = _dot(seg, seg)
    t = np.clip(_dot(p - s, seg) / np.where(len2 > 0, len2, 1), 0, 1)
    line = _norm(p - s - t[..., None] * seg)
    return np.where(is_arc, arc, line)


def point_arc_distance(
    points: Any, center: Any, radius: float, start_angle_rad: float, sweep_rad: float
) -> Array:
    """Exact distance (long double) from points to the arc about ``center`` of ``radius``
    from polar angle ``start_angle_rad`` through ``sweep_rad`` (signed, ``|sweep| ≤ 2π``):
    ``|‖P − C‖ − r|`` when ``σ(θ_P − θ₀) mod 2π ≤ |sweep|`` (``σ`` the sweep's sign), else
    the distance to the nearer end point ``C + r·(cos θ, sin θ)``."""
    pts = _ld(points)
    one = np.ones(pts.shape[:-1], dtype=bool)
    c = _ld(center)
    sense = LD(1 if sweep_rad >= 0 else -1)
    return _segment_distance(
        pts, one, c, c, c, _ld(radius), sense, _ld(start_angle_rad), _ld(sweep_rad)
    )


def point_line_distance(points: Any, start: Any, end: Any) -> Array:
    """Exact distance (long double) from points to the segment ``start``–``end``:
    ``‖P − A − τ(B − A)‖`` with ``τ = clip((P − A)·(B − A)/‖B − A‖², 0, 1)``."""
    pts = _ld(points)
    zero = np.zeros(pts.shape[:-1], dtype=bool)
    a = _ld(start)
    return _segment_distance(pts, zero, a, _ld(end), a, LD(1), LD(0), LD(0), LD(0))


# -- maxima ----------------------------------------------------------------------------


def _golden_max(
    f: Callable[[Array], Array], lo: Array, hi: Array, iterations: int
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


def _refined_rows(
    f: Callable[[Array, Array], Array],
    x: Array,
    values: Array,
    keep: int = REFINED_PEAKS,
    iterations: int = GOLDEN_ITERATIONS,
) -> tuple[Array, Array]:
    """Per row ``i`` of ``values = f(i, x)`` (``x`` ascending along each row): ``(x*, f*)``,
    the largest sample or, if larger, the largest of its ``keep`` largest local maxima each
    refined by golden section on the two cells around it. All rows' refinements run as one
    vectorised search (``f`` takes arrays of row indices and abscissae)."""
    x = np.asarray(x, dtype=np.float64)
    v = np.asarray(values, dtype=LD)
    n, m = v.shape
    at = np.argmax(v, axis=1)
    best_x = x[np.arange(n), at].copy()
    best_f = v[np.arange(n), at].copy()
    if m == 1:
        return best_x, best_f
    neg = np.full((n, 1), -np.inf, dtype=LD)
    left = np.concatenate([neg, v[:, :-1]], axis=1)
    right = np.concatenate([v[:, 1:], neg], axis=1)
    score = np.where((v >= left) & (v >= right), v, -np.inf)
    order = np.argsort(-score, axis=1, kind="stable")[:, :keep]
    valid = np.isfinite(np.take_along_axis(score, order, axis=1))
    rows = np.repeat(np.arange(n), order.shape[1])[valid.ravel()]
    cols = order.ravel()[valid.ravel()]
    a = x[rows, np.maximum(cols - 1, 0)]
    b = x[rows, np.minimum(cols + 1, m - 1)]
    xr, fr = _golden_max(lambda xx: f(rows, xx), a, b, iterations)
    for row, xi, fi in zip(rows, xr, _ld(fr), strict=True):
        if fi > best_f[row]:
            best_x[row], best_f[row] = xi, fi
    return best_x, best_f


def _refined_max(
    f: Callable[[Array], Array],
    x: Array,
    values: Array,
    keep: int = REFINED_PEAKS,
    iterations: int = GOLDEN_ITERATIONS,
) -> tuple[float, float]:
    """:func:`_refined_rows` for a single row: ``(x*, f(x*))`` as floats."""
    xs, fs = _refined_rows(
        lambda _rows, xx: f(xx),
        np.asarray(x)[None, :],
        np.asarray(values)[None, :],
        keep,
        iterations,
    )
    return float(xs[0]), float(fs[0])


# -- one piece -------------------------------------------------------------------------


@dataclass(frozen=True)
class PieceDistance:
    """Both one-sided distances between a source piece and an output segment.

    ``source_to_output``: ``max_{t∈[u0,u1]} dist(S(t), segment)``, reached at ``t``;
    ``output_to_source``: ``max_s dist(segment(s), S([u0,u1]))``, reached at fraction ``s``.
    """

    source_to_output: float
    t: float
    output_to_source: float
    s: float

    @property
    def hausdorff(self) -> float:
        return max(self.source_to_output, self.output_to_source)


def source_to_output(
    src: SourceCurve, u0: float, u1: float, out: Outputs, samples: int = SAMPLES
) -> tuple[float, float]:
    """``(max_t dist(S(t), out), t)`` over ``t ∈ [u0, u1]`` for one output segment ``out``:
    ``samples`` parameters even in length plus turning, maxima refined by golden section."""
    grid = even_grid(src, u0, u1, samples)

    def f(t: Array) -> Array:
        return out.distance(src.point(t))

    t, d = _refined_max(f, grid, f(grid))
    return d, t


def output_to_source(
    src: SourceCurve, u0: float, u1: float, out: Outputs, samples: int = SAMPLES
) -> tuple[float, float]:
    """``(max_s dist(out(s), S([u0, u1])), s)`` for one output segment: ``samples`` even
    fractions of the segment, foot-point distances (:func:`foot_distance`), maxima refined by
    golden section."""
    coarse = coarse_samples(src, u0, u1)

    def f(s: Array) -> Array:
        return foot_distance(src, out.point_at(s), u0, u1, coarse)[0]

    grid = np.linspace(0.0, 1.0, samples)
    s, d = _refined_max(f, grid, f(grid))
    return d, s


def measure_piece_sides(
    source_segment: Segment,
    u0: float,
    u1: float,
    out_segment: Mapping[str, Any],
    samples: int = SAMPLES,
) -> PieceDistance:
    """Both one-sided distances between the source piece ``t ∈ [u0, u1]`` and one output
    segment (a dict of the service's JSON), by :func:`source_to_output` and
    :func:`output_to_source`."""
    src = SourceCurve.of(source_segment)
    out = Outputs.of([out_segment]).take(0)
    d1, t = source_to_output(src, u0, u1, out, samples)
    d2, s = output_to_source(src, u0, u1, out, samples)
    return PieceDistance(source_to_output=d1, t=t, output_to_source=d2, s=s)


def measure_piece(
    source_segment: Segment,
    u0: float,
    u1: float,
    out_segment: Mapping[str, Any],
    samples: int = SAMPLES,
) -> float:
    """Two-sided Hausdorff distance between the source piece ``t ∈ [u0, u1]`` and one output
    segment: ``max(sup_t dist(S(t), seg), sup_{P∈seg} dist(P, S([u0, u1])))``, each side by
    ``samples`` samples with every sampled maximum refined (:func:`measure_piece_sides`)."""
    return measure_piece_sides(source_segment, u0, u1, out_segment, samples).hausdorff


# -- a whole subpath -------------------------------------------------------------------


def _bbox_distance(points: Array, lo: Array, hi: Array) -> Array:
    """Distance from points to an axis-aligned box (a lower bound for anything inside)."""
    gap = np.maximum(np.maximum(lo - points, points - hi), 0)
    return _norm(gap)


def _distance_to_sources(
    sources: Sequence[SourceCurve], points: Array, own: Array | None = None
) -> Array:
    """Distance from each point to the union of whole source curves: first to its ``own``
    source (an index per point, if given), then to every other one whose bounding box lies
    nearer than the best distance so far (the box distance is a lower bound)."""
    pts = _ld(points).reshape(-1, 2)
    shape = np.shape(points)[:-1]
    best = np.full(len(pts), np.inf, dtype=LD)
    mine = np.full(len(pts), -1) if own is None else np.broadcast_to(own, shape).reshape(-1)
    for j, src in enumerate(sources):
        mask = mine == j
        if np.any(mask):
            best[mask] = foot_distance(src, pts[mask])[0]
    for j, src in enumerate(sources):
        mask = (mine != j) & (_bbox_distance(pts, *src.bbox) < best)
        if np.any(mask):
            best[mask] = np.minimum(best[mask], foot_distance(src, pts[mask])[0])
    return best.reshape(shape)


@dataclass(frozen=True)
class UnionDistance:
    """Both one-sided distances between a source subpath and its output chain as sets."""

    source_to_output: float
    output_to_source: float

    @property
    def hausdorff(self) -> float:
        return max(self.source_to_output, self.output_to_source)


def union_hausdorff(
    subpath: Subpath,
    outputs: Sequence[Mapping[str, Any]],
    samples: int = 257,
    iterations: int = 24,
) -> UnionDistance:
    """Hausdorff distance between the union of a subpath's source segments and the union of
    its output segments, using no reported ``source_segment`` or ``u`` range for the result.

    Source side: ``samples`` parameters per source segment (even in length plus turning),
    each point's distance the minimum over all output segments. Output side: ``samples``
    fractions per output segment, each point's foot-point distance to every source curve
    (pruned by bounding boxes). The sampled maxima are refined by ``iterations`` steps of
    golden section (the union is a cross-check of the per-piece measurement, which bounds it
    whenever the ``u`` ranges tile the source, so it gets a coarser default).
    """
    sources = [SourceCurve.of(s) for s in subpath.segments]
    outs = Outputs.of(outputs)
    every = outs.take(np.arange(len(outs))[None, :])
    worst_src = 0.0
    for src in sources:
        grid = even_grid(src, 0.0, 1.0, samples)

        def f(t: Array, src: SourceCurve = src) -> Array:
            q = src.point(t)[..., None, :]
            return np.min(every.distance(q), axis=-1)

        worst_src = max(worst_src, _refined_max(f, grid, f(grid), 4, iterations)[1])
    own = np.array(
        [o["source_segment"] if isinstance(o.get("source_segment"), int) else -1 for o in outputs]
    )
    frac = np.broadcast_to(np.linspace(0.0, 1.0, samples), (len(outs), samples))
    rows = np.broadcast_to(np.arange(len(outs))[:, None], frac.shape)

    def g(r: Array, s: Array) -> Array:
        return _distance_to_sources(sources, outs.take(r).point_at(s), own[r])

    worst_out = float(np.max(_refined_rows(g, frac, g(rows, frac), 4, iterations)[1]))
    return UnionDistance(source_to_output=worst_src, output_to_source=worst_out)


# -- the checks ------------------------------------------------------------------------


@dataclass
class Verdict:
    """Everything :func:`check_path` found.

    ``violations``: one line per broken guarantee (empty when all hold). Per subpath:
    ``subpath_max`` the largest measured per-piece deviation (:func:`measure_piece` of each
    output segment against its own source piece), ``subpath_union`` the union Hausdorff
    distance (:func:`union_hausdorff`), ``segment_deviation`` each output segment's measured
    deviation (NaN where it could not be measured).
    """

    tolerance: float
    violations: list[str] = field(default_factory=list)
    subpath_max: list[float] = field(default_factory=list)
    subpath_union: list[float] = field(default_factory=list)
    segment_deviation: list[list[float]] = field(default_factory=list)

    @property
    def ok(self) -> bool:
        return not self.violations

    def describe(self) -> str:
        head = f"tolerance {self.tolerance:.6g}: " + ", ".join(
            f"subpath {i}: max {m:.9g}, union {u:.9g}"
            for i, (m, u) in enumerate(zip(self.subpath_max, self.subpath_union, strict=False))
        )
        return "\n".join([head, *self.violations])


_ARC_KEYS = ("center", "radius", "direction", "start_angle_rad", "sweep_rad")
_COMMON_KEYS = ("type", "start", "end", "source_segment", "u_start", "u_end", "max_deviation")


def _pair(v: Any) -> bool:
    """Two finite numbers."""
    try:
        return len(v) == 2 and all(math.isfinite(float(x)) for x in v)
    except (TypeError, ValueError):
        return False


def _finite(v: Any) -> bool:
    """A finite int or float (not a bool)."""
    return isinstance(v, int | float) and not isinstance(v, bool) and math.isfinite(v)


def _shape_violations(seg: Mapping[str, Any], where: str, n_sources: int) -> list[str]:
    """Missing keys, unknown types, non-finite numbers, a bad source index or ``u`` range."""
    out: list[str] = []
    missing = [k for k in _COMMON_KEYS if k not in seg]
    if seg.get("type") == "arc":
        missing += [k for k in _ARC_KEYS if k not in seg]
    elif seg.get("type") != "line":
        out.append(f"{where}: type {seg.get('type')!r} is neither 'arc' nor 'line'")
    if missing:
        out.append(f"{where}: missing {', '.join(missing)}")
        return out
    pairs = ["start", "end"] + (["center"] if seg["type"] == "arc" else [])
    numbers = ["u_start", "u_end", "max_deviation"]
    numbers += ["radius", "start_angle_rad", "sweep_rad"] if seg["type"] == "arc" else []
    out += [
        f"{where}: {k} {seg[k]!r} is not two finite numbers" for k in pairs if not _pair(seg[k])
    ]
    out += [
        f"{where}: {k} {seg[k]!r} is not a finite number" for k in numbers if not _finite(seg[k])
    ]
    j = seg["source_segment"]
    if not (isinstance(j, int) and not isinstance(j, bool) and 0 <= j < n_sources):
        out.append(f"{where}: source_segment {j!r} is not an index below {n_sources}")
    if seg["type"] == "arc" and seg["direction"] not in ("ccw", "cw"):
        out.append(f"{where}: direction {seg['direction']!r} is neither 'ccw' nor 'cw'")
    return out


def _emitted_scale(seg: Mapping[str, Any]) -> float:
    """Largest number that defines an output segment: coordinates and, for an arc, radius."""
    values = [*seg["start"], *seg["end"]]
    if seg["type"] == "arc":
        values += [*seg["center"], seg["radius"]]
    return float(np.max(np.abs(np.asarray(values, dtype=np.float64))))


def _arc_violations(seg: Mapping[str, Any], where: str, rounding: float) -> list[str]:
    """An arc's internal consistency: ``radius > 0``; ``‖start − C‖ = ‖end − C‖ = r``;
    ``start_angle_rad`` the polar angle of start; ``sweep_rad`` the turn from start to end in
    ``direction`` (sign agreeing, ``0 < |sweep| ≤ 2π``); a line has positive length. Slack:
    ``rounding`` in length, ``1e-12 + rounding/r`` in angle."""
    out: list[str] = []
    start, end = _ld(seg["start"]), _ld(seg["end"])
    if seg["type"] == "line":
        if not _norm(end - start) > 0:
            out.append(f"{where}: zero-length line (no direction)")
        return out
    r = float(seg["radius"])
    if not r > 0:
        return [f"{where}: radius {r!r} is not positive"]
    c = _ld(seg["center"])
    for name, p in (("start", start), ("end", end)):
        gap = float(_norm(p - c) - LD(r))
        if not abs(gap) <= rounding:
            out.append(f"{where}: ‖{name} − center‖ − radius = {gap:.3g} (allowed {rounding:.3g})")
    angle_tol = 1e-12 + rounding / r
    v = start - c
    polar = float(np.arctan2(v[1], v[0]))
    if not abs(_wrap(float(seg["start_angle_rad"]) - polar)) <= angle_tol:
        out.append(
            f"{where}: start_angle_rad {seg['start_angle_rad']!r} but start's polar angle "
            f"is {polar!r}"
        )
    sweep = float(seg["sweep_rad"])
    ccw = seg["direction"] == "ccw"
    if not (0 < abs(sweep) <= 2 * math.pi + angle_tol) or (sweep > 0) != ccw:
        out.append(f"{where}: sweep_rad {sweep!r} does not fit direction {seg['direction']!r}")
    geo = float(geometric_sweep(start, end, c, ccw, sweep))
    if not abs(geo - sweep) <= angle_tol:
        out.append(f"{where}: sweep_rad {sweep!r} but start→end turns {geo!r} ({seg['direction']})")
    return out


def _tiling_violations(
    outs: Sequence[Mapping[str, Any]], sources: Sequence[SourceCurve], head: str
) -> list[str]:
    """Each source segment's output segments are consecutive, in order, and tile its
    ``[0, 1]`` exactly (``u_start`` 0.0, each ``u_end`` the next ``u_start``, last ``u_end``
    1.0, every range non-empty); a source segment without output must be a single point."""
    out: list[str] = []
    idx = [o["source_segment"] for o in outs]
    for i in range(len(idx) - 1):
        if idx[i + 1] < idx[i]:
            out.append(
                f"{head}: output {i + 1} answers for source segment {idx[i + 1]} after "
                f"output {i} answered for {idx[i]} (out of order)"
            )
    runs: dict[int, list[int]] = {}
    for i, j in enumerate(idx):
        runs.setdefault(j, []).append(i)
    for j, src in enumerate(sources):
        mine = runs.get(j, [])
        if not mine:
            if not src.degenerate:
                out.append(f"{head}: source segment {j} has no output segments")
            continue
        if mine != list(range(mine[0], mine[0] + len(mine))):
            out.append(f"{head}: source segment {j}'s outputs {mine} are not consecutive")
            continue
        us = [float(outs[i]["u_start"]) for i in mine]
        ue = [float(outs[i]["u_end"]) for i in mine]
        if us[0] != 0.0 or ue[-1] != 1.0:
            out.append(f"{head}: source segment {j}'s u ranges run {us[0]!r}..{ue[-1]!r}, not 0..1")
        for a, (lo, hi) in enumerate(zip(us, ue, strict=True)):
            if not lo < hi:
                out.append(f"{head}: output {mine[a]}: u range [{lo!r}, {hi!r}] is empty")
            if a + 1 < len(us) and hi != us[a + 1]:
                out.append(
                    f"{head}: outputs {mine[a]}/{mine[a + 1]}: u ranges do not tile "
                    f"({hi!r} != {us[a + 1]!r})"
                )
    return out


def _joint_smooth(
    sources: Sequence[SourceCurve],
    a: Mapping[str, Any],
    b: Mapping[str, Any],
    *,
    seam: bool = False,
) -> tuple[bool, str]:
    """Whether the source is smooth where output ``a`` ends and ``b`` starts: inside one
    source segment (unless at a cusp), or between two whose tangents agree to 1e-9 rad.

    At the ``seam`` of a closed subpath (``a`` the last output, ``b`` the first) the source
    passes from the end of ``a``'s source segment to the start of ``b``'s, even when both are
    the same segment (a subpath of one segment): its end tangent against its start tangent."""
    ja, jb = a["source_segment"], b["source_segment"]
    if ja == jb and not seam:
        u = float(a["u_end"])
        return sources[ja].smooth_at(u), f"inside source segment {ja} at u={u!r}"
    angle = _angle_between(sources[ja].tangent(1.0), sources[jb].tangent(0.0))
    where = "at the seam, " if seam else ""
    return bool(angle <= ANGLE_TOL_RAD), f"{where}between source segments {ja} and {jb}"


def _subpath_violations(
    k: int,
    subpath: Subpath,
    outs: Sequence[Mapping[str, Any]],
    tolerance: float,
    samples: int,
) -> tuple[list[str], list[float], float]:
    head = f"subpath {k}"
    sources = [SourceCurve.of(s) for s in subpath.segments]
    if not outs:
        return [f"{head}: no output segments"], [], math.nan
    shape: list[str] = []
    for i, seg in enumerate(outs):
        shape += _shape_violations(seg, f"{head} output {i}", len(sources))
    if shape:
        return shape, [math.nan] * len(outs), math.nan
    violations: list[str] = []
    src_scale = max(s.scale for s in sources)
    scale = max(src_scale, *(_emitted_scale(o) for o in outs))
    rounding = rounding_slack(scale)

    # Each output segment on its own, and against its own source piece.
    deviations: list[float] = []
    for i, seg in enumerate(outs):
        j = seg["source_segment"]
        u0, u1 = float(seg["u_start"]), float(seg["u_end"])
        where = f"{head} output {i} (source {j}, u {u0:.9g}..{u1:.9g})"
        seg_slack = rounding_slack(max(sources[j].scale, _emitted_scale(seg)))
        violations += _arc_violations(seg, where, seg_slack)
        if not 0.0 <= u0 <= u1 <= 1.0:
            deviations.append(math.nan)
            violations.append(f"{where}: u range outside [0, 1] or reversed")
            continue
        d = measure_piece(subpath.segments[j], u0, u1, seg, samples)
        deviations.append(d)
        if not d <= tolerance + seg_slack:
            violations.append(
                f"{where}: measured deviation {d!r} exceeds tolerance {tolerance!r} "
                f"(bound with rounding slack {tolerance + seg_slack!r})"
            )
        rep = seg["max_deviation"]
        if not rep >= 0:
            violations.append(f"{where}: reported max_deviation {rep!r} is negative")
        if not d <= rep + seg_slack:
            violations.append(
                f"{where}: measured deviation {d!r} above the reported max_deviation {rep!r}"
            )
        if not rep <= d * (1 + DEVIATION_RTOL) + seg_slack:
            violations.append(
                f"{where}: reported max_deviation {rep!r} above the measured deviation {d!r}"
            )
    violations += _tiling_violations(outs, sources, head)

    # The chain: its ends, its joints, G1 where the source is smooth.
    chain = Outputs.of(outs)
    first = subpath.segments[0].start
    if tuple(float(x) for x in outs[0]["start"]) != (float(first[0]), float(first[1])):
        gap = float(_norm(chain.start[0] - _ld(first)))
        violations.append(
            f"{head}: chain start gap {gap!r}: output 0 starts at {outs[0]['start']!r}, the "
            f"subpath at {tuple(first)!r} (must be exact)"
        )
    gap = float(_norm(chain.end[-1] - _ld(subpath.segments[-1].end)))
    if not gap <= rounding:
        violations.append(
            f"{head}: chain end gap {gap:.3g}: the last output ends away from the subpath's "
            f"end (allowed {rounding:.3g})"
        )
    size = chain.size().astype(np.float64)
    with np.errstate(divide="ignore"):
        angle_slack = np.where(size > 0, rounding / size, np.inf)
    t_start = chain.tangent_at(0.0)
    t_end = chain.tangent_at(1.0)
    joints = [(i, i + 1) for i in range(len(outs) - 1)]
    if subpath.closed:
        joints.append((len(outs) - 1, 0))
    for a, b in joints:
        name = "seam" if b == 0 else "joint"
        if b != 0:
            gap = float(_norm(chain.end[a] - chain.start[b]))
            if not gap <= rounding:
                violations.append(
                    f"{head}: {name} {a}/{b}: gap {gap:.3g} between output {a}'s end and "
                    f"output {b}'s start (allowed {rounding:.3g})"
                )
        smooth, what = _joint_smooth(sources, outs[a], outs[b], seam=b == 0)
        if not smooth:
            continue
        angle = _angle_between(t_end[a], t_start[b])
        bound = ANGLE_TOL_RAD + float(angle_slack[a]) + float(angle_slack[b])
        if not angle <= bound:
            violations.append(
                f"{head}: {name} {a}/{b}: output tangents differ by {angle:.3g} rad where the "
                f"source is smooth ({what}; allowed {bound:.3g})"
            )

    # The chain as a set against the source as a set.
    union = union_hausdorff(subpath, outs, samples=max(17, samples // 8)).hausdorff
    if not union <= tolerance + rounding:
        violations.append(
            f"{head}: union Hausdorff distance {union!r} exceeds tolerance {tolerance!r} "
            f"(bound with rounding slack {tolerance + rounding!r})"
        )
    return violations, deviations, union


def check_path(
    path: Path,
    subpaths_out: Sequence[Sequence[Mapping[str, Any]]],
    tolerance: float,
    samples: int = SAMPLES,
) -> Verdict:
    """Check an approximation (the service's per-subpath output dicts) of ``path``.

    Per output segment: the fields are well formed; an arc is internally consistent; its
    measured two-sided deviation from its own source piece (:func:`measure_piece`) is at most
    ``tolerance + 64·eps·scale`` and agrees with the reported ``max_deviation`` (measured ≤
    reported + slack, reported ≤ measured·(1 + 1e-3) + slack). Per subpath: the ``u`` ranges
    tile each source segment's ``[0, 1]``; the chain starts exactly at the subpath's start,
    ends within slack of its end, and each segment starts within slack of where the previous
    ended; where the source is smooth (inside a source segment, or across a joint whose
    tangents agree to 1e-9 rad; also the seam of a closed subpath) the output tangents agree
    to 1e-9 rad plus ``slack/ρ`` each side (``ρ`` an arc's radius or a line's length); and the
    union Hausdorff distance (:func:`union_hausdorff`) is within tolerance plus slack.
    ``scale`` is the largest coordinate (or radius) of the source segment and output segment
    concerned, or of the whole subpath for the chain.
    """
    verdict = Verdict(tolerance=tolerance)
    if len(subpaths_out) != len(path.subpaths):
        verdict.violations.append(
            f"{len(subpaths_out)} output subpaths for {len(path.subpaths)} source subpaths"
        )
    for k, (subpath, outs) in enumerate(zip(path.subpaths, subpaths_out, strict=False)):
        found, deviations, union = _subpath_violations(k, subpath, outs, tolerance, samples)
        verdict.violations += found
        verdict.segment_deviation.append(deviations)
        measured = [d for d in deviations if not math.isnan(d)]
        verdict.subpath_max.append(max(measured, default=math.nan))
        verdict.subpath_union.append(union)
    return verdict


# -- certified bounds (python-flint) ---------------------------------------------------


def _q(x: float) -> fmpq:
    """A float as the exact rational it stands for."""
    x = float(x)
    if not math.isfinite(x):
        raise ValueError(f"{x!r} is not finite")
    num, den = x.as_integer_ratio()
    return fmpq(num, den)


def _bezier_polys(control_points: Any) -> tuple[fmpq_poly, fmpq_poly]:
    """The Bézier's coordinates in the power basis, exactly:
    ``B(t) = Σ C(n,i)·tⁱ·(1−t)ⁿ⁻ⁱ·Pᵢ`` over the rationals."""
    pts = [(_q(p[0]), _q(p[1])) for p in control_points]
    if len(pts) < 2:
        raise ValueError("a Bézier needs at least two control points")
    n = len(pts) - 1
    t, s = fmpq_poly([0, 1]), fmpq_poly([1, -1])
    bx, by = fmpq_poly([]), fmpq_poly([])
    for i, (x, y) in enumerate(pts):
        basis = math.comb(n, i) * t**i * s ** (n - i)
        bx += basis * x
        by += basis * y
    return bx, by


def _eval(p: fmpq_poly, t: arb) -> arb:
    """``p(t)`` by Horner's rule in ball arithmetic (an enclosure of ``p`` over ``t``)."""
    acc = arb(0)
    for c in reversed(p.coeffs()):
        acc = acc * t + arb(c)
    return acc


def _candidates(g: fmpq_poly, u0: fmpq, u1: fmpq) -> list[arb]:
    """``u0``, ``u1`` (exact) and an isolating ball of every real root of ``g`` that may lie
    in ``[u0, u1]``. The roots come from ``complex_roots`` of ``g`` (FLINT's certified
    isolation on its squarefree factors: real roots as balls with imaginary part exactly zero,
    never overlapping another root); a ball that overlaps ``[u0, u1]`` only partly is kept
    whole, which only widens the enclosure by its radius (~2⁻ᵖʳᵉᶜ)."""
    lo, hi = arb(u0), arb(u1)
    out = [lo, hi]
    if g.is_zero() or g.degree() < 1:
        return out
    for root, _mult in g.complex_roots():
        if not root.imag.is_zero():
            continue
        x = root.real
        if x.upper() >= lo and x.lower() <= hi:
            out.append(x)
    return out


def _float_up(x: arb) -> float:
    """The upper end of a ball as a float rounded upwards (an upper bound)."""
    up = x.upper()
    f = float(up)
    if arb(f) < up:
        f = math.nextafter(f, math.inf)
    return f


def _check_range(u0: float, u1: float) -> tuple[fmpq, fmpq]:
    if not 0.0 <= u0 <= u1 <= 1.0:
        raise ValueError(f"need 0 ≤ u0 ≤ u1 ≤ 1, got {u0!r}, {u1!r}")
    return _q(u0), _q(u1)


def certified_arc_deviation(
    control_points: Any,
    u0: float,
    u1: float,
    center: Any,
    radius: float,
    prec: int = 128,
) -> float:
    """Certified ``max_{t∈[u0,u1]} |‖B(t) − C‖ − r|`` for a Bézier (3 points: quadratic,
    4: cubic) against the full circle about ``center`` of ``radius``, as a float that is an
    upper bound (the ball's upper end rounded up).

    Every float is taken exactly as a rational; ``X = Bx − cx``, ``Y = By − cy`` and
    ``g = X·X' + Y·Y'`` (half the derivative of ``‖B − C‖²``) are exact ``fmpq_poly``. The
    distance is smooth where ``B ≠ C`` and its critical points there are roots of ``g``
    (``B = C`` is one too), so the maximum lies at ``u0``, ``u1`` or a real root of ``g``
    (:func:`_candidates`). There ``|√(X² + Y²) − r|`` is enclosed in ``prec``-bit ball
    arithmetic and the largest upper end returned (``g ≡ 0``, a single point, leaves the ends).
    """
    q0, q1 = _check_range(u0, u1)
    cx, cy = _q(center[0]), _q(center[1])
    r = _q(radius)
    with ctx.workprec(prec):
        bx, by = _bezier_polys(control_points)
        x, y = bx - cx, by - cy
        g = x * x.derivative() + y * y.derivative()
        best = 0.0
        for t in _candidates(g, q0, q1):
            xt, yt = _eval(x, t), _eval(y, t)
            dist = (xt * xt + yt * yt).nonnegative_part().sqrt()
            best = max(best, _float_up((dist - arb(r)).abs_upper()))
        return best


def certified_line_deviation(
    control_points: Any,
    u0: float,
    u1: float,
    line_start: Any,
    line_end: Any,
    prec: int = 128,
) -> float:
    """Certified ``max_{t∈[u0,u1]}`` distance from a Bézier (3 or 4 control points) to the
    infinite line through ``A = line_start`` and ``B = line_end``, as an upper-bound float.

    With ``n = (−(B−A)ᵧ, (B−A)ₓ)`` exactly rational, ``h(t) = n·(B(t) − A)`` is an exact
    polynomial and the distance is ``|h(t)|/‖n‖``; its maximum on ``[u0, u1]`` lies at an
    end or at a real root of ``h' = n·B'(t)`` (:func:`_candidates`), where it is enclosed in
    ``prec``-bit ball arithmetic.
    """
    q0, q1 = _check_range(u0, u1)
    ax, ay = _q(line_start[0]), _q(line_start[1])
    dx, dy = _q(line_end[0]) - ax, _q(line_end[1]) - ay
    if dx == 0 and dy == 0:
        raise ValueError("the line's two points coincide")
    nx, ny = -dy, dx
    with ctx.workprec(prec):
        bx, by = _bezier_polys(control_points)
        h = (bx - ax) * nx + (by - ay) * ny
        norm = arb(nx * nx + ny * ny).sqrt()
        best = 0.0
        for t in _candidates(h.derivative(), q0, q1):
            best = max(best, _float_up((_eval(h, t) / norm).abs_upper()))
        return best
