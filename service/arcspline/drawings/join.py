"""Joining a drawing's elements into toolpaths: open subpaths whose ends meet within a join
tolerance become one subpath, reversed where needed; a chain whose ends meet is closed
(docs/drawings.md §5).

Ends are matched greedily: every pair of free ends (of different elements, or the two ends of
one chain) closer than the tolerance is a candidate, found through a grid of cells one
tolerance wide; the candidates are taken shortest first (ties by the ends' input order), each
end at most once. Where three or more ends meet at one point (a branch), the two closest (then
the first in input order) join and the others stay ends of their own toolpaths. The result
depends only on the input, and takes ``O(n log n)`` time for ``n`` elements.

Segments of one subpath must chain bit for bit, so each join closes its gap: it moves the end
point of a line or Bézier curve (which moves that curve by at most the gap), or of an arc where
the moved point still lies on the arc within ``ARC_RTOL``; between two arcs that cannot take it
a short line bridges the gap.
"""

from __future__ import annotations

import math
from collections import defaultdict
from collections.abc import Sequence
from typing import NamedTuple

import numpy as np
import numpy.typing as npt

from arcspline.geometry.curves.segments import (
    CircularArc,
    Cubic,
    EllipticalArc,
    Line,
    Quadratic,
    Segment,
    Subpath,
)
from arcspline.geometry.segment_table import ARC_RTOL
from arcspline.geometry.spline import FloatArray, Point

from .model import Element

#: At most this many ends of one grid cell are candidates for an end's partner (the first in
#: input order): it bounds the work where thousands of ends crowd one tolerance-sized cell
#: without coinciding exactly (ends that coincide exactly are paired before the grid is used).
MAX_CANDIDATES_PER_CELL = 8
#: An arc end point moved by a join must stay this much closer to the arc than ``ARC_RTOL``
#: allows, leaving room for the rounding of the check that recomputes it.
ARC_SNAP_MARGIN = 0.5


IntArray = npt.NDArray[np.int64]


class Toolpath(NamedTuple):
    """One subpath to cut (``subpath.closed`` when it returns to its start) and the elements it
    was joined from, in cutting order."""

    subpath: Subpath
    sources: tuple[str, ...]


class Joined(NamedTuple):
    """The toolpaths, in the order of their first element in the input; the largest gap a join
    closed (0 when every join met exactly or there was none), the number of joins made (a
    chain closing on itself counts one) and of lines added to bridge arc-to-arc gaps."""

    toolpaths: tuple[Toolpath, ...]
    largest_gap: float
    joins: int
    bridges: int


class JoinError(ValueError):
    """The join tolerance is not a finite number ≥ 0."""


def reversed_segment(segment: Segment) -> Segment:
    """The same curve traversed the other way: points in reverse order; an arc from its end,
    starting at ``start_angle + sweep`` and turning ``-sweep``."""
    if isinstance(segment, Line):
        return Line(segment.end, segment.start)
    if isinstance(segment, Quadratic):
        return Quadratic(segment.end, segment.control, segment.start)
    if isinstance(segment, Cubic):
        return Cubic(segment.end, segment.control2, segment.control1, segment.start)
    if isinstance(segment, CircularArc):
        return segment._replace(
            start=segment.end,
            end=segment.start,
            start_angle_rad=segment.start_angle_rad + segment.sweep_rad,
            sweep_rad=-segment.sweep_rad,
        )
    return segment._replace(
        start=segment.end,
        end=segment.start,
        start_angle_rad=segment.start_angle_rad + segment.sweep_rad,
        sweep_rad=-segment.sweep_rad,
    )


def reversed_subpath(subpath: Subpath) -> Subpath:
    """The subpath traversed the other way (still closed if it was)."""
    return Subpath(tuple(reversed_segment(s) for s in reversed(subpath.segments)), subpath.closed)


def join(elements: Sequence[Element], join_tolerance: float) -> Joined:
    """The elements as toolpaths: open subpaths with ends within ``join_tolerance`` joined
    end to end (see the module's docstring); closed subpaths as they are."""
    tol = float(join_tolerance)
    if not (math.isfinite(tol) and tol >= 0.0):
        raise JoinError(f"join tolerance must be a finite number >= 0, got {join_tolerance!r}")
    open_ids = [k for k, e in enumerate(elements) if not e.subpath.closed and e.subpath.segments]
    ends = [p for k in open_ids for p in _ends(elements[k].subpath)]
    partner = _match(ends, tol, _closable(elements, open_ids))
    # Each toolpath goes where its first element in input order was.
    slots: list[Toolpath | None] = [
        Toolpath(e.subpath, (e.source,)) if e.subpath.closed or not e.subpath.segments else None
        for e in elements
    ]
    largest, joins, bridges = 0.0, 0, 0
    for chain, closed in _chains(partner, len(open_ids)):
        first = open_ids[min(i for i, _ in chain)]
        if len(chain) == 1 and not closed:
            slots[first] = Toolpath(elements[first].subpath, (elements[first].source,))
            continue
        pieces = [(elements[open_ids[i]], forward) for i, forward in chain]
        slots[first], gap, made = _joined(pieces, closed)
        largest = max(largest, gap)
        joins += len(chain) - 1 + closed
        bridges += made
    return Joined(tuple(t for t in slots if t is not None), largest, joins, bridges)


def _ends(subpath: Subpath) -> tuple[Point, Point]:
    return subpath.segments[0].start, subpath.segments[-1].end


def _closable(elements: Sequence[Element], open_ids: list[int]) -> list[bool]:
    """Whether a piece may close on itself: not a single line (whose ends within the tolerance
    make it a speck, not a contour)."""
    segs = [elements[k].subpath.segments for k in open_ids]
    return [not (len(s) == 1 and isinstance(s[0], Line)) for s in segs]


def _match(ends: list[Point], tol: float, closable: list[bool]) -> list[int]:
    """Each end's partner end (``-1`` for none): end ``2i`` is piece ``i``'s start, ``2i + 1``
    its end. Ends that coincide exactly pair first, in input order; the rest pair greedily,
    nearest first (ties by the ends' order)."""
    partner = [-1] * len(ends)
    same: defaultdict[Point, list[int]] = defaultdict(list)
    for e, p in enumerate(ends):
        same[p].append(e)
    for group in same.values():
        waiting = -1
        for e in group:
            if waiting < 0:
                waiting = e
            elif waiting // 2 != e // 2 or closable[e // 2]:
                partner[waiting], partner[e] = e, waiting
                waiting = -1
            # else: a single line's own two ends, coinciding: a speck, left open.
    free = np.array([e for e in range(len(ends)) if partner[e] < 0], dtype=np.int64)
    if tol == 0.0 or len(free) < 2:
        return partner
    xy = np.array([ends[e] for e in free.tolist()], dtype=np.float64)
    near = _near_pairs(xy, tol)
    a, b = free[near[:, 0]], free[near[:, 1]]
    allowed = (a // 2 != b // 2) | np.array(closable, dtype=np.bool_)[a // 2]
    a, b, near = a[allowed], b[allowed], near[allowed]
    gap = np.hypot(*(xy[near[:, 0]] - xy[near[:, 1]]).T)
    for e, f in zip(*(v[np.lexsort((b, a, gap))].tolist() for v in (a, b)), strict=True):
        if partner[e] < 0 and partner[f] < 0:
            partner[e], partner[f] = f, e
    return partner


def _near_pairs(xy: FloatArray, tol: float) -> IntArray:
    """The pairs ``(i, j)``, ``i < j``, of points within ``tol`` of each other, found through
    square cells at least ``tol`` wide (each point against the first
    :data:`MAX_CANDIDATES_PER_CELL` of its own and the eight neighbouring cells)."""
    m = len(xy)
    # Cells wide enough that their indices stay exact integers below 2^50.
    cell = max(tol, float(np.abs(xy).max()) * 2.0**-50)
    c = np.floor(xy / cell).astype(np.int64)
    ux, rx = np.unique(c[:, 0], return_inverse=True)
    uy, ry = np.unique(c[:, 1], return_inverse=True)
    width = len(uy)
    key = rx.reshape(-1) * width + ry.reshape(-1)
    by_cell = np.lexsort((np.arange(m), key))
    sorted_key = key[by_cell]
    found = []
    for dx in (-1, 0, 1):
        ix, okx = _rank(ux, c[:, 0] + dx)
        for dy in (-1, 0, 1):
            iy, oky = _rank(uy, c[:, 1] + dy)
            neighbour = ix * width + iy
            lo = np.searchsorted(sorted_key, neighbour, "left")
            hi = np.searchsorted(sorted_key, neighbour, "right")
            count = np.where(okx & oky, np.minimum(hi - lo, MAX_CANDIDATES_PER_CELL), 0)
            src = np.repeat(np.arange(m), count)
            first = np.repeat(lo - (np.cumsum(count) - count), count)
            dst = by_cell[first + np.arange(len(src))]
            close = np.hypot(*(xy[src] - xy[dst]).T) <= tol
            found.append(np.stack([src[close], dst[close]], axis=1))
    pairs = np.concatenate(found)
    pairs = np.sort(pairs[pairs[:, 0] != pairs[:, 1]], axis=1)
    return np.unique(pairs, axis=0).astype(np.int64)


def _rank(values: IntArray, wanted: IntArray) -> tuple[IntArray, npt.NDArray[np.bool_]]:
    """The position of each ``wanted`` in the sorted ``values``, and whether it is there."""
    at = np.minimum(np.searchsorted(values, wanted), len(values) - 1)
    return at, values[at] == wanted


def _chains(partner: list[int], pieces: int) -> list[tuple[list[tuple[int, bool]], bool]]:
    """The chains of pieces the partners link: each a list of ``(piece, forward)`` in cutting
    order, oriented so that its first piece in input order runs forward (and, for a closed
    chain, starting there), and whether it closes."""
    seen = [False] * pieces
    chains = []
    for first in range(pieces):
        if seen[first]:
            continue
        if partner[2 * first] < 0 and partner[2 * first + 1] < 0:
            chains.append(([(first, True)], False))
            continue
        back, closed = _walk(partner, first, forward=False)
        if closed:
            chain = _walk(partner, first, forward=True)[0]
        else:
            head = [(i, not forward) for i, forward in reversed(back)]
            chain = head[:-1] + _walk(partner, first, forward=True)[0]
        for i, _ in chain:
            seen[i] = True
        chains.append((chain, closed))
    return chains


def _walk(partner: list[int], first: int, forward: bool) -> tuple[list[tuple[int, bool]], bool]:
    """The pieces from ``first`` (run ``forward`` or not) on through the partners of each
    exit end, until a free end or back at ``first`` (then closed)."""
    chain = [(first, forward)]
    piece = first
    while True:
        exit_end = 2 * piece + (1 if forward else 0)
        mate = partner[exit_end]
        if mate < 0:
            return chain, False
        piece, forward = mate // 2, mate % 2 == 0
        if piece == first:
            return chain, True
        chain.append((piece, forward))


def _joined(pieces: list[tuple[Element, bool]], closed: bool) -> tuple[Toolpath, float, int]:
    """One toolpath of the pieces in order (each reversed unless ``forward``), every gap
    closed; with the largest gap and the number of bridging lines."""
    segments: list[Segment] = []
    largest, bridges = 0.0, 0
    junctions = []
    for element, forward in pieces:
        sub = element.subpath if forward else reversed_subpath(element.subpath)
        if segments:
            junctions.append(len(segments))
        segments.extend(sub.segments)
    if closed:
        junctions.append(0)
    # Bridges are inserted after all junctions are fixed, from the last back, so that the
    # recorded positions stay valid.
    inserts: list[tuple[int, Line]] = []
    for j in junctions:
        before, after = (j - 1) % len(segments), j
        gap = math.dist(segments[before].end, segments[after].start)
        largest = max(largest, gap)
        if segments[before].end == segments[after].start:
            continue
        bridge = _close_gap(segments, before, after)
        if bridge is not None:
            inserts.append((j if j else len(segments), bridge))
    for position, bridge in sorted(inserts, reverse=True, key=lambda t: t[0]):
        segments.insert(position, bridge)
        bridges += 1
    sources = tuple(element.source for element, _ in pieces)
    return Toolpath(Subpath(tuple(segments), closed), sources), largest, bridges


def _close_gap(segments: list[Segment], before: int, after: int) -> Line | None:
    """Make ``segments[before]`` end where ``segments[after]`` starts: move the start of the
    one after (a line or Bézier, or an arc that stays consistent), else the end of the one
    before; between arcs that cannot move, a bridging line (returned, for the caller to
    insert)."""
    meet = segments[before].end
    moved = _moved_start(segments[after], meet)
    if moved is not None:
        segments[after] = moved
        return None
    meet = segments[after].start
    moved = _moved_end(segments[before], meet)
    if moved is not None:
        segments[before] = moved
        return None
    return Line(segments[before].end, segments[after].start)


def _moved_start(segment: Segment, point: Point) -> Segment | None:
    if isinstance(segment, Line | Quadratic | Cubic) or _on_arc(segment, point, at_end=False):
        return segment._replace(start=point)
    return None


def _moved_end(segment: Segment, point: Point) -> Segment | None:
    if isinstance(segment, Line | Quadratic | Cubic) or _on_arc(segment, point, at_end=True):
        return segment._replace(end=point)
    return None


def _on_arc(arc: CircularArc | EllipticalArc, point: Point, at_end: bool) -> bool:
    """Whether ``point`` lies where the arc's centre, radii and angle put its start (or end)
    within ``ARC_SNAP_MARGIN · ARC_RTOL`` of its coordinate scale (the consistency
    ``segment_table.check`` requires of arcs)."""
    if isinstance(arc, CircularArc):
        rx = ry = arc.radius
        rotation = 0.0
    else:
        rx, ry, rotation = arc.rx, arc.ry, arc.rotation_rad
    angle = arc.start_angle_rad + (arc.sweep_rad if at_end else 0.0)
    ex, ey = rx * math.cos(angle), ry * math.sin(angle)
    px = arc.center[0] + math.cos(rotation) * ex - math.sin(rotation) * ey
    py = arc.center[1] + math.sin(rotation) * ex + math.cos(rotation) * ey
    reach = max(rx, ry)
    scale = max(
        *(abs(c) for c in (*arc.start, *arc.end, *point)),
        abs(arc.center[0]) + reach,
        abs(arc.center[1]) + reach,
    )
    return math.hypot(px - point[0], py - point[1]) <= ARC_SNAP_MARGIN * ARC_RTOL * scale
