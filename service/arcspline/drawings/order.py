"""Ordering toolpaths to shorten the rapids between them (docs/drawings.md §5).

The rapids run from ``start`` to the first toolpath's start, then from each toolpath's end to
the next one's start (not back home at the end). The order is built by nearest neighbour
from ``start`` (an open toolpath may be entered at either end, and is then cut reversed; a
closed one at its start, or with ``choose_start`` at whichever segment start is nearest, the
contour rotated to begin there), then improved by 2-opt: reversing a run of the order (which
also reverses the open toolpaths in it) wherever that shortens the rapids. The 2-opt search is
bounded (:data:`TWO_OPT_MAX_PATHS`, :data:`TWO_OPT_WINDOW`, :data:`TWO_OPT_MAX_PASSES`) so
that its work stays near linear, and deterministic: no clock is read. If the result were
longer than the input order, the input order is kept.

Closed toolpaths are never reversed: that would turn climb milling into conventional.
"""

from __future__ import annotations

import math
from collections import defaultdict
from collections.abc import Sequence
from typing import NamedTuple

import numpy as np
import numpy.typing as npt

from arcspline.geometry.curves.segments import Subpath
from arcspline.geometry.spline import FloatArray, Point

from .join import Toolpath, reversed_subpath

IntArray = npt.NDArray[np.int64]

#: Where the rapids start when no start is given.
ORIGIN = Point(0.0, 0.0)
#: Up to this many toolpaths, 2-opt tries every pair of positions.
TWO_OPT_MAX_PATHS = 400
#: Beyond it, 2-opt tries only runs of up to this many toolpaths.
TWO_OPT_WINDOW = 24
#: At most this many sweeps over the order.
TWO_OPT_MAX_PASSES = 20
#: A 2-opt move must gain more than this fraction of the total rapid length (rounding noise
#: would otherwise let moves undo each other).
MIN_GAIN = 1e-12


class Ordered(NamedTuple):
    """The toolpaths in cutting order (reversed or rotated as they are to be cut); the rapid
    length from ``start`` through the toolpaths in input order and in this order; and for each
    toolpath here, its index in the input."""

    toolpaths: tuple[Toolpath, ...]
    rapid_before: float
    rapid_after: float
    order: tuple[int, ...]


def rapid_length(toolpaths: Sequence[Toolpath], start: Point = ORIGIN) -> float:
    """From ``start`` to the first toolpath's start, then each end to the next start."""
    total, here = 0.0, start
    for toolpath in toolpaths:
        segments = toolpath.subpath.segments
        total += math.dist(here, segments[0].start)
        here = segments[-1].end
    return total


def rotated(subpath: Subpath, first: int) -> Subpath:
    """A closed subpath begun at its segment ``first`` (the same segments, in cyclic order)."""
    return Subpath(subpath.segments[first:] + subpath.segments[:first], subpath.closed)


def order(
    toolpaths: Sequence[Toolpath], start: Point = ORIGIN, choose_start: bool = False
) -> Ordered:
    """The toolpaths ordered to shorten the rapids (see the module's docstring)."""
    start = Point(float(start[0]), float(start[1]))
    before = rapid_length(toolpaths, start)
    unchanged = Ordered(tuple(toolpaths), before, before, tuple(range(len(toolpaths))))
    if not toolpaths or any(not t.subpath.segments for t in toolpaths):
        # An empty toolpath has no place to go between others.
        return unchanged
    entries = _entries(toolpaths, choose_start)
    used = _nearest_neighbour(entries, len(toolpaths), start)
    perm, flipped = _two_opt(entries.entry[used], entries.exit[used], start)
    used = used[perm]
    result = []
    for e, flip in zip(used.tolist(), flipped.tolist(), strict=True):
        toolpath = toolpaths[int(entries.path[e])]
        kind = int(entries.kind[e])
        if kind == _CLOSED:
            # A closed contour is never reversed: only where it starts changes.
            toolpath = toolpath._replace(subpath=rotated(toolpath.subpath, int(entries.vertex[e])))
        elif (kind == _REVERSED) != flip:
            toolpath = Toolpath(reversed_subpath(toolpath.subpath), toolpath.sources[::-1])
        result.append(toolpath)
    after = rapid_length(result, start)
    if after > before:
        return unchanged
    return Ordered(tuple(result), before, after, tuple(entries.path[used].tolist()))


_FORWARD, _REVERSED, _CLOSED = 0, 1, 2


class _Entries(NamedTuple):
    """The ways into each toolpath: where the cut starts and ends, which toolpath, how (kind:
    forward, reversed, closed) and for a closed one at which segment."""

    entry: FloatArray
    exit: FloatArray
    path: IntArray
    kind: IntArray
    vertex: IntArray


def _entries(toolpaths: Sequence[Toolpath], choose_start: bool) -> _Entries:
    entry: list[Point] = []
    exit_: list[Point] = []
    path: list[int] = []
    kind: list[int] = []
    vertex: list[int] = []
    for k, toolpath in enumerate(toolpaths):
        segments = toolpath.subpath.segments
        if toolpath.subpath.closed:
            starts = [s.start for s in segments] if choose_start else [segments[0].start]
            entry += starts
            exit_ += starts
            path += [k] * len(starts)
            kind += [_CLOSED] * len(starts)
            vertex += range(len(starts))
        else:
            entry += [segments[0].start, segments[-1].end]
            exit_ += [segments[-1].end, segments[0].start]
            path += [k, k]
            kind += [_FORWARD, _REVERSED]
            vertex += [0, 0]
    return _Entries(
        np.array(entry, dtype=np.float64).reshape(-1, 2),
        np.array(exit_, dtype=np.float64).reshape(-1, 2),
        np.array(path, dtype=np.int64),
        np.array(kind, dtype=np.int64),
        np.array(vertex, dtype=np.int64),
    )


class _Grid:
    """The entry points in square cells, for nearest-neighbour queries with removal; rebuilt
    whenever half the points it was built with are gone, so that searches do not wander over
    emptied cells."""

    def __init__(self, points: FloatArray, owner: list[int], alive: list[bool]) -> None:
        self.xy = [(float(x), float(y)) for x, y in points.tolist()]
        self.owner = owner
        self.alive = alive
        self._build()

    def _build(self) -> None:
        live = [i for i, k in enumerate(self.owner) if self.alive[k]]
        self.count = len(live)
        pts = np.array([self.xy[i] for i in live], dtype=np.float64).reshape(-1, 2)
        lo, hi = pts.min(axis=0), pts.max(axis=0)
        extent = hi - lo
        side = float(extent.max())
        area = float(np.prod(np.maximum(extent, side / max(len(live), 1))))
        # About two points a cell (a line of points gets cells along its length).
        cell = math.sqrt(2.0 * area / len(live)) if area > 0.0 else 1.0
        self.cell = cell if math.isfinite(cell) and cell > 0.0 else 1.0
        self.lo = (float(lo[0]), float(lo[1]))
        keys = np.floor((pts - lo) / self.cell).astype(np.int64)
        self.cells: defaultdict[tuple[int, int], list[int]] = defaultdict(list)
        for i, (cx, cy) in zip(live, keys.tolist(), strict=True):
            self.cells[(cx, cy)].append(i)
        self.span = (int(keys[:, 0].max()) + 1, int(keys[:, 1].max()) + 1)
        self.removed = 0

    def nearest(self, x: float, y: float) -> int:
        """The live point nearest ``(x, y)`` (ties: the lowest index). The rings of cells are
        searched about the query's cell clamped into the grid: the distance to the grid's
        nearest point is a lower bound of the distance to any point in it."""
        cx = min(max(math.floor((x - self.lo[0]) / self.cell), 0), self.span[0] - 1)
        cy = min(max(math.floor((y - self.lo[1]) / self.cell), 0), self.span[1] - 1)
        best, best_d2 = -1, math.inf
        xy, owner, alive = self.xy, self.owner, self.alive
        last_ring = max(self.span) + 1
        for ring in range(last_ring + 1):
            # Cells of this ring and beyond lie at least (ring - 1) cells from the query.
            if best >= 0 and (ring - 1) * self.cell > math.sqrt(best_d2):
                break
            for key in _ring(cx, cy, ring):
                bucket = self.cells.get(key)
                if not bucket:
                    continue
                kept = []
                for i in bucket:
                    if alive[owner[i]]:
                        kept.append(i)
                        px, py = xy[i]
                        d2 = (px - x) ** 2 + (py - y) ** 2
                        if d2 < best_d2 or (d2 == best_d2 and i < best):
                            best, best_d2 = i, d2
                bucket[:] = kept
        return best

    def removed_path(self, points_of_path: int) -> None:
        self.removed += points_of_path
        if self.removed * 2 > self.count and any(self.alive):
            self._build()


def _ring(cx: int, cy: int, r: int) -> list[tuple[int, int]]:
    if r == 0:
        return [(cx, cy)]
    rows = [(cx + d, cy + s) for s in (-r, r) for d in range(-r, r + 1)]
    return rows + [(cx + s, cy + d) for s in (-r, r) for d in range(-r + 1, r)]


def _nearest_neighbour(entries: _Entries, paths: int, start: Point) -> IntArray:
    """The entry used for each toolpath in visiting order, by nearest neighbour."""
    alive = [True] * paths
    owner = entries.path.tolist()
    per_path = np.bincount(entries.path, minlength=paths).tolist()
    grid = _Grid(entries.entry, owner, alive)
    used = np.empty(paths, dtype=np.int64)
    exits = entries.exit.tolist()
    x, y = start
    for step in range(paths):
        e = grid.nearest(x, y)
        k = owner[e]
        used[step] = e
        alive[k] = False
        x, y = exits[e]
        grid.removed_path(per_path[k])
    return used


def _two_opt(
    entry: FloatArray, exit_: FloatArray, start: Point
) -> tuple[IntArray, npt.NDArray[np.bool_]]:
    """Reverse runs ``i..j`` of the order (one toolpath alone included) where that shortens
    the rapids: the rapid into ``i`` and the one out of ``j`` become one into ``j``'s old exit
    and one out of ``i``'s old entry. Each sweep finds the best run from every ``i`` (up to
    ``window`` long) at once, then makes the best of them that share no rapid, so that their
    gains add up exactly. Returns the new order (as positions of the old) and which
    positions run reversed. A closed toolpath's entry and exit coincide: reversing it in a
    run changes no rapid, and it is not reversed."""
    n = len(entry)
    perm = np.arange(n)
    flip = np.zeros(n, dtype=np.bool_)
    entry, exit_ = entry.copy(), exit_.copy()
    window = n if n <= TWO_OPT_MAX_PATHS else TWO_OPT_WINDOW
    origin = np.array(start, dtype=np.float64).reshape(1, 2)
    i = np.arange(n).reshape(-1, 1)
    j = i + np.arange(window).reshape(1, -1)
    inside = j < n
    j = np.minimum(j, n - 1)
    has_next = inside & (j + 1 < n)
    after = np.minimum(j + 1, n - 1)
    for _ in range(TWO_OPT_MAX_PASSES):
        before = np.concatenate([origin, exit_[:-1]])
        into = np.hypot(*(entry - before).T)
        total = float(into.sum())
        old = into[:, None] + np.where(has_next, into[after], 0.0)
        new = np.hypot(*(exit_[j] - before[:, None]).transpose(2, 0, 1)) + np.where(
            has_next, np.hypot(*(entry[after] - entry[:, None]).transpose(2, 0, 1)), 0.0
        )
        gain = np.where(inside, old - new, -np.inf)
        best = np.argmax(gain, axis=1)
        best_gain = gain[np.arange(n), best]
        runs = np.flatnonzero(best_gain > MIN_GAIN * max(total, 1e-300))
        if not len(runs):
            break
        runs = runs[np.lexsort((runs, -best_gain[runs]))]
        taken = np.zeros(n + 1, dtype=np.bool_)
        for first in runs.tolist():
            last = first + int(best[first])
            # Runs that share no rapid: a free toolpath on each side.
            if taken[max(first - 1, 0) : last + 2].any():
                continue
            taken[first : last + 1] = True
            k = slice(first, last + 1)
            perm[k] = perm[k][::-1].copy()
            entry[k], exit_[k] = exit_[k][::-1].copy(), entry[k][::-1].copy()
            flip[k] = ~flip[k][::-1]
    return perm, flip
