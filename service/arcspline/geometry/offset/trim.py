"""The global step: cut the raw offset where it meets itself, keep the slices that stay at
least ``d`` from the source, and stitch them into loops or pieces (docs/offsets.md §5).

A slice between two consecutive cut points is either wholly at distance ``≥ d`` from the
source or wholly nearer (the distance changes from one to the other only where the slice
meets another part of the offset, where it was cut), so one exact minimum distance per slice
decides it. An open chain's raw offset is also cut where it crosses the circles of radius
``d`` about the chain's two ends, the only other places where that can change.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Sequence
from typing import NamedTuple

import numpy as np

from ..curves.segments import CircularArc
from ..path_spline import IntArray
from ..spline import Point
from .broad import overlapping
from .chain import Rows, self_hits
from .distance import min_distances
from .intersect import hits
from .shapes import piece
from .table import Table, boxes, element_lengths, table_of
from .types import Element

#: At most this many elements of one slice are measured against the source.
TESTED = 256


class Cut(NamedTuple):
    """A cut point on the raw chain: element ``at`` at parameter ``t``, at ``point``."""

    at: int
    t: float
    point: Point


class Slice(NamedTuple):
    """Part of the raw chain between two cuts: its elements, each with its raw index and
    parameter range."""

    elements: list[Element]
    spans: list[tuple[int, float, float]]

    @property
    def start(self) -> Point:
        return Point(*self.elements[0].start)

    @property
    def end(self) -> Point:
        return Point(*self.elements[-1].end)


class Kept(NamedTuple):
    """The slices kept, in chain order, and the raw elements (by index) any of them uses."""

    slices: list[Slice]
    used: set[int]


def keep_slices(
    raws: Sequence[Sequence[Element]],
    closed: Sequence[bool],
    sources: Sequence[Sequence[Element]],
    distance: float,
    tol: float,
    keep_tol: float,
    scale: float,
) -> list[Kept]:
    """For each raw chain, its slices at least ``distance − keep_tol`` from its own source
    chain (module docstring); an open chain is also cut at the circles about its source's
    ends. All chains go through each vectorised step together."""
    table = table_of([e for raw in raws for e in raw])
    rows = Rows.of([len(r) for r in raws], closed)
    first = np.concatenate([[0], np.cumsum([len(r) for r in raws])])
    cuts = _cuts(table, rows, first, closed, sources, distance, tol, scale)
    slices = [
        _slices(list(raw), is_closed, chain_cuts)
        for raw, is_closed, chain_cuts in zip(raws, closed, cuts, strict=True)
    ]
    flat = [s for chain in slices for s in chain]
    if not flat:
        return [Kept([], set()) for _ in raws]
    slice_chain = np.repeat(np.arange(len(raws)), [len(c) for c in slices])
    tested = [_tested(s) for s in flat]
    pieces = [e for s in tested for e in s]
    owner = np.repeat(np.arange(len(flat)), [len(s) for s in tested])
    source = table_of([e for src in sources for e in src])
    source_chain = np.repeat(np.arange(len(sources)), [len(s) for s in sources])
    nearest = min_distances(
        table_of(pieces), owner, slice_chain[owner], len(flat), source, source_chain, distance,
        tol,
    )  # fmt: skip
    good = (nearest >= distance - keep_tol).tolist()
    out, k = [], 0
    for chain in slices:
        kept = [s for s, ok in zip(chain, good[k : k + len(chain)], strict=True) if ok]
        k += len(chain)
        out.append(Kept(kept, {i for s in kept for i, _, _ in s.spans}))
    return out


def _tested(s: Slice) -> list[Element]:
    """The elements of a slice whose distance to the source decides it: up to three, and one
    in eight beyond, at most ``TESTED``, spread along it (with its first and last). A slice
    lies wholly on one side of the distance ``d`` (module docstring), so one would do; the
    spread guards against a crossing lost in rounding, at a bounded cost: an element near a
    long smooth stretch of source has hundreds of source elements within ``d``."""
    n = len(s.elements)
    count = min(n, TESTED, 3 + n // 8)
    if count == n:
        return s.elements
    picks = np.unique(np.linspace(0, n - 1, count).round().astype(np.int64))
    return [s.elements[k] for k in picks.tolist()]


def _cuts(
    table: Table,
    rows: Rows,
    first: IntArray,
    closed: Sequence[bool],
    sources: Sequence[Sequence[Element]],
    distance: float,
    tol: float,
    scale: float,
) -> list[list[Cut]]:
    """Every chain's cut points, sorted along it, duplicates removed."""
    found, i, j = self_hits(table, rows, tol, scale)
    index = np.concatenate([i, j])
    t = np.concatenate([found.ta, found.tb])
    point = np.concatenate([found.point, found.point])
    open_chains = [c for c, is_closed in enumerate(closed) if not is_closed and sources[c]]
    if open_chains:
        ends = [(Point(*sources[c][0].start), Point(*sources[c][-1].end)) for c in open_chains]
        caps = _circles(ends, distance)
        cap_chain = np.repeat(np.asarray(open_chains), 4)
        ci, cj = overlapping(boxes(table), boxes(caps), 0.0)
        mine = rows.chain[ci] == cap_chain[cj]
        ci, cj = ci[mine], cj[mine]
        capped = hits(table.take(ci), caps.take(cj), tol)
        index = np.concatenate([index, ci[capped.pair]])
        t = np.concatenate([t, capped.ta])
        point = np.concatenate([point, capped.point])
    order = np.lexsort((t, index))
    size = element_lengths(table)
    out: list[list[Cut]] = [[] for _ in closed]
    chain_of = rows.chain.tolist()
    starts = first.tolist()
    for k, row, tk, (x, y) in zip(
        order.tolist(), index[order].tolist(), t[order].tolist(), point[order].tolist(),
        strict=True,
    ):  # fmt: skip
        del k
        c = chain_of[row]
        cut = Cut(row - starts[c], tk, Point(x, y))
        mine_cuts = out[c]
        if (
            mine_cuts
            and mine_cuts[-1].at == cut.at
            and (cut.t - mine_cuts[-1].t) * size[row] <= tol
        ):
            continue
        mine_cuts.append(cut)
    return out


def _circles(ends: list[tuple[Point, Point]], radius: float) -> Table:
    """The circles of ``radius`` about both ends of each chain, as two half-circle arcs each
    (four rows per chain)."""
    arcs = []
    for cx, cy in (p for pair in ends for p in pair):
        for a0 in (0.0, math.pi):
            start = Point(cx + radius * math.cos(a0), cy + radius * math.sin(a0))
            end = Point(cx + radius * math.cos(a0 + math.pi), cy + radius * math.sin(a0 + math.pi))
            arcs.append(CircularArc(start, end, Point(cx, cy), radius, a0, math.pi))
    return table_of(arcs)


def _slices(elements: list[Element], closed: bool, cuts: list[Cut]) -> list[Slice]:
    """The raw chain cut at ``cuts`` (sorted): between consecutive cuts (cyclically when
    closed; from the start and to the end when open)."""
    n = len(elements)
    if closed:
        if not cuts:
            return [Slice(list(elements), [(i, 0.0, 1.0) for i in range(n)])]
        bounds = [*cuts, cuts[0]]
    else:
        bounds = [
            Cut(0, 0.0, Point(*elements[0].start)),
            *cuts,
            Cut(n - 1, 1.0, Point(*elements[-1].end)),
        ]
    out = []
    for a, b in itertools.pairwise(bounds):
        built = _between(elements, a, b, closed and a is bounds[-2])
        if built is not None:
            out.append(built)
    return out


def _between(elements: list[Element], a: Cut, b: Cut, last: bool) -> Slice | None:
    """The slice from cut ``a`` to cut ``b`` (going round the end of a closed chain when
    ``b`` is not after ``a``)."""
    n = len(elements)
    if a.at == b.at and a.t < b.t and not (last and a.t >= b.t):
        span = [(a.at, a.t, b.t)]
    elif a.at == b.at and a.t == b.t and not last:
        return None
    else:
        stop = b.at if b.at > a.at or not last else b.at + n
        if b.at == a.at and last:
            stop = a.at + n
        span = [(a.at, a.t, 1.0)]
        span += [(k % n, 0.0, 1.0) for k in range(a.at + 1, stop)]
        span.append((b.at, 0.0, b.t))
    span = [s for s in span if s[2] > s[1]]
    if not span:
        return None
    pieces = []
    for k, (i, t0, t1) in enumerate(span):
        e = elements[i]
        start = a.point if k == 0 else Point(*e.start)
        end = b.point if k == len(span) - 1 else Point(*e.end)
        if t0 == 0.0 and t1 == 1.0 and start == e.start and end == e.end:
            pieces.append(e)
        else:
            pieces.append(piece(e, t0, t1, start, end))
    return Slice(pieces, span)
