"""The raw offset: every element moved to the side, and the corners between them joined
(docs/offsets.md §3).

A line moves by ``d`` along its normal; an arc keeps its centre and angles and its radius
becomes ``r ∓ d``; an arc whose radius would fall to ``≤ 0`` collapses and is replaced by
the chord between its two offset ends, which lies within ``d`` of the arc and so is removed
by the global step. At a corner, the two offset ends ``e`` (of the element before) and
``s`` (of the one after) lie ``d`` from the source corner ``P``: equal, they are shared;
apart on the outside of the corner (convex), an arc of radius ``d`` about ``P`` joins them
(or, between two lines with ``join="mitre"``, the lines are extended to meet within
``mitre_limit·d`` of ``P``); on the inside (concave), both are cut at their intersection, or
where they do not meet the arc about ``P`` connects them the short way and the global step
removes the loop. The intersections at concave corners of every chain are found in one
vectorised call.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import NamedTuple

from ..curves.segments import CircularArc, Line
from ..spline import Point
from .intersect import hits
from .shapes import movable, piece, polar
from .table import table_of
from .types import Element, OffsetOptions

#: A corner arc turning less than this is replaced by its chord: it strays at most
#: ``d·θ²/8`` (below 1e-15·d) from the arc.
CHORD_TURN_RAD = 1e-7
#: A line no longer than this many point tolerances is left out of the raw offset (its
#: direction, and so its normal, is lost in rounding); its neighbours' corner joins it.
SHORT_LINE = 1e3


class RawElement(NamedTuple):
    """One element of the raw offset chain: the element and the source element it offsets
    (``-1`` for a corner join)."""

    element: Element
    source: int


class RawChain(NamedTuple):
    """The raw offset chain, chained bit for bit, and the source elements that collapsed."""

    elements: list[RawElement]
    collapsed: list[int]


class _Joint(NamedTuple):
    """A corner between moved elements ``k`` and ``k + 1`` of a chain (``k + 1`` wraps to 0
    at a closed chain's closing corner): what joins them."""

    k: int
    kind: str  # "same", "snap_next", "snap_prev", "mitre", "round", "concave"
    point: Point | None  # the mitre point
    sweep: float


class _Moved(NamedTuple):
    elements: list[Element]
    source: list[int]
    collapsed: list[int]
    corners: list[Point]  # the source corner before each moved element
    joints: list[_Joint]


def raw_offsets(
    chains: Sequence[tuple[Sequence[Element], bool, float]], options: OffsetOptions, tol: float
) -> list[RawChain]:
    """The raw offset chain of each ``(elements, closed, sign)`` (``sign`` +1: to the left,
    -1: to the right) (module docstring); ``tol`` is the length below which two points are
    one."""
    moved = [_move(elements, closed, sign, options, tol) for elements, closed, sign in chains]
    # Every concave corner's two elements, intersected at once.
    firsts, seconds, owners = [], [], []
    for c, m in enumerate(moved):
        for j in m.joints:
            if j.kind == "concave":
                firsts.append(m.elements[j.k])
                seconds.append(m.elements[(j.k + 1) % len(m.elements)])
                owners.append((c, j.k))
    crossing: dict[tuple[int, int], list[tuple[float, float, Point]]] = {}
    if firsts:
        found = hits(table_of(firsts), table_of(seconds), tol)
        for p, ta, tb, (x, y) in zip(
            found.pair.tolist(), found.ta.tolist(), found.tb.tolist(), found.point.tolist(),
            strict=True,
        ):  # fmt: skip
            crossing.setdefault(owners[p], []).append((ta, tb, Point(x, y)))
    return [
        _assemble(m, closed, options.distance, c, crossing)
        for c, (m, (_, closed, _)) in enumerate(zip(moved, chains, strict=True))
    ]


def _move(
    elements: Sequence[Element], closed: bool, sign: float, options: OffsetOptions, tol: float
) -> _Moved:
    """The elements moved, and the kind of each corner between them; a line shorter than
    ``SHORT_LINE`` tolerances is left out (its neighbours are joined about the next one's
    start)."""
    out: list[Element] = []
    source: list[int] = []
    collapsed: list[int] = []
    corners: list[Point] = []
    for k, e in enumerate(elements):
        shifted, collapses = _shift(e, sign * options.distance, tol)
        if collapses:
            collapsed.append(k)
        for j, moved in enumerate(shifted):
            if moved.start != moved.end:
                out.append(moved)
                source.append(k)
                # the corner before it: the element's start; between a collapsing arc's two
                # arcs (which meet exactly), its end
                corners.append(Point(*e.start) if j == 0 else Point(*e.end))
    count = len(out) if closed and len(out) > 1 else len(out) - 1
    joints = [
        _classify(out[k], out[(k + 1) % len(out)], corners[(k + 1) % len(out)], k, sign,
                  options, tol)
        for k in range(max(count, 0))
    ]  # fmt: skip
    return _Moved(out, source, collapsed, corners, joints)


def _shift(e: Element, offset: float, tol: float) -> tuple[list[Element], bool]:
    """The element moved ``offset`` to its left (negative: right): a line or an arc, nothing
    for a line too short to have a direction, two arcs for a collapsing arc
    (:func:`_collapse`); and whether it collapsed."""
    if isinstance(e, Line):
        (x0, y0), (x1, y1) = e.start, e.end
        length = math.hypot(x1 - x0, y1 - y0)
        if length <= SHORT_LINE * tol:  # its normal would be rounding noise
            return [], False
        nx, ny = -(y1 - y0) / length * offset, (x1 - x0) / length * offset
        return [Line(Point(x0 + nx, y0 + ny), Point(x1 + nx, y1 + ny))], False
    # To the left of an anticlockwise arc is its centre.
    radius = e.radius - (offset if e.sweep_rad > 0.0 else -offset)
    (cx, cy), a0, a1 = e.center, e.start_angle_rad, e.start_angle_rad + e.sweep_rad
    start = Point(cx + radius * math.cos(a0), cy + radius * math.sin(a0))
    end = Point(cx + radius * math.cos(a1), cy + radius * math.sin(a1))
    if radius <= tol:
        return _collapse(e, start, end, abs(offset)), True
    return [CircularArc(start, end, Point(*e.center), radius, a0, e.sweep_rad)], False


def _collapse(e: CircularArc, start: Point, end: Point, d: float) -> list[Element]:
    """A collapsing arc's offset (docs/offsets.md §3): on the side of its centre, nearer
    than ``d`` to its radius, the points at ``d`` from the arc are those at ``d`` from its
    ends; so the arc about its start from ``start`` to where the circles of radius ``d``
    about both ends meet on that side, ``M``, then the arc about its end from ``M`` to
    ``end``."""
    p0, p1 = Point(*e.start), Point(*e.end)
    half = 0.5 * math.dist(p0, p1)
    mid = ((p0[0] + p1[0]) * 0.5, (p0[1] + p1[1]) * 0.5)
    # The side of the centre: the chord's normal towards it (the chord's left for an
    # anticlockwise arc of less than a half turn, and so on: take it from the centre).
    side = (mid[0] - e.center[0], mid[1] - e.center[1])
    along = (p1[0] - p0[0], p1[1] - p0[1])
    normal = (-along[1], along[0])
    if normal[0] * side[0] + normal[1] * side[1] > 0.0:  # normal points away from the centre
        normal = (along[1], -along[0])
    size = math.hypot(*normal)
    if size == 0.0:  # a point: the corner join about it does all
        return []
    h = math.sqrt(max(d * d - half * half, 0.0)) / size
    meet = Point(mid[0] + h * normal[0], mid[1] + h * normal[1])
    return [
        piece_
        for piece_ in (_about(p0, start, meet, d), _about(p1, meet, end, d))
        if piece_ is not None
    ]


def _about(centre: Point, a: Point, b: Point, d: float) -> Element | None:
    """The short arc of radius ``d`` about ``centre`` from ``a`` to ``b`` (a line for a
    negligible turn; nothing where they coincide)."""
    if a == b:
        return None
    v1 = (a[0] - centre[0], a[1] - centre[1])
    v2 = (b[0] - centre[0], b[1] - centre[1])
    turn = math.atan2(v1[0] * v2[1] - v1[1] * v2[0], v1[0] * v2[0] + v1[1] * v2[1])
    return _corner_arc(a, b, centre, turn, d)


def _classify(
    a: Element, b: Element, corner: Point, k: int, sign: float, options: OffsetOptions,
    tol: float,
) -> _Joint:  # fmt: skip
    """How the end of ``a`` and the start of ``b`` are joined about ``corner``."""
    e, s = a.end, b.start
    if e == s:
        return _Joint(k, "same", None, 0.0)
    gap = math.dist(e, s)
    if gap <= tol and movable(b, gap):
        return _Joint(k, "snap_next", None, 0.0)
    if gap <= tol and movable(a, gap):
        return _Joint(k, "snap_prev", None, 0.0)
    v1 = (e[0] - corner[0], e[1] - corner[1])
    v2 = (s[0] - corner[0], s[1] - corner[1])
    turn = math.atan2(v1[0] * v2[1] - v1[1] * v2[0], v1[0] * v2[0] + v1[1] * v2[1])
    if sign * turn < 0.0 or abs(turn) >= math.pi * (1.0 - 1e-12):  # convex (or a cusp)
        mitre = _mitre(a, b, corner, options) if options.join == "mitre" else None
        if mitre is not None:
            return _Joint(k, "mitre", mitre, 0.0)
        return _Joint(k, "round", None, -sign * abs(turn))
    return _Joint(k, "concave", None, turn)


def _assemble(
    m: _Moved,
    closed: bool,
    radius: float,
    chain: int,
    crossing: dict[tuple[int, int], list[tuple[float, float, Point]]],
) -> RawChain:
    """The moved elements, cut or extended at their corners, with the corner arcs between."""
    n = len(m.elements)
    t0, t1 = [0.0] * n, [1.0] * n
    starts = [Point(*e.start) for e in m.elements]
    ends = [Point(*e.end) for e in m.elements]
    between: dict[int, Element] = {}
    for j in m.joints:
        k, nxt = j.k, (j.k + 1) % n
        if j.kind == "snap_next":
            starts[nxt] = ends[k]
        elif j.kind == "snap_prev":
            ends[k] = starts[nxt]
        elif j.kind == "mitre" and j.point is not None:
            ends[k] = starts[nxt] = j.point
        elif j.kind == "round":
            between[k] = _corner_arc(ends[k], starts[nxt], m.corners[nxt], j.sweep, radius)
        elif j.kind == "concave":
            cut = _nearest(crossing.get((chain, k), []), m.corners[nxt], t0[k], t1[nxt])
            if cut is None:
                between[k] = _corner_arc(ends[k], starts[nxt], m.corners[nxt], j.sweep, radius)
            else:
                t1[k], t0[nxt] = cut[0], cut[1]
                ends[k] = starts[nxt] = cut[2]
    out: list[RawElement] = []
    for k, e in enumerate(m.elements):
        out.append(RawElement(piece(e, t0[k], t1[k], starts[k], ends[k]), m.source[k]))
        if k in between:
            out.append(RawElement(between[k], -1))
    return RawChain(out, m.collapsed)


def _nearest(
    found: list[tuple[float, float, Point]], corner: Point, after: float, before: float
) -> tuple[float, float, Point] | None:
    """The crossing nearest the corner that leaves something of both elements: after the
    first element's kept start ``after`` and before the second's kept end ``before``."""
    usable = [f for f in found if f[0] > after and f[1] < before and f[0] > 0.0]
    if not usable:
        return None
    return min(usable, key=lambda f: math.dist(f[2], corner))


def _corner_arc(e: Point, s: Point, corner: Point, sweep: float, radius: float) -> Element:
    """The arc of ``radius`` about ``corner`` from ``e`` to ``s`` turning ``sweep`` (its
    chord when the turn is negligible)."""
    if abs(sweep) < CHORD_TURN_RAD:
        return Line(e, s)
    return CircularArc(e, s, corner, radius, polar(corner, e), sweep)


def _mitre(a: Element, b: Element, corner: Point, options: OffsetOptions) -> Point | None:
    """Where two offset lines extended meet, if within ``mitre_limit·d`` of the corner
    (docs/offsets.md §3: arcs are joined round, as an arc's tangent is not its offset)."""
    if not (isinstance(a, Line) and isinstance(b, Line)):
        return None
    (ax, ay), (ex, ey) = a.start, a.end
    (sx, sy), (bx, by) = b.start, b.end
    u, v = (ex - ax, ey - ay), (bx - sx, by - sy)
    den = u[0] * v[1] - u[1] * v[0]
    if den == 0.0:
        return None
    # e + t·u = s + τ·v (t ≥ 0 ahead of a's end, τ ≤ 0 behind b's start)
    wx, wy = sx - ex, sy - ey
    t = (wx * v[1] - wy * v[0]) / den
    tau = (wx * u[1] - wy * u[0]) / den
    if t < 0.0 or tau > 0.0:
        return None
    point = Point(ex + t * u[0], ey + t * u[1])
    if math.dist(point, corner) > options.mitre_limit * options.distance:
        return None
    return point
