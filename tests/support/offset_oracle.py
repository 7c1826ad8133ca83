"""An independent oracle for tool-radius offsets: is a tool-centre path at the tool radius
``d`` from the part's contours, and does it reach every point of them that a tool can reach?

It shares no code with ``arcspline.geometry.offset`` or ``arcspline.machining``: it reads the
service's JSON segments (:func:`from_json`) or the core's plain ``Line``/``CircularArc``
values (:func:`from_core`, by field names) into its own :class:`OSeg`, and measures
everything with its own computation. Points are ``(N, 2) float64`` arrays; angles anticlockwise
positive; an arc is ``centre + radius·(cos θ, sin θ)``, ``θ = θ₀ + t·sweep``, ``t ∈ [0, 1]``.

* Exact distance from points to a line segment (clamped projection,
  ``‖P − A − τ(B − A)‖``, ``τ = clip((P − A)·(B − A)/‖B − A‖², 0, 1)``) and to an arc
  (``|‖P − C‖ − r|`` when the polar angle of ``P`` about ``C`` lies within the sweep, else
  the distance to the nearer end), vectorised (:func:`distance_to`).
* A broad phase that keeps this fast and its memory bounded: every segment cut into pieces
  no longer than a grid cell (an arc's pieces sweep at most π/4), each piece registered in the
  cells its box (chord box grown by the sagitta) meets; a point looks at the block of
  ``(2k + 1)²`` cells around its own for ``k`` in :data:`RINGS` (each time only the new ring)
  until the nearest piece found is nearer than anything outside the block can be (the
  distance to the block's nearest side that is not the grid's edge); points still open after
  the widest block go to a coarser grid. Memory stays ``O(PAIR_BUDGET)`` per query.
* Two-way sampling (:func:`check_offset`): every segment sampled at least
  :data:`MIN_SAMPLES` times, ends included, more for long ones; the worst samples refined by
  golden-section search along the segment's parameter, so an extreme is accurate to ~1e-9
  relative. :func:`check_each` does the same for every contour against only its own paths,
  in one pass (per-contour offsets may come within the radius of a neighbour).

"Reachable" (the brief of issue 20): a contour point ``p`` is reachable from the cut side
when the disc of radius ``d`` tangent to the contour at ``p`` on that side does not cut into
any contour: its centre ``p + d·n`` (``n`` the unit normal on the cut side) is at least
``d − reach_tolerance`` from every contour. A slot narrower than ``2d`` is not reachable.
Every reachable point must be within ``d`` of the path (``farthest_mm``) and, so that the cut
side is right too, the centre ``p + d·n`` must lie on the path (``centre_gap_mm``).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterator, Mapping, Sequence
from typing import Any, Literal, NamedTuple

import numpy as np
import numpy.typing as npt

Array = npt.NDArray[np.float64]
Side = Literal["outside", "inside", "left", "right"]
#: How :func:`check_offset` is told the cut side of each contour: one side for all, one per
#: contour (``None``: the contour only constrains, none of its points must be reached), or a
#: function of the contour's index giving the same.
SideSpec = Side | None | Sequence[Side | None] | Callable[[int], Side | None]

#: Fewest samples on one segment (ends included): enough to see a local extreme inside it.
MIN_SAMPLES = 9
#: Most samples on one segment.
MAX_SAMPLES = 4097
#: The global sample spacing is the contours' (or paths') box diagonal over this.
SPACING_DIVISOR = 4096.0
#: Segments whose worst sample is refined by golden section, worst first.
REFINED = 64
#: Golden-section steps: the bracket (two sample spacings) shrinks by 0.618⁶⁰ ≈ 3e-13.
GOLDEN_STEPS = 60
#: Point–piece pairs evaluated at once (bounds the memory of a query, ~40 MB).
PAIR_BUDGET = 1 << 19
#: The blocks of cells (``i ± k``, ``j ± k``) looked at in turn around a point, each adding
#: the ring around the one before; a point still open after the last goes to a grid
#: :data:`COARSER` times coarser (which ends up as one block holding every piece).
RINGS = (0, 1, 2, 3, 5, 8, 12, 16)
COARSER = 16.0
#: Default slack of the reachability test, relative to the drawing's size: rounding only.
REACH_RTOL = 1e-9
#: Relative slack for "the chain is closed" (last end on first start).
CLOSE_RTOL = 1e-9

# -- segments -----------------------------------------------------------------------------


class OSeg(NamedTuple):
    """The oracle's own segment: a line ``start``–``end``, or an arc about ``centre`` of
    ``radius`` from ``start`` through the signed ``sweep_rad`` (anticlockwise positive) to
    ``end``. A line's ``centre`` is NaN, its ``radius`` and ``sweep_rad`` 0."""

    kind: Literal["line", "arc"]
    start: tuple[float, float]
    end: tuple[float, float]
    centre: tuple[float, float] = (math.nan, math.nan)
    radius: float = 0.0
    sweep_rad: float = 0.0

    @property
    def start_angle_rad(self) -> float:
        """Polar angle of ``start`` about ``centre`` (an arc's ``θ₀``)."""
        return math.atan2(self.start[1] - self.centre[1], self.start[0] - self.centre[0])

    @property
    def length(self) -> float:
        """Arc length: ``‖B − A‖`` or ``r·|sweep|``."""
        if self.kind == "line":
            return math.dist(self.start, self.end)
        return self.radius * abs(self.sweep_rad)

    def point(self, t: float) -> tuple[float, float]:
        """The point at parameter ``t ∈ [0, 1]``."""
        xy = _Arrays.of([self]).points(np.zeros(1, dtype=np.intp), np.array([t]))[0]
        return float(xy[0]), float(xy[1])


def line(start: Sequence[float], end: Sequence[float]) -> OSeg:
    return OSeg("line", (float(start[0]), float(start[1])), (float(end[0]), float(end[1])))


def arc(centre: Sequence[float], radius: float, start_angle_rad: float, sweep_rad: float) -> OSeg:
    """The arc ``centre + radius·(cos θ, sin θ)``, ``θ`` from ``start_angle_rad`` through
    ``sweep_rad``; its ends computed from them."""
    cx, cy = float(centre[0]), float(centre[1])
    a1 = start_angle_rad + sweep_rad
    return OSeg(
        "arc",
        (cx + radius * math.cos(start_angle_rad), cy + radius * math.sin(start_angle_rad)),
        (cx + radius * math.cos(a1), cy + radius * math.sin(a1)),
        (cx, cy),
        float(radius),
        float(sweep_rad),
    )


def circle(centre: Sequence[float], radius: float, anticlockwise: bool = True) -> list[OSeg]:
    """A full circle as two half arcs from angle 0, closed bit for bit."""
    sense = 1.0 if anticlockwise else -1.0
    first = arc(centre, radius, 0.0, sense * math.pi)
    second = arc(centre, radius, sense * math.pi, sense * math.pi)
    return [first, second._replace(start=first.end, end=first.start)]


def polygon(points: Sequence[Sequence[float]]) -> list[OSeg]:
    """A closed chain of lines through ``points``."""
    return [line(points[i - 1], points[i]) for i in range(1, len(points))] + [
        line(points[-1], points[0])
    ]


def from_json(segments: Sequence[Mapping[str, Any]]) -> list[OSeg]:
    """API answer segments (``type`` ``line``/``arc``, ``start``, ``end``, an arc's
    ``center``, ``radius``, signed ``sweep_rad``)."""
    out = []
    for seg in segments:
        start = (float(seg["start"][0]), float(seg["start"][1]))
        end = (float(seg["end"][0]), float(seg["end"][1]))
        if seg["type"] == "line":
            out.append(OSeg("line", start, end))
        elif seg["type"] == "arc":
            centre = (float(seg["center"][0]), float(seg["center"][1]))
            out.append(OSeg("arc", start, end, centre, float(seg["radius"]), seg["sweep_rad"]))
        else:
            raise ValueError(f"segment type {seg['type']!r} is neither line nor arc")
    return out


def from_core(segments: Sequence[Any]) -> list[OSeg]:
    """Core ``Line``/``CircularArc`` values, read by their field names (``start``, ``end``,
    an arc's ``center``, ``radius``, ``sweep_rad``)."""
    out = []
    for seg in segments:
        start = (float(seg.start[0]), float(seg.start[1]))
        end = (float(seg.end[0]), float(seg.end[1]))
        fields = getattr(seg, "_fields", ())
        if "radius" in fields:
            centre = (float(seg.center[0]), float(seg.center[1]))
            out.append(OSeg("arc", start, end, centre, float(seg.radius), float(seg.sweep_rad)))
        elif fields == ("start", "end"):
            out.append(OSeg("line", start, end))
        else:
            raise ValueError(f"{type(seg).__name__} is neither a Line nor a CircularArc")
    return out


class _Arrays:
    """Segments as parallel arrays: ``a``/``b`` ends, ``c`` centre, ``r``, ``a0`` start angle,
    ``sw`` sweep, ``arc`` mask, ``length``."""

    def __init__(
        self, a: Array, b: Array, c: Array, r: Array, a0: Array, sw: Array, arc: npt.NDArray[Any]
    ) -> None:
        self.a, self.b, self.c, self.r, self.a0, self.sw = a, b, c, r, a0, sw
        self.arc = np.asarray(arc, dtype=bool)
        chord = np.hypot(*(b - a).T) if len(a) else np.zeros(0)
        self.length = np.where(self.arc, r * np.abs(sw), chord)

    @classmethod
    def of(cls, segs: Sequence[OSeg]) -> _Arrays:
        n = len(segs)
        a = np.array([s.start for s in segs], dtype=np.float64).reshape(n, 2)
        b = np.array([s.end for s in segs], dtype=np.float64).reshape(n, 2)
        c = np.array([s.centre for s in segs], dtype=np.float64).reshape(n, 2)
        is_arc = np.array([s.kind == "arc" for s in segs], dtype=bool)
        r = np.array([s.radius for s in segs], dtype=np.float64)
        sw = np.where(is_arc, np.array([s.sweep_rad for s in segs], dtype=np.float64), 0.0)
        with np.errstate(invalid="ignore"):
            a0 = np.where(is_arc, np.arctan2(a[:, 1] - c[:, 1], a[:, 0] - c[:, 0]), 0.0)
        return cls(a, b, np.where(is_arc[:, None], c, 0.0), r, a0, sw, is_arc)

    def __len__(self) -> int:
        return len(self.r)

    def points(self, i: npt.NDArray[np.intp], t: Array) -> Array:
        """Points at parameters ``t`` on segments ``i``; the ends are the stored ones."""
        theta = self.a0[i] + t * self.sw[i]
        on_arc = self.c[i] + self.r[i, None] * np.stack([np.cos(theta), np.sin(theta)], -1)
        on_line = self.a[i] + t[:, None] * (self.b[i] - self.a[i])
        out = np.where(self.arc[i, None], on_arc, on_line)
        out = np.where((t == 0.0)[:, None], self.a[i], out)
        return np.where((t == 1.0)[:, None], self.b[i], out)

    def left_normals(self, i: npt.NDArray[np.intp], t: Array) -> Array:
        """Unit normals to the left of the direction of travel: the tangent turned by +90°;
        on an arc ``−sign(sweep)·(cos θ, sin θ)`` (towards the centre when anticlockwise).
        NaN on a zero-length line."""
        theta = self.a0[i] + t * self.sw[i]
        radial = np.stack([np.cos(theta), np.sin(theta)], -1)
        on_arc = -np.sign(self.sw[i])[:, None] * radial
        d = self.b[i] - self.a[i]
        with np.errstate(invalid="ignore", divide="ignore"):
            on_line = np.stack([-d[:, 1], d[:, 0]], -1) / np.hypot(d[:, 0], d[:, 1])[:, None]
        return np.where(self.arc[i, None], on_arc, on_line)

    def box(self) -> tuple[Array, Array]:
        """The box of every segment: its ends, and where an arc's sweep passes the polar
        angles 0, π/2, π, 3π/2 its points there (an arc of huge radius and tiny sweep keeps a
        box the size of its chord: the grid and the default slacks scale with this box)."""
        ends = np.concatenate([self.a, self.b])
        if not len(ends):
            return np.zeros(2), np.zeros(2)
        lo, hi = ends.min(axis=0), ends.max(axis=0)
        arc = np.flatnonzero(self.arc)
        sense = np.where(self.sw[arc] >= 0, 1.0, -1.0)
        for angle in (0.0, math.pi / 2, math.pi, 1.5 * math.pi):
            passed = np.mod(sense * (angle - self.a0[arc]), 2 * math.pi) <= np.abs(self.sw[arc])
            if passed.any():
                j = arc[passed]
                extreme = self.c[j] + self.r[j, None] * np.array([math.cos(angle), math.sin(angle)])
                lo, hi = np.minimum(lo, extreme.min(axis=0)), np.maximum(hi, extreme.max(axis=0))
        return lo, hi


def _pair_distances(p: Array, s: _Arrays, i: npt.NDArray[np.intp]) -> Array:
    """Exact distance from each point ``p[k]`` to segment ``i[k]`` (see the module doc)."""
    out = np.empty(len(p))
    arc = s.arc[i]
    lin = ~arc
    if lin.any():
        q, a, b = p[lin], s.a[i[lin]], s.b[i[lin]]
        ab, aq = b - a, q - a
        den = ab[:, 0] ** 2 + ab[:, 1] ** 2
        with np.errstate(invalid="ignore", divide="ignore"):
            tau = np.clip((aq[:, 0] * ab[:, 0] + aq[:, 1] * ab[:, 1]) / den, 0.0, 1.0)
        tau = np.where(den > 0, tau, 0.0)
        out[lin] = np.hypot(aq[:, 0] - tau * ab[:, 0], aq[:, 1] - tau * ab[:, 1])
    if arc.any():
        j = i[arc]
        q, c = p[arc], s.c[j]
        v = q - c
        rho = np.hypot(v[:, 0], v[:, 1])
        sense = np.where(s.sw[j] >= 0, 1.0, -1.0)
        u = np.mod(sense * (np.arctan2(v[:, 1], v[:, 0]) - s.a0[j]), 2 * math.pi)
        inside = (u <= np.abs(s.sw[j])) & (rho > 0)
        to_ends = np.minimum(
            np.hypot(*(q - s.a[j]).T),
            np.hypot(*(q - s.b[j]).T),
        )
        out[arc] = np.where(inside, np.abs(rho - s.r[j]), to_ends)
    return out


# -- the broad phase ----------------------------------------------------------------------


class SegmentIndex:
    """Segments bucketed in a uniform grid, for the distance from many points to the nearest
    of them (see the module doc). Build once, query many times."""

    def __init__(self, segs: Sequence[OSeg]) -> None:
        if not segs:
            raise ValueError("no segments to measure against")
        arrays = _Arrays.of(segs)
        lo, hi = arrays.box()
        n = len(segs)
        span = hi - lo
        diag = float(np.hypot(*span))
        total = float(arrays.length.sum())
        # About four cells per segment over the box, never thinner than the average piece.
        cell = max(math.sqrt(float(span[0] * span[1]) / (4 * n)), total / (4 * n), diag / (8 * n))
        self._setup(arrays, cell if cell > 0 else 1.0)

    def _setup(self, arrays: _Arrays, cell: float) -> None:
        self.segments = arrays
        lo, hi = arrays.box()
        self.cell, self.origin = cell, lo
        self.shape = (int((hi - lo)[0] // cell) + 1, int((hi - lo)[1] // cell) + 1)
        self.pieces = self._cut(arrays, cell)
        self._bucket()
        self._coarser: SegmentIndex | None = None

    def _coarse(self) -> SegmentIndex:
        """The same segments over cells :data:`COARSER` times as wide (for far points)."""
        if self._coarser is None:
            coarse = SegmentIndex.__new__(SegmentIndex)
            coarse._setup(self.segments, self.cell * COARSER)
            self._coarser = coarse
        return self._coarser

    @staticmethod
    def _cut(s: _Arrays, cell: float) -> _Arrays:
        """Every segment as pieces of length ≤ ``cell`` (arcs: sweep ≤ π/4 as well)."""
        count = np.maximum(1, np.ceil(s.length / cell)).astype(np.intp)
        count = np.where(s.arc, np.maximum(count, np.ceil(np.abs(s.sw) / (math.pi / 4))), count)
        count = count.astype(np.intp)
        owner = np.repeat(np.arange(len(s)), count)
        first = np.repeat(np.cumsum(count) - count, count)
        k = np.arange(len(owner)) - first
        t0, t1 = k / count[owner], (k + 1) / count[owner]
        a, b = s.points(owner, t0), s.points(owner, t1)
        sw = s.sw[owner] / count[owner]
        a0 = s.a0[owner] + t0 * s.sw[owner]
        return _Arrays(a, b, s.c[owner], s.r[owner], a0, sw, s.arc[owner])

    def _cells(self, xy: Array) -> tuple[npt.NDArray[np.intp], npt.NDArray[np.intp]]:
        ij = np.floor((xy - self.origin) / self.cell)
        i = np.clip(ij[:, 0], 0, self.shape[0] - 1).astype(np.intp)
        j = np.clip(ij[:, 1], 0, self.shape[1] - 1).astype(np.intp)
        return i, j

    def _bucket(self) -> None:
        """CSR of cell → pieces whose box (chord box grown by the sagitta) meets the cell."""
        p = self.pieces
        sag = np.where(p.arc, p.r * (1 - np.cos(p.sw / 2)), 0.0)
        lo = np.minimum(p.a, p.b) - sag[:, None]
        hi = np.maximum(p.a, p.b) + sag[:, None]
        i0, j0 = self._cells(lo)
        i1, j1 = self._cells(hi)
        ids, keys = [], []
        for di in range(int((i1 - i0).max()) + 1):
            for dj in range(int((j1 - j0).max()) + 1):
                take = (i0 + di <= i1) & (j0 + dj <= j1)
                ids.append(np.flatnonzero(take))
                keys.append((i0[take] + di) * self.shape[1] + (j0[take] + dj))
        key, piece = np.concatenate(keys), np.concatenate(ids)
        order = np.argsort(key, kind="stable")
        self._piece = piece[order]
        cells = self.shape[0] * self.shape[1]
        self._start = np.searchsorted(key[order], np.arange(cells + 1)).astype(np.intp)

    def distance(self, points: Any) -> Array:
        """Exact distance from each point to the nearest segment, ``(n,)``."""
        xy = np.asarray(points, dtype=np.float64).reshape(-1, 2)
        best = np.full(len(xy), np.inf)
        i, j = self._cells(xy)
        todo = np.arange(len(xy))
        inner = -1
        for k in RINGS:
            ring = _ring(inner, k)
            for chunk in _chunks(todo, max(1, PAIR_BUDGET // len(ring))):
                self._block(xy, chunk, i[chunk], j[chunk], ring, best)
            done = best[todo] <= self._beyond(xy[todo], i[todo], j[todo], k)
            todo = todo[~done]
            inner = k
            if not todo.size:
                return best
        best[todo] = self._coarse().distance(xy[todo])
        return best

    def _beyond(self, xy: Array, i: npt.NDArray[np.intp], j: npt.NDArray[np.intp], k: int) -> Array:
        """A lower bound on the distance from each point to any piece outside its block
        (cells ``i ± k``, ``j ± k``): the distance to the nearest side of the block that is
        not the grid's own edge (nothing lies beyond that); ∞ when the block is the grid."""
        h, (nx, ny) = self.cell, self.shape
        x, y = (xy - self.origin).T
        inf = np.inf
        bound: Array = np.min(
            [
                np.where(i - k > 0, x - (i - k) * h, inf),
                np.where(i + k + 1 < nx, (i + k + 1) * h - x, inf),
                np.where(j - k > 0, y - (j - k) * h, inf),
                np.where(j + k + 1 < ny, (j + k + 1) * h - y, inf),
            ],
            axis=0,
        )
        return bound

    def _block(
        self,
        xy: Array,
        chunk: npt.NDArray[np.intp],
        i: npt.NDArray[np.intp],
        j: npt.NDArray[np.intp],
        ring: npt.NDArray[np.intp],
        best: Array,
    ) -> None:
        """Every piece in the cells ``(i, j) + ring`` of each point of ``chunk``."""
        ci = i[:, None] + ring[None, :, 0]
        cj = j[:, None] + ring[None, :, 1]
        inside = (ci >= 0) & (ci < self.shape[0]) & (cj >= 0) & (cj < self.shape[1])
        key = np.where(inside, ci * self.shape[1] + cj, 0)
        start = self._start[key]
        count = np.where(inside, self._start[key + 1] - start, 0)
        per_point = count.sum(axis=1)
        for part in _split_by_pairs(per_point):
            self._pairs(xy, chunk[part], start[part].ravel(), count[part].ravel(), best)

    def _pairs(
        self,
        xy: Array,
        pts: npt.NDArray[np.intp],
        start: npt.NDArray[np.intp],
        count: npt.NDArray[np.intp],
        best: Array,
    ) -> None:
        total = int(count.sum())
        if total == 0:
            return
        cells_per_point = len(start) // len(pts)
        owner = np.repeat(np.repeat(pts, cells_per_point), count)
        offset = np.repeat(start - (np.cumsum(count) - count), count)
        piece = self._piece[offset + np.arange(total)]
        d = _pair_distances(xy[owner], self.pieces, piece)
        np.minimum.at(best, owner, d)


def _ring(inner: int, outer: int) -> npt.NDArray[np.intp]:
    """Cell offsets ``(di, dj)`` with ``inner < max(|di|, |dj|) ≤ outer``, ``(m, 2)``."""
    span = np.arange(-outer, outer + 1)
    di, dj = np.meshgrid(span, span, indexing="ij")
    keep = np.maximum(np.abs(di), np.abs(dj)) > inner
    return np.stack([di[keep], dj[keep]], -1).astype(np.intp)


def _chunks(index: npt.NDArray[np.intp], size: int) -> Iterator[npt.NDArray[np.intp]]:
    for s in range(0, len(index), size):
        yield index[s : s + size]


def _split_by_pairs(per_point: npt.NDArray[np.intp]) -> Iterator[slice]:
    """Consecutive runs of points whose pairs add up to at most :data:`PAIR_BUDGET` (a single
    point over it runs alone)."""
    edges = np.cumsum(per_point)
    s = 0
    while s < len(per_point):
        base = edges[s - 1] if s else 0
        e = max(s + 1, int(np.searchsorted(edges, base + PAIR_BUDGET, side="right")))
        yield slice(s, e)
        s = e


def distance_to(points: Any, segs: Sequence[OSeg]) -> Array:
    """Exact distance from each of ``points`` (``(n, 2)``) to the nearest of ``segs``."""
    return SegmentIndex(segs).distance(points)


# -- sampling and refinement --------------------------------------------------------------


class _Samples(NamedTuple):
    seg: npt.NDArray[np.intp]  # which segment
    t: Array  # parameter on it
    step: Array  # the segment's parameter spacing


def _samples(s: _Arrays, spacing: float) -> _Samples:
    """Every segment sampled evenly in its parameter (= arc length), ends included: at least
    :data:`MIN_SAMPLES`, one per ``spacing`` of length, at most :data:`MAX_SAMPLES`."""
    n = np.clip(np.ceil(s.length / spacing) + 1, MIN_SAMPLES, MAX_SAMPLES).astype(np.intp)
    seg = np.repeat(np.arange(len(s)), n)
    first = np.repeat(np.cumsum(n) - n, n)
    k = np.arange(len(seg)) - first
    step = 1.0 / (n[seg] - 1)
    return _Samples(seg, np.minimum(k * step, 1.0), step)


def _golden(
    f: Callable[[npt.NDArray[np.intp], Array], Array],
    seg: npt.NDArray[np.intp],
    lo: Array,
    hi: Array,
) -> tuple[Array, Array]:
    """Element-wise golden-section search for the maximum of ``f(seg, t)`` on ``[lo, hi]``;
    the ends of the bracket are candidates too (the extreme may sit at a segment's end)."""
    g = (math.sqrt(5.0) - 1.0) / 2.0
    a, b = lo.copy(), hi.copy()
    x1, x2 = b - g * (b - a), a + g * (b - a)
    f1, f2 = f(seg, x1), f(seg, x2)
    for _ in range(GOLDEN_STEPS):
        left = f1 >= f2
        a, b = np.where(left, a, x1), np.where(left, x2, b)
        x2n = np.where(left, x1, a + g * (b - a))
        x1n = np.where(left, b - g * (b - a), x2)
        fn = f(seg, np.where(left, x1n, x2n))
        f1, f2 = np.where(left, fn, f2), np.where(left, f1, fn)
        x1, x2 = x1n, x2n
    t = np.stack([lo, hi, x1, x2], -1)
    v = np.stack([f(seg, lo), f(seg, hi), f1, f2], -1)
    pick = np.argmax(v, axis=1)
    rows = np.arange(len(seg))
    return t[rows, pick], v[rows, pick]


class _Extreme(NamedTuple):
    value: float
    at: tuple[float, float]
    counted: int  # samples where f > −∞
    samples: int


def _extreme(
    s: _Arrays, f: Callable[[npt.NDArray[np.intp], Array], Array], spacing: float
) -> _Extreme:
    """The maximum of ``f`` over all segments of ``s``: sampled, then the :data:`REFINED`
    best segments refined around their best sample (± one sample spacing); ``f = −∞``
    marks parameters that do not count."""
    smp = _samples(s, spacing)
    v = f(smp.seg, smp.t)
    counted = int((v > -math.inf).sum())
    if not counted:
        return _Extreme(-math.inf, (math.nan, math.nan), 0, len(v))
    order = np.lexsort((-v, smp.seg))  # per segment, best first
    heads = order[np.r_[True, smp.seg[order][1:] != smp.seg[order][:-1]]]
    heads = heads[v[heads] > -math.inf]
    heads = heads[np.argsort(-v[heads], kind="stable")[:REFINED]]
    seg, t, step = smp.seg[heads], smp.t[heads], smp.step[heads]
    tt, vv = _golden(f, seg, np.maximum(t - step, 0.0), np.minimum(t + step, 1.0))
    better = vv >= v[heads]
    tt, vv = np.where(better, tt, t), np.where(better, vv, v[heads])
    k = int(np.argmax(vv))
    at = s.points(seg[k : k + 1], tt[k : k + 1])[0]
    return _Extreme(float(vv[k]), (float(at[0]), float(at[1])), counted, len(v))


# -- sides, closedness, corners -----------------------------------------------------------


def is_closed(segs: Sequence[OSeg]) -> bool:
    """The chain's last end meets its first start (within :data:`CLOSE_RTOL` of its size)."""
    if not segs:
        return False
    scale = max(1.0, *(abs(c) for s in segs for c in (*s.start, *s.end)))
    return math.dist(segs[-1].end, segs[0].start) <= CLOSE_RTOL * scale


def signed_area(segs: Sequence[OSeg]) -> float:
    """Area enclosed by a closed chain, anticlockwise positive: the shoelace sum of the chords
    ``½(xₐ·y_b − x_b·yₐ)`` plus each arc's circular segment ``½r²(Δθ − sin Δθ)``."""
    area = 0.0
    for s in segs:
        area += 0.5 * (s.start[0] * s.end[1] - s.end[0] * s.start[1])
        if s.kind == "arc":
            area += 0.5 * s.radius**2 * (s.sweep_rad - math.sin(s.sweep_rad))
    return area


def _left_sign(segs: Sequence[OSeg], side: Side | None, k: int) -> float:
    """+1 when the cut side is left of the direction of travel, −1 right, 0 none."""
    if side is None:
        return 0.0
    if side in ("left", "right"):
        return 1.0 if side == "left" else -1.0
    if side not in ("outside", "inside"):
        raise ValueError(f"contour {k}: side {side!r} is not outside/inside/left/right")
    if not is_closed(segs):
        raise ValueError(f"contour {k}: {side} needs a closed contour")
    anticlockwise = signed_area(segs) > 0
    # Outside of an anticlockwise loop is on the right of travel.
    return (-1.0 if anticlockwise else 1.0) * (1.0 if side == "outside" else -1.0)


def _sides(spec: SideSpec, n: int) -> list[Side | None]:
    if spec is None or isinstance(spec, str):
        return [spec] * n
    if callable(spec):
        return [spec(k) for k in range(n)]
    sides = list(spec)
    if len(sides) != n:
        raise ValueError(f"{len(sides)} sides for {n} contours")
    return sides


def corners(segs: Sequence[OSeg], closed: bool, angle_deg: float = 1e-3) -> list[int]:
    """Joints that are not G1: indices ``j`` where the unit tangent at the end of segment
    ``j − 1`` and at the start of segment ``j`` differ by more than ``angle_deg`` (``j = 0``
    is the closing joint of a closed chain). Angle ``atan2(|u×v|, u·v)``."""
    if not segs:
        return []
    s = _Arrays.of(segs)
    n = len(s)
    idx = np.arange(n)
    # Direction of travel = the left normal turned by −90°: (x, y) → (y, −x).
    start_n = s.left_normals(idx, np.zeros(n))
    end_n = s.left_normals(idx, np.ones(n))
    out = []
    for j in range(0 if closed else 1, n):
        u, v = end_n[j - 1], start_n[j]
        angle = math.degrees(math.atan2(abs(u[0] * v[1] - u[1] * v[0]), u[0] * v[0] + u[1] * v[1]))
        if not angle <= angle_deg:
            out.append(j)
    return out


# -- the check ----------------------------------------------------------------------------


class OffsetReport(NamedTuple):
    """What :func:`check_offset` measured. ``farthest_mm`` (and ``centre_gap_mm``) is 0 at
    NaN when no contour point is reachable; ``reachable`` counts the reachable contour
    samples of ``samples``.

    ``centre_gap_mm``: max over reachable contour points ``p`` of the distance from the tool
    centre that touches ``p`` on the cut side (``p + d·n``) to the path. ``farthest_mm``
    alone cannot tell the sides apart (a circle's inside offset is also ``d`` from every
    point of it); this can: the path must pass through every reachable tool position.
    """

    closest_mm: float
    closest_at: tuple[float, float]
    farthest_mm: float
    farthest_at: tuple[float, float]
    centre_gap_mm: float = 0.0
    centre_gap_at: tuple[float, float] = (math.nan, math.nan)
    reachable: int = 0
    samples: int = 0

    def ok(self, distance: float, tolerance: float, *, sided: bool = True) -> bool:
        """The path keeps ``distance − tolerance`` clear of every contour and comes within
        ``distance + tolerance`` of every reachable contour point; ``sided``: and passes
        within ``tolerance`` of every reachable tool position on the cut side."""
        return (
            self.closest_mm >= distance - tolerance
            and self.farthest_mm <= distance + tolerance
            and (not sided or self.centre_gap_mm <= tolerance)
        )

    def describe(self) -> str:
        x0, y0 = self.closest_at
        x1, y1 = self.farthest_at
        x2, y2 = self.centre_gap_at
        return (
            f"tool path comes within {self.closest_mm:.12g} of a contour at ({x0:.9g}, {y0:.9g});"
            f" a reachable contour point is {self.farthest_mm:.12g} from the tool path at "
            f"({x1:.9g}, {y1:.9g}); the tool touching the contour at ({x2:.9g}, {y2:.9g}) "
            f"has its centre {self.centre_gap_mm:.12g} off the path ({self.reachable} of "
            f"{self.samples} contour samples reachable)"
        )


def check_offset(
    contours: Sequence[Sequence[OSeg]],
    paths: Sequence[Sequence[OSeg]],
    distance: float,
    side_of: SideSpec = "outside",
    *,
    reach_tolerance: float | None = None,
) -> OffsetReport:
    """Measure tool-centre ``paths`` against the part's ``contours`` for a tool of radius
    ``distance``:

    * ``closest_mm``: min over path points of the distance to every contour (all of them);
    * ``farthest_mm``: max over reachable contour points of the distance to the paths.

    ``side_of`` says which side of each contour is cut: ``"outside"``/``"inside"`` (closed
    contours, by the oracle's own signed area), ``"left"``/``"right"`` of the direction of
    travel (any contour), ``None`` (the contour only constrains: it bounds the tool and the
    reachability, but none of its points must be reached); one value for all contours, one
    per contour (``side_of[k]``), or a callable ``side_of(k)``. E.g. "outside of contour 2
    only": ``lambda k: "outside" if k == 2 else None``. ``reach_tolerance`` (default
    :data:`REACH_RTOL` × the drawing's size) is the slack of the reachability test.
    """
    if not (math.isfinite(distance) and distance > 0):
        raise ValueError(f"distance {distance!r} must be finite and > 0")
    every = [s for c in contours for s in c]
    tool = [s for p in paths for s in p]
    if not every:
        raise ValueError("no contour segments")
    sides = _sides(side_of, len(contours))
    signs = [
        _left_sign(list(c), side, k)
        for k, (c, side) in enumerate(zip(contours, sides, strict=True))
    ]
    part = SegmentIndex(every)
    lo, hi = part.segments.box()
    size = float(max(np.abs(lo).max(), np.abs(hi).max(), np.hypot(*(hi - lo)), distance))
    reach = REACH_RTOL * size if reach_tolerance is None else reach_tolerance
    spacing = size / SPACING_DIVISOR

    closest, closest_at = math.inf, (math.nan, math.nan)
    along = SegmentIndex(tool) if tool else None
    if along is not None:
        on_path = along.segments

        def negated(i: npt.NDArray[np.intp], t: Array) -> Array:
            return -part.distance(on_path.points(i, t))

        nearest = _extreme(on_path, negated, spacing)
        closest, closest_at = -nearest.value, nearest.at

    sign = np.repeat(np.array(signs), [len(c) for c in contours])
    cut = part.segments

    def reached(of_centre: bool) -> Callable[[npt.NDArray[np.intp], Array], Array]:
        """Distance from each reachable contour point (or the centre of the tool touching
        it) to the path; −∞ where not reachable."""

        def f(i: npt.NDArray[np.intp], t: Array) -> Array:
            p = cut.points(i, t)
            centre = p + distance * sign[i, None] * cut.left_normals(i, t)
            ok = (sign[i] != 0) & np.isfinite(centre).all(axis=1)
            ok[ok] = part.distance(centre[ok]) >= distance - reach
            out = np.full(len(i), -math.inf)
            if ok.any():
                measured = centre[ok] if of_centre else p[ok]
                out[ok] = along.distance(measured) if along is not None else math.inf
            return out

        return f

    far = _extreme(cut, reached(False), spacing)
    gap = _extreme(cut, reached(True), spacing)
    return OffsetReport(
        closest,
        closest_at,
        max(far.value, 0.0),
        far.at,
        max(gap.value, 0.0),
        gap.at,
        far.counted,
        far.samples,
    )


def _moved(segs: Sequence[OSeg], dx: float, dy: float) -> list[OSeg]:
    def at(p: tuple[float, float]) -> tuple[float, float]:
        return (p[0] + dx, p[1] + dy)

    return [
        s._replace(
            start=at(s.start), end=at(s.end), centre=at(s.centre) if s.kind == "arc" else s.centre
        )
        for s in segs
    ]


def check_each(
    contours: Sequence[Sequence[OSeg]],
    paths: Sequence[Sequence[OSeg]],
    origin: Sequence[int],
    distance: float,
    side_of: SideSpec = "outside",
    *,
    reach_tolerance: float | None = None,
) -> OffsetReport:
    """:func:`check_offset` of every contour ``k`` against only the paths made from it
    (``origin[i]``: the contour path ``i`` was made from), in one pass: each contour with its
    paths is moved to a square of its own on a grid, squares more than ``4·distance`` apart,
    so that nothing of one is within reach of another's (a contour without a path is more
    than ``4·distance`` from any). The reported places are moved back.
    ``reach_tolerance`` defaults to :data:`REACH_RTOL` × the unmoved drawing's size."""
    if len(origin) != len(paths):
        raise ValueError(f"{len(origin)} origins for {len(paths)} paths")
    n = len(contours)
    boxes = []
    for k, c in enumerate(contours):
        own = [s for p, o in zip(paths, origin, strict=True) if o == k for s in p]
        boxes.append(_Arrays.of([*c, *own]).box())
    lo = np.min([b[0] for b in boxes], axis=0)
    hi = np.max([b[1] for b in boxes], axis=0)
    size = float(max(np.abs(lo).max(), np.abs(hi).max(), np.hypot(*(hi - lo)), distance))
    pitch = max(float(np.max(b[1] - b[0])) for b in boxes) + 4 * distance + 1.0
    columns = math.ceil(math.sqrt(n))
    shift = [
        (k % columns * pitch - float(boxes[k][0][0]), k // columns * pitch - float(boxes[k][0][1]))
        for k in range(n)
    ]
    sides = _sides(side_of, n)
    report = check_offset(
        [_moved(c, *shift[k]) for k, c in enumerate(contours)],
        [_moved(p, *shift[o]) for p, o in zip(paths, origin, strict=True)],
        distance,
        sides,
        reach_tolerance=REACH_RTOL * size if reach_tolerance is None else reach_tolerance,
    )

    def back(at: tuple[float, float]) -> tuple[float, float]:
        if not all(math.isfinite(v) for v in at):
            return at
        k = int(at[1] // pitch) * columns + int(at[0] // pitch)
        return (at[0] - shift[k][0], at[1] - shift[k][1])

    return report._replace(
        closest_at=back(report.closest_at),
        farthest_at=back(report.farthest_at),
        centre_gap_at=back(report.centre_gap_at),
    )
