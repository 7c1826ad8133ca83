"""Exact distances between points, lines and arcs (docs/offsets.md §4).

A point's distance to a line segment is to its foot, clamped to the segment; to an arc, the
distance to its circle where the point's polar angle lies within the sweep, otherwise to the
nearer end. Two elements that meet are 0 apart; otherwise their nearest points are an end of
one against the other, or (with an arc) the points where the normal of one passes through
the other's nearest point: for an arc against a line, the arc's points ``c ± r·n`` (``n``
the line's normal); for two arcs, the points of each on the line of centres.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from ..errors import GeometryError
from ..path_spline import IntArray
from ..spline import FloatArray, Point
from .broad import overlapping
from .intersect import hits
from .table import Table, boxes, coordinate_scale, fraction, table_of
from .types import Element

#: The tolerance (relative to the coordinates) within which elements count as meeting.
MEET_RTOL = 1e-12
#: Element pairs measured in one vectorised call (a few hundred MB of temporaries at most).
_PAIRS_AT_ONCE = 1 << 18


def point_distances(points: FloatArray, table: Table) -> FloatArray:
    """The distance from ``points[k]`` to element ``k`` of ``table`` (docs/offsets.md §4)."""
    out = np.empty(len(table))
    lines = np.flatnonzero(~table.is_arc)
    if len(lines):
        p, a, b = points[lines], table.start[lines], table.end[lines]
        u = b - a
        uu = np.einsum("ij,ij->i", u, u)
        with np.errstate(divide="ignore", invalid="ignore"):
            t = np.clip(np.einsum("ij,ij->i", p - a, u) / uu, 0.0, 1.0)
        t = np.where(uu > 0.0, t, 0.0)
        out[lines] = np.hypot(*(a + t[:, None] * u - p).T)
    arcs = np.flatnonzero(table.is_arc)
    if len(arcs):
        sub = table.take(arcs)
        rel = points[arcs] - sub.center
        t = fraction(sub, np.arctan2(rel[:, 1], rel[:, 0]), 0.0)
        radial = np.abs(np.hypot(*rel.T) - sub.radius)
        ends = np.minimum(
            np.hypot(*(points[arcs] - sub.start).T), np.hypot(*(points[arcs] - sub.end).T)
        )
        out[arcs] = np.where((t >= 0.0) & (t <= 1.0), radial, ends)
    return out


def pair_distances(a: Table, b: Table, tol: float) -> FloatArray:
    """The exact minimum distance between ``a[k]`` and ``b[k]`` for each ``k``; 0 where they
    meet (within ``tol``)."""
    with np.errstate(all="ignore"):  # a point-like element's direction: its ends decide
        return _pair_distances(a, b, tol)


def _pair_distances(a: Table, b: Table, tol: float) -> FloatArray:
    best: FloatArray = np.minimum.reduce(
        [
            point_distances(a.start, b),
            point_distances(a.end, b),
            point_distances(b.start, a),
            point_distances(b.end, a),
        ]
    )
    for first, second in ((a, b), (b, a)):
        for point, valid in _normal_points(first, second):
            rows = np.flatnonzero(valid)
            d = point_distances(point[rows], second.take(rows))
            best[rows] = np.minimum(best[rows], d)
    # Only elements whose boxes overlap can meet.
    box_a, box_b = boxes(a), boxes(b)
    close = np.flatnonzero(
        (box_a[:, 0] <= box_b[:, 2] + tol) & (box_b[:, 0] <= box_a[:, 2] + tol)
        & (box_a[:, 1] <= box_b[:, 3] + tol) & (box_b[:, 1] <= box_a[:, 3] + tol)
    )  # fmt: skip
    met = close[hits(a.take(close), b.take(close), tol).pair]
    best[met] = 0.0
    return best


def _normal_points(arc: Table, other: Table) -> list[tuple[FloatArray, np.ndarray]]:
    """The points of each arc of ``arc`` (rows that are arcs) where the normal to the arc
    passes through the nearest point of ``other`` (see the module), with their validity."""
    line_normal = np.column_stack(
        [-(other.end - other.start)[:, 1], (other.end - other.start)[:, 0]]
    )
    to_centre = other.center - arc.center
    direction = np.where(other.is_arc[:, None], to_centre, line_normal)
    size = np.hypot(*direction.T)
    with np.errstate(divide="ignore", invalid="ignore"):
        unit = direction / size[:, None]
    usable = arc.is_arc & (size > 0.0)
    out = []
    for sign in (1.0, -1.0):
        point = arc.center + sign * arc.radius[:, None] * np.nan_to_num(unit)
        t = fraction(arc, np.arctan2(sign * unit[:, 1], sign * unit[:, 0]), 0.0)
        out.append((point, usable & (t >= 0.0) & (t <= 1.0)))
    return out


def segment_distance(a: Element, b: Element) -> float:
    """The exact minimum distance between two lines or arcs (docs/offsets.md §4); 0 if they
    meet.

    >>> from arcspline.geometry.curves.segments import Line
    >>> segment_distance(Line((0.0, 0.0), (1.0, 0.0)), Line((2.0, 1.0), (2.0, 3.0)))
    1.4142135623730951
    """
    table = table_of([a, b])
    tol = MEET_RTOL * coordinate_scale(table)
    first, second = table.take(np.array([0])), table.take(np.array([1]))
    return float(pair_distances(first, second, tol)[0])


def chain_distance(point: Point | tuple[float, float], elements: Sequence[Element]) -> float:
    """The exact distance from ``point`` to the nearest element of a chain
    (docs/offsets.md §4)."""
    if not elements:
        raise GeometryError("elements", "a chain needs at least one element")
    table = table_of(elements)
    points = np.broadcast_to(np.asarray(point, dtype=np.float64), (len(table), 2))
    return float(point_distances(np.ascontiguousarray(points), table).min())


def min_distances(
    pieces: Table,
    owner: IntArray,
    piece_chain: IntArray,
    groups: int,
    source: Table,
    source_chain: IntArray,
    reach: float,
    tol: float,
) -> FloatArray:
    """For each group of pieces (``owner[k]`` is piece ``k``'s group), the smallest distance
    from its pieces to the ``source`` elements of the same chain, or ``inf`` where none lies
    within ``reach`` (docs/offsets.md §5, the validity of slices). Broad phase through
    bounding boxes."""
    out = np.full(groups, np.inf)
    i, j = overlapping(boxes(pieces), boxes(source), reach)
    mine = piece_chain[i] == source_chain[j]
    i, j = i[mine], j[mine]
    for chunk in range(0, len(i), _PAIRS_AT_ONCE):  # bounds the memory of the temporaries
        ci, cj = i[chunk : chunk + _PAIRS_AT_ONCE], j[chunk : chunk + _PAIRS_AT_ONCE]
        np.minimum.at(out, owner[ci], pair_distances(pieces.take(ci), source.take(cj), tol))
    return out
