"""Paths of any segments approximated as one arc spline per subpath (docs/method.md §11).

A path's segments are written to one table (``segment_table.py``), cut into pieces of
monotone curvature (``curves/split.pyx``), fitted in one compiled loop under one segment
budget for the whole path (``fit/batch.pyx``), and gathered back per subpath
(``path_spline.py``).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import NamedTuple

import numpy as np
import numpy.typing as npt

from .approximate import fit_of
from .curves.segments import CircularArc, Path, Segment
from .curves.split import split
from .errors import GeometryError
from .fit import MONOTONE_PIECES, FitMany, StrategyName
from .fit.batch import FRAME_FIELDS, PIECE_KINDS, STATS_FIELDS, STATUS, tolerance_floor
from .limits import DEFAULT_LIMITS, Limits
from .path_spline import IntArray, PathSpline, SubpathCurve, SubpathSpline
from .segment_table import check, segment_table, where
from .spline import COLUMN, ArcSpline, FloatArray, Point, SplineStats

_FRAME = {name: j for j, name in enumerate(FRAME_FIELDS)}
_STATS = {name: j for j, name in enumerate(STATS_FIELDS)}
_STATUS_NAME = {code: name for name, code in STATUS.items()}
_ARC_PIECE = PIECE_KINDS["arc"]


def approximate_path(
    path: Path,
    tolerance: float,
    strategy: StrategyName = "subdivide",
    limits: Limits = DEFAULT_LIMITS,
) -> PathSpline:
    """The arc splines of every subpath of ``path`` within ``tolerance``, by ``strategy``.

    ``limits.max_segments`` caps the output segments of the whole path. Raises
    :class:`GeometryError` naming the subpath and segment for input the core cannot take, and
    for a tolerance it cannot meet there.
    """
    fit = fit_of(strategy)
    if not (isinstance(tolerance, int | float) and math.isfinite(tolerance) and tolerance > 0):
        raise GeometryError("tolerance", f"must be a finite number > 0, got {tolerance!r}")
    if not path.subpaths:
        raise GeometryError("path", "has no subpaths")
    owner: list[tuple[int, int]] = []
    for i, sub in enumerate(path.subpaths):
        if not sub.segments:
            raise GeometryError(f"path.subpaths[{i}]", "has no segments")
        owner += [(i, j) for j in range(len(sub.segments))]
    table = segment_table([segment for sub in path.subpaths for segment in sub.segments])
    check(table, owner)
    # A strategy that does not need monotone curvature gets fewer cuts; where that fails on
    # a piece (a sharp curvature peak inside it), the path is cut fully and fitted again.
    done = _fit(table, fit, float(tolerance), limits, MONOTONE_PIECES[strategy])
    if not done.ok:
        done = _fit(table, fit, float(tolerance), limits, True)
    bad = np.flatnonzero(done.status != STATUS["ok"])
    if len(bad):
        k = int(bad[0])
        i, j = owner[int(done.pieces[k, 0])]
        raise _refusal(int(done.status[k]), tolerance, where(i, j), done.frames[k], limits)
    return _gather(path, done, float(tolerance), strategy)


class _Fitted(NamedTuple):
    frames: FloatArray
    pieces: FloatArray
    blocks: list[FloatArray]
    where: IntArray
    stats: FloatArray
    status: npt.NDArray[np.int32]

    @property
    def ok(self) -> bool:
        """Every piece fitted but those below the tolerance floor (which more cuts cannot
        help)."""
        status = self.status
        return not np.any((status != STATUS["ok"]) & (status != STATUS["tolerance_floor"]))


def _fit(
    table: FloatArray, fit: FitMany, tolerance: float, limits: Limits, extrema: bool
) -> _Fitted:
    """Cut the segments (at curvature extrema too, if ``extrema``) and fit every piece under
    one segment budget."""
    frames, pieces = split(table, limits.max_segments, extrema)
    if frames is None or pieces is None:
        raise GeometryError(
            "tolerance",
            f"the path needs more than the limit of {limits.max_segments} segments; "
            "split it into several requests",
            kind="segment_limit",
            limit=float(limits.max_segments),
        )
    tol = np.full(len(frames), tolerance)
    blocks, where, stats, status, _aux = fit(
        frames, tol, limits.max_segments, limits.min_relative_tolerance, True
    )
    return _Fitted(frames, pieces, blocks, where, stats, status)


def _gather(path: Path, done: _Fitted, tolerance: float, strategy: str) -> PathSpline:
    """The fitted rows of every piece, in order, cut into one spline per subpath (vectorised:
    a path of thousands of subpaths costs microseconds each)."""
    frames, pieces, blocks, where, stats = (
        done.frames,
        done.pieces,
        done.blocks,
        done.where,
        done.stats,
    )
    # With one budget the pieces' rows follow each other through the blocks, in order.
    table = np.concatenate(blocks)
    counts = where[:, 2] - where[:, 1]
    sizes = [len(sub.segments) for sub in path.subpaths]
    first_segment = np.concatenate([[0], np.cumsum(sizes)])
    piece_subpath = np.searchsorted(first_segment, pieces[:, 0], side="right") - 1
    piece_bounds = np.searchsorted(piece_subpath, np.arange(len(sizes) + 1))
    empty = np.flatnonzero(piece_bounds[1:] == piece_bounds[:-1])
    if len(empty):
        raise GeometryError(
            f"path.subpaths[{int(empty[0])}]", "has no length (all its points coincide)"
        )
    # u → piece parameter g = (index of the piece in its subpath) + u
    row_piece = np.repeat(np.arange(len(pieces)), counts)
    shift = (row_piece - piece_bounds[piece_subpath[row_piece]]).astype(np.float64)
    for name in ("u_start", "u_end", "u_at_max_deviation"):
        table[:, COLUMN[name]] += shift
    segments = [segment for sub in path.subpaths for segment in sub.segments]
    table, row_piece = _merge_circular(table, row_piece, pieces, frames, segments)
    row_bounds = np.searchsorted(row_piece, piece_bounds)
    lengths = np.add.reduceat(stats[:, _STATS["spiral_length"]], piece_bounds[:-1])
    scales = np.maximum.reduceat(frames[:, _FRAME["coordinate_scale"]], piece_bounds[:-1])
    summaries = _stats(table, row_bounds, lengths)
    of_batch = ArcSpline._of_batch
    local_pieces = pieces.copy()
    local_pieces[:, 0] -= first_segment[piece_subpath]
    results = [
        SubpathSpline(
            of_batch(table, r0, r1, summaries, i, tolerance, strategy),
            SubpathCurve(
                frames[k0:k1], Point(*sub.segments[0].start), Point(*sub.segments[-1].end), scale
            ),
            sub.closed,
            local_pieces[k0:k1],
        )
        for i, (sub, k0, k1, r0, r1, scale) in enumerate(zip(
            path.subpaths, piece_bounds[:-1].tolist(), piece_bounds[1:].tolist(),
            row_bounds[:-1].tolist(), row_bounds[1:].tolist(), scales.tolist(),
            strict=True,
        ))
    ]  # fmt: skip
    if len(results) == 1:
        overall = summaries[0].tolist()  # one subpath: its statistics are the path's
    else:
        (overall,) = _stats(table, np.array([0, len(table)]), lengths.sum(keepdims=True)).tolist()
    return PathSpline(tuple(results), SplineStats.of(overall, tolerance), tolerance, strategy)


def _merge_circular(
    table: FloatArray,
    row_piece: IntArray,
    pieces: FloatArray,
    frames: FloatArray,
    segments: Sequence[Segment],
) -> tuple[FloatArray, IntArray]:
    """The rows of an input circular arc (one per quarter-turn piece) as the one arc it is:
    its own centre, radius and sweep. Returns the table and each row's piece."""
    is_arc_piece = frames[row_piece, _FRAME["kind"]] == _ARC_PIECE
    if not is_arc_piece.any():
        return table, row_piece
    segment = pieces[row_piece, 0].astype(np.int64)
    # Keep every row but the second and later rows of an arc segment.
    later = is_arc_piece & np.concatenate([[False], segment[1:] == segment[:-1]])
    keep = ~later
    # A circular arc flatter than the assembly's flat-arc limit came back as its chord (one
    # row, a line): it stays one.
    for r in np.flatnonzero(is_arc_piece & keep & (table[:, COLUMN["is_arc"]] != 0.0)).tolist():
        arc = segments[int(segment[r])]
        assert isinstance(arc, CircularArc)
        last = r
        while last + 1 < len(table) and later[last + 1]:
            last += 1
        row = table[r]
        row[COLUMN["end_x"]], row[COLUMN["end_y"]] = arc.end
        row[COLUMN["center_x"]], row[COLUMN["center_y"]] = arc.center
        row[COLUMN["radius"]] = arc.radius
        row[COLUMN["start_angle_rad"]] = math.atan2(
            arc.start[1] - arc.center[1], arc.start[0] - arc.center[0]
        )
        row[COLUMN["sweep_rad"]] = arc.sweep_rad
        row[COLUMN["length"]] = arc.radius * abs(arc.sweep_rad)
        row[COLUMN["u_end"]] = table[last, COLUMN["u_end"]]
    return table[keep], row_piece[keep]


def _stats(table: FloatArray, bounds: IntArray, curve_lengths: FloatArray) -> FloatArray:
    """The statistics rows (``STATS_FIELDS``) of each group of rows ``bounds[i]:bounds[i + 1]``
    (none empty)."""
    starts = bounds[:-1]
    is_arc = table[:, COLUMN["is_arc"]] != 0.0
    dev = table[:, COLUMN["max_deviation"]]
    group = np.repeat(np.arange(len(starts)), np.diff(bounds))
    # The first row of each group with its largest deviation.
    order = np.lexsort((-dev, group))
    worst = order[starts]
    arcs = np.add.reduceat(is_arc.astype(np.float64), starts)
    radius = np.where(is_arc, table[:, COLUMN["radius"]], np.nan)
    with np.errstate(invalid="ignore"):
        low = np.fmin.reduceat(radius, starts)
        high = np.fmax.reduceat(radius, starts)
    columns = np.zeros((len(starts), len(STATS_FIELDS)))
    columns[:, _STATS["arc_count"]] = arcs
    columns[:, _STATS["line_count"]] = np.diff(bounds) - arcs
    columns[:, _STATS["max_deviation"]] = dev[worst]
    columns[:, _STATS["u_at_max_deviation"]] = table[worst, COLUMN["u_at_max_deviation"]]
    columns[:, _STATS["mean_segment_deviation"]] = np.add.reduceat(dev, starts) / np.diff(bounds)
    columns[:, _STATS["spiral_length"]] = curve_lengths
    columns[:, _STATS["spline_length"]] = np.add.reduceat(table[:, COLUMN["length"]], starts)
    columns[:, _STATS["min_radius"]] = low
    columns[:, _STATS["max_radius"]] = high
    return columns


def _refusal(
    code: int, tolerance: float, where: str, frame: FloatArray, limits: Limits
) -> GeometryError:
    why = _STATUS_NAME[code]
    if why == "tolerance_floor":
        floor = tolerance_floor(
            float(frame[_FRAME["chord"]]),
            float(frame[_FRAME["coordinate_scale"]]),
            limits.min_relative_tolerance,
        )
        return GeometryError(
            "tolerance",
            f"{tolerance:.6g} is below the smallest reachable tolerance {floor:.6g} at {where} "
            "(its size and coordinates); double precision cannot deliver less",
            kind="tolerance_floor",
            limit=floor,
        )
    if why == "segment_limit":
        return GeometryError(
            "tolerance",
            f"{tolerance:.6g} needs more than the limit of {limits.max_segments} segments for "
            f"this path (reached at {where}); raise the tolerance or split the path",
            kind="segment_limit",
            limit=float(limits.max_segments),
        )
    if why == "stuck":
        return GeometryError(
            where,
            "turns too sharply (a near-cusp, or nearly straight control points that double "
            f"back) for double precision to follow within {tolerance:.6g}; make the cusp exact "
            "(coincident control points) or smooth it",
            kind="precision",
        )
    return GeometryError(
        "tolerance",
        f"{tolerance:.6g} cannot be held in double precision at {where}; raise the tolerance",
        kind="precision",
    )
