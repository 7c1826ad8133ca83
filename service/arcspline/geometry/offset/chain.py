"""Chains of lines and arcs: from a fitted spline, their area and where they cross
themselves (docs/offsets.md §2)."""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import NamedTuple

import numpy as np

from ..curves.segments import CircularArc, Line
from ..path_spline import IntArray
from ..spline import COLUMN, ArcSpline, BoolArray, Point
from .broad import overlapping
from .distance import MEET_RTOL
from .intersect import Hits, hits
from .shapes import piece
from .table import Table, boxes, coordinate_scale, element_lengths, table_of
from .types import Element

#: Two neighbours meeting within this fraction of their lengths of their shared joint meet
#: *at* it: at a near-tangent joint of a fitted chain (tiny arcs, or nearly flat ones whose
#: circles nearly coincide) the second intersection is lost in rounding.
JOINT_FRACTION = 1e-5
#: ... or within this fraction of the coordinate scale.
JOINT_RTOL = 1e-9


def elements_of(spline: ArcSpline) -> tuple[Element, ...]:
    """The rows of a fitted spline as :class:`Line` and :class:`CircularArc` values, chained
    bit for bit as the rows are (docs/offsets.md §2)."""
    c = COLUMN
    out: list[Element] = []
    for row in spline.values():
        start = Point(row[c["start_x"]], row[c["start_y"]])
        end = Point(row[c["end_x"]], row[c["end_y"]])
        if row[c["is_arc"]]:
            centre = Point(row[c["center_x"]], row[c["center_y"]])
            out.append(
                CircularArc(
                    start, end, centre, row[c["radius"]], row[c["start_angle_rad"]],
                    row[c["sweep_rad"]],
                )
            )  # fmt: skip
        else:
            out.append(Line(start, end))
    return tuple(out)


def signed_area(elements: Sequence[Element]) -> float:
    """The area a closed chain encloses, > 0 when it runs anticlockwise (docs/offsets.md §2):
    the shoelace sum over the chords plus each arc's circular segment
    ``r²/2·(θ − sin θ)`` (signed with its sweep ``θ``)."""
    total = 0.0
    for e in elements:
        (x0, y0), (x1, y1) = e.start, e.end
        total += 0.5 * (x0 * y1 - x1 * y0)
        if isinstance(e, CircularArc):
            total += 0.5 * e.radius**2 * (e.sweep_rad - math.sin(e.sweep_rad))
    return total


class Rows(NamedTuple):
    """Where each row of a table of several chains belongs: its chain, its index in the
    chain, the chain's length and whether the chain is closed."""

    chain: IntArray
    local: IntArray
    size: IntArray
    closed: BoolArray

    @classmethod
    def of(cls, sizes: Sequence[int], closed: Sequence[bool]) -> Rows:
        count = np.asarray(sizes, dtype=np.int64)
        chain = np.repeat(np.arange(len(count)), count)
        local = np.arange(len(chain)) - np.repeat(np.cumsum(count) - count, count)
        return cls(chain, local, count[chain], np.asarray(closed, dtype=bool)[chain])


def self_hits(
    table: Table, rows: Rows, tol: float, scale: float
) -> tuple[Hits, IntArray, IntArray]:
    """Where each chain meets itself: the hits and, per hit, its two rows ``i < j`` (of one
    chain); neighbours meeting at (or within rounding of) their shared joint do not count
    (docs/offsets.md §5). ``scale``: the coordinate scale."""
    i, j = overlapping(boxes(table), None, 0.0)
    same = rows.chain[i] == rows.chain[j]
    i, j = i[same], j[same]
    found = hits(table.take(i), table.take(j), tol)
    hi, hj = i[found.pair], j[found.pair]
    li, lj, size, closed = rows.local[hi], rows.local[hj], rows.size[hi], rows.closed[hi]
    # i < j: i's end is j's start for j = i + 1; closed, the last one's end is the first's start
    next_one = lj == li + 1
    wrap = closed & (li == 0) & (lj == size - 1)
    lengths = element_lengths(table)
    near = np.maximum(JOINT_FRACTION * (lengths[hi] + lengths[hj]), JOINT_RTOL * scale)
    to_end = np.hypot(*(found.point - table.end[hi]).T)  # i's end: j's start when next
    to_start = np.hypot(*(found.point - table.start[hi]).T)  # i's start: j's end on wrapping
    at_joint = (next_one & (to_end <= near)) | (wrap & (to_start <= near))
    keep = ~at_joint
    kept = Hits(found.pair[keep], found.point[keep], found.ta[keep], found.tb[keep])
    return kept, hi[keep], hj[keep]


def crossings(
    elements: Sequence[Element], closed: bool, *, min_loop: float = 0.0
) -> tuple[Point, ...]:
    """Where the chain crosses or touches itself away from the joints of neighbours
    (docs/offsets.md §2), in chain order of the first element met. With ``min_loop`` > 0, a
    crossing that cuts off a loop shorter than ``min_loop`` (a loop that small lies within
    ``min_loop / 2`` of one point: a drawing's rounding, not a figure eight) does not count."""
    if len(elements) < 2:
        return ()
    table = table_of(elements)
    scale = coordinate_scale(table)
    found, hi, hj = self_hits(table, Rows.of([len(elements)], [closed]), MEET_RTOL * scale, scale)
    if min_loop > 0.0 and len(hi):
        lengths = element_lengths(table)
        before = np.concatenate([[0.0], np.cumsum(lengths)])
        at_i = before[hi] + found.ta * lengths[hi]
        at_j = before[hj] + found.tb * lengths[hj]
        inner = np.abs(at_j - at_i)
        loop = np.minimum(inner, before[-1] - inner) if closed else inner
        keep = loop >= min_loop
        found = Hits(found.pair[keep], found.point[keep], found.ta[keep], found.tb[keep])
        hi = hi[keep]
    order = np.lexsort((found.ta, hi))
    return tuple(Point(float(x), float(y)) for x, y in found.point[order])


class Excised(NamedTuple):
    """A chain with its tiny loops cut out, and the longest loop removed."""

    elements: tuple[Element, ...]
    longest_loop: float


#: At most this many tiny loops are cut out of one chain (each pass finds them afresh).
_MAX_EXCISED = 64


def excise_loops(elements: Sequence[Element], closed: bool, min_loop: float) -> Excised:
    """The chain with every loop shorter than ``min_loop`` cut out where it crosses itself
    (docs/offsets.md §2): a drawing's rounding (an outline closed over itself by a hair)
    that the offset would otherwise have to follow. The chain moves by at most half the
    longest loop removed."""
    chain = list(elements)
    longest = 0.0
    for _ in range(_MAX_EXCISED):
        if len(chain) < 2 or min_loop <= 0.0:
            break
        table = table_of(chain)
        scale = coordinate_scale(table)
        found, hi, hj = self_hits(table, Rows.of([len(chain)], [closed]), MEET_RTOL * scale, scale)
        if not len(hi):
            break
        lengths = element_lengths(table)
        before = np.concatenate([[0.0], np.cumsum(lengths)])
        inner = np.abs(before[hj] + found.tb * lengths[hj] - before[hi] - found.ta * lengths[hi])
        outer = before[-1] - inner if closed else np.full(len(inner), np.inf)
        loop = np.minimum(inner, outer)
        k = int(np.argmin(loop))
        if loop[k] >= min_loop:
            break
        longest = max(longest, float(loop[k]))
        i, j = int(hi[k]), int(hj[k])
        ta, tb = float(found.ta[k]), float(found.tb[k])
        at = Point(float(found.point[k, 0]), float(found.point[k, 1]))
        if inner[k] <= outer[k]:  # keep what comes before i's crossing and after j's
            chain = [*chain[:i], *_part(chain[i], 0.0, ta, None, at),
                     *_part(chain[j], tb, 1.0, at, None), *chain[j + 1 :]]  # fmt: skip
        else:  # the loop is the way round past the chain's closing point
            chain = [*_part(chain[i], ta, 1.0, at, None), *chain[i + 1 : j],
                     *_part(chain[j], 0.0, tb, None, at)]  # fmt: skip
    return Excised(tuple(chain), longest)


def _part(
    e: Element, t0: float, t1: float, start: Point | None, end: Point | None
) -> list[Element]:
    """``e`` from ``t0`` to ``t1`` (from ``start``/to ``end`` where given, else its own
    ends); nothing if that is a point."""
    first = Point(*e.start) if start is None else start
    last = Point(*e.end) if end is None else end
    if t1 <= t0 or first == last:
        return []
    if t0 == 0.0 and t1 == 1.0 and first == e.start and last == e.end:
        return [e]
    return [piece(e, t0, t1, first, last)]


def meets_itself(chains: Sequence[tuple[Sequence[Element], bool]]) -> list[bool]:
    """Whether each ``(elements, closed)`` chain meets itself anywhere but at its joints
    (:func:`crossings`), for many chains in one vectorised pass."""
    sizes = [len(elements) for elements, _ in chains]
    table = table_of([e for elements, _ in chains for e in elements])
    if not len(table):
        return [False] * len(chains)
    scale = coordinate_scale(table)
    rows = Rows.of(sizes, [closed for _, closed in chains])
    _, hi, _ = self_hits(table, rows, MEET_RTOL * scale, scale)
    hit = np.zeros(len(chains), dtype=bool)
    hit[rows.chain[hi]] = True
    return [bool(h) for h in hit]
