"""Lead arcs and where a closed contour's cut starts (docs/machining.md §5).

A lead-in is a quarter circle of radius ``R`` on the waste side (the tool's side of its
travel), ending tangent to the tool path at its start; a lead-out leaves the path's end the
same way. For the tool on the left, the lead-in's centre is ``C = P + R·n`` (``n`` the left
normal of the travel direction ``t`` at ``P``) and it turns anticlockwise by π/2 into ``P``:
at ``C − R·n`` an anticlockwise circle moves along ``rot90(−n) = t``. On the right, ``n`` is
the right normal and the arcs turn clockwise.

A closed contour starts at the midpoint of one of its elements (a smooth point, never a
corner): the longest straight first, then the longest arcs. The leads must keep the tool at
least its radius from every contour of the drawing, measured exactly
(``geometry.offset``'s distances); the first candidate whose leads do is taken, at the
wanted radius, else at half of it, and so on down to :data:`MIN_LEAD_FRACTION` of it; failing
that, the contour is cut without leads (and the caller warns). The leads' free ends must
moreover keep ``r + R/2`` from every contour: the tool enters and leaves in the waste, away
from the finished wall.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import NamedTuple

import numpy as np

from arcspline.geometry import CircularArc, Line, Point
from arcspline.geometry.offset.broad import overlapping
from arcspline.geometry.offset.distance import MEET_RTOL, pair_distances, point_distances
from arcspline.geometry.offset.table import boxes, coordinate_scale, table_of

from .chains import Chain, Element, length, point_at, rotated, split, tangent_at

#: The smallest lead radius tried, as a fraction of the one wanted (four halvings).
MIN_LEAD_FRACTION = 1.0 / 16.0
#: A lead's free end keeps the tool radius plus this fraction of the lead radius from every
#: contour (beside a straight it keeps the whole lead radius more).
FREE_END_FRACTION = 0.5
#: Start points tried per contour, best first.
MAX_CANDIDATES = 12
#: Clearance is met to within this fraction of the coordinates: where a lead joins the tool
#: path, its distance to the contour *is* the tool radius, up to the rounding of the offset.
CLEARANCE_RTOL = 1e-9


def waste_normal(direction: tuple[float, float], left: bool) -> tuple[float, float]:
    """The unit normal of ``direction`` towards the tool's (the waste) side."""
    tx, ty = direction
    return (-ty, tx) if left else (ty, -tx)


def lead_in(point: Point, direction: tuple[float, float], left: bool, radius: float) -> CircularArc:
    """The quarter circle on the waste side that ends at ``point`` moving along
    ``direction`` (its end is ``point`` itself, bit for bit)."""
    nx, ny = waste_normal(direction, left)
    centre = Point(point[0] + radius * nx, point[1] + radius * ny)
    sweep = 0.5 * math.pi if left else -0.5 * math.pi
    angle = math.atan2(point[1] - centre.y, point[0] - centre.x) - sweep
    start = Point(centre.x + radius * math.cos(angle), centre.y + radius * math.sin(angle))
    return CircularArc(start, Point(*point), centre, radius, angle, sweep)


def lead_out(
    point: Point, direction: tuple[float, float], left: bool, radius: float
) -> CircularArc:
    """The quarter circle on the waste side that leaves ``point`` along ``direction``."""
    nx, ny = waste_normal(direction, left)
    centre = Point(point[0] + radius * nx, point[1] + radius * ny)
    sweep = 0.5 * math.pi if left else -0.5 * math.pi
    angle = math.atan2(point[1] - centre.y, point[0] - centre.x)
    end = Point(
        centre.x + radius * math.cos(angle + sweep), centre.y + radius * math.sin(angle + sweep)
    )
    return CircularArc(Point(*point), end, centre, radius, angle, sweep)


class Probe(NamedTuple):
    """Moves and points to check: every move must keep ``move_distance`` from the contours,
    every point ``point_distance``."""

    moves: Sequence[Element]
    move_distance: float
    points: Sequence[Point]
    point_distance: float


class Obstacles:
    """Every contour of the drawing, for exact clearance checks of moves near them: the
    pairs that boxes cannot rule out (``geometry.offset``'s broad phase) are measured at
    once, by its exact distances (docs/offsets.md §3)."""

    def __init__(self, contours: Sequence[Sequence[Element]]) -> None:
        elements = [e for chain in contours for e in chain]
        self.table = table_of(elements)
        self.boxes = boxes(self.table) if elements else np.zeros((0, 4))
        self.scale = float(np.abs(self.boxes).max()) if len(self.boxes) else 1.0

    def clear(self, probes: Sequence[Probe]) -> list[bool]:
        """For each probe, whether its moves and points keep their distances from every
        contour (to within :data:`CLEARANCE_RTOL`)."""
        ok = np.ones(len(probes), dtype=np.bool_)
        slack = (
            CLEARANCE_RTOL
            * max(self.scale, *(max(p.move_distance, p.point_distance) for p in probes), 0.0)
            if probes
            else 0.0
        )
        moves = [m for p in probes for m in p.moves]
        if moves and len(self.boxes):
            owner = np.repeat(np.arange(len(probes)), [len(p.moves) for p in probes])
            floor = np.repeat([p.move_distance for p in probes], [len(p.moves) for p in probes])
            table = table_of(moves)
            i, j = overlapping(boxes(table), self.boxes, float(floor.max()))
            tol = MEET_RTOL * max(self.scale, coordinate_scale(table))
            gaps = pair_distances(table.take(i), self.table.take(j), tol)
            ok[owner[i[gaps < floor[i] - slack]]] = False
        points = [q for p in probes for q in p.points]
        if points and len(self.boxes):
            owner = np.repeat(np.arange(len(probes)), [len(p.points) for p in probes])
            floor = np.repeat([p.point_distance for p in probes], [len(p.points) for p in probes])
            xy = np.array(points, dtype=np.float64).reshape(-1, 2)
            i, j = overlapping(np.hstack([xy, xy]), self.boxes, float(floor.max()))
            gaps = point_distances(xy[i], self.table.take(j))
            ok[owner[i[gaps < floor[i] - slack]]] = False
        return [bool(v) for v in ok]


class Start(NamedTuple):
    """A closed loop begun at a chosen point, and its leads (``None``: none fit)."""

    loop: Chain
    lead_in: CircularArc | None
    lead_out: CircularArc | None


def candidates(loop: Sequence[Element]) -> list[int]:
    """The elements whose midpoints are tried as start points, best first: straights, then
    arcs, each longest first."""
    ranked = sorted(
        range(len(loop)),
        key=lambda i: (not isinstance(loop[i], Line), -length(loop[i]), i),
    )
    return ranked[:MAX_CANDIDATES]


def begun_at(loop: Sequence[Element], index: int) -> Chain:
    """The closed loop begun at the midpoint of its element ``index``."""
    head, tail = split(loop[index], 0.5)
    rest = rotated(loop, index)[1:]
    return (tail, *rest, head)


def choose_starts(
    loops: Sequence[Sequence[Element]],
    left: bool,
    radius: float,
    tool_radius: float,
    obstacles: Obstacles,
    inset: float = 0.0,
) -> list[tuple[Start, float]]:
    """Each loop begun where leads of the largest radius tried fit, and that radius (0 when
    none fit: the loop is then begun at its best candidate, without leads). The tries run in
    rounds, one batched clearance check for every loop still looking.

    ``inset`` > 0 is for a loop that the controller offsets (cutter compensation): the leads
    returned are of radius ``R + inset`` about the same centres, and the ones checked are the
    tool centre's, of radius ``R``, at ``inset`` from the loop on the waste side."""
    radii = []
    r = radius
    while radius > 0.0 and r >= radius * MIN_LEAD_FRACTION:
        radii.append(r)
        r *= 0.5
    ranked = [candidates(loop) for loop in loops]
    tries = [[(index, r) for r in radii for index in ranks] for ranks in ranked]
    found: list[tuple[Start, float] | None] = [None] * len(loops)
    looking = list(range(len(loops)))
    step = 0
    while looking:
        now = [k for k in looking if step < len(tries[k])]
        verdict = obstacles.clear(
            [_probe(loops[k], *tries[k][step], left, tool_radius, inset) for k in now]
        )
        for k, fits_here in zip(now, verdict, strict=True):
            if fits_here:
                found[k] = _begun(loops[k], *tries[k][step], left, inset)
        looking = [k for k in now if found[k] is None]
        step += 1
    return [
        f if f is not None else (Start(begun_at(loops[k], ranked[k][0]), None, None), 0.0)
        for k, f in enumerate(found)
    ]


def _begun(
    loop: Sequence[Element], index: int, radius: float, left: bool, inset: float
) -> tuple[Start, float]:
    chain = begun_at(loop, index)
    start, direction = chain[0].start, tangent_at(loop[index], 0.5)
    return Start(
        chain,
        lead_in(start, direction, left, radius + inset),
        lead_out(start, direction, left, radius + inset),
    ), radius


def _probe(
    loop: Sequence[Element],
    index: int,
    radius: float,
    left: bool,
    tool_radius: float,
    inset: float,
) -> Probe:
    """The tool centre's leads at the midpoint of element ``index``, and their free ends."""
    point, direction = point_at(loop[index], 0.5), tangent_at(loop[index], 0.5)
    nx, ny = waste_normal(direction, left)
    centre_point = Point(point[0] + inset * nx, point[1] + inset * ny)
    first = lead_in(centre_point, direction, left, radius)
    last = lead_out(centre_point, direction, left, radius)
    # The free ends lie in the waste, away from the finished wall (a lead about the centre
    # of a round hole would run along the tool path itself).
    away = tool_radius + FREE_END_FRACTION * radius
    return Probe((first, last), tool_radius, (first.start, last.end), away)


#: The straight moves that turn cutter compensation on and off are this many tool radii
#: long: LinuxCNC refuses an entry move not longer than the radius.
APPROACH_RADII = 2.0


def approach(first: CircularArc, last: CircularArc, tool_radius: float) -> tuple[Point, Point]:
    """Under cutter compensation: where the straight entry move onto ``first`` starts (behind
    its start, along its start tangent) and where the exit move off ``last`` ends (ahead of
    its end, along its end tangent), :data:`APPROACH_RADII` tool radii away. Both moves run
    at ``safe_z``, above the stock: along the tangent, the controller's entry move ends with
    the tool where the compensated lead-in starts, which is clear of the contours."""
    reach = APPROACH_RADII * tool_radius
    tx, ty = tangent_at(first, 0.0)
    ux, uy = tangent_at(last, 1.0)
    (sx, sy), (ex, ey) = first.start, last.end
    return Point(sx - reach * tx, sy - reach * ty), Point(ex + reach * ux, ey + reach * uy)


def nearest_start(loop: Sequence[Element], point: Point, snap: float) -> Chain:
    """The closed loop begun at its point nearest ``point`` (at a joint when the nearest
    point lies within ``snap`` of one)."""
    best, best_t, best_d = 0, 0.0, math.inf
    for i, element in enumerate(loop):
        t = _nearest_t(element, point)
        d = math.dist(point_at(element, t), point)
        if d < best_d:
            best, best_t, best_d = i, t, d
    size = length(loop[best])
    if best_t * size <= snap:
        return rotated(loop, best)
    if (1.0 - best_t) * size <= snap:
        return rotated(loop, (best + 1) % len(loop))
    head, tail = split(loop[best], best_t)
    return (tail, *rotated(loop, best)[1:], head)


def _nearest_t(element: Element, point: Point) -> float:
    """The fraction of ``element`` nearest ``point``."""
    if isinstance(element, Line):
        (x0, y0), (x1, y1) = element.start, element.end
        dx, dy = x1 - x0, y1 - y0
        t = ((point[0] - x0) * dx + (point[1] - y0) * dy) / (dx * dx + dy * dy)
        return min(max(t, 0.0), 1.0)
    cx, cy = element.center
    sweep = element.sweep_rad
    turned = math.atan2(point[1] - cy, point[0] - cx) - element.start_angle_rad
    along = (turned if sweep > 0.0 else -turned) % (2.0 * math.pi)
    if along <= abs(sweep):
        return along / abs(sweep)
    # Outside the arc: the nearer end.
    ends = [math.dist(point, element.start), math.dist(point, element.end)]
    return 0.0 if ends[0] <= ends[1] else 1.0
