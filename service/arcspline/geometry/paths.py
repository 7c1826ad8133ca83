"""Paths of any segments approximated as one arc spline per subpath (docs/method.md §11).

A path's segments are written to one table (``curves/split.pyx``'s ``SEGMENT_FIELDS``), cut
into pieces of monotone curvature, fitted in one compiled loop under one segment budget for
the whole path (``fit/batch.pyx``), and gathered back per subpath. Each subpath's result is an
:class:`~arcspline.geometry.spline.ArcSpline` whose parameter ``u`` is the *piece parameter*
``g = k + u_k`` (piece ``k``, local ``u_k``), paired with a :class:`SubpathCurve` that
evaluates and measures the source in that parameter (what the G-code planner and the preview
need); :meth:`SubpathSpline.sources` turns ``g`` into the input segment and its own
parameter ``t``.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np
import numpy.typing as npt

from .curves.segments import CircularArc, Cubic, EllipticalArc, Line, Path, Quadratic, Segment
from .curves.split import SEGMENT_FIELDS, SEGMENT_KINDS, split
from .errors import GeometryError
from .fit import MONOTONE_PIECES, STRATEGIES, FitMany, StrategyName
from .fit.batch import FRAME_FIELDS, PIECE_KINDS, STATS_FIELDS, STATUS
from .limits import DEFAULT_LIMITS, Limits
from .measure import circle_deviations, line_deviations, points
from .spline import COLUMN, ArcSpline, FloatArray, Point, SplineStats

IntArray = npt.NDArray[np.int64]

#: Coordinates and radii stay below this magnitude, so that squares and products of them stay
#: finite in double precision (as for spirals).
MAX_MAGNITUDE = 1e150
#: A segment smaller than this (but not a point) would underflow in the squares of its size.
MIN_SIZE = 1e-150

_SEG = {name: j for j, name in enumerate(SEGMENT_FIELDS)}
_FRAME = {name: j for j, name in enumerate(FRAME_FIELDS)}
_STATS = {name: j for j, name in enumerate(STATS_FIELDS)}
_STATUS_NAME = {code: name for name, code in STATUS.items()}
_ARC_PIECE = PIECE_KINDS["arc"]


@dataclass(frozen=True, slots=True)
class Source:
    """Where an output segment comes from: input segment ``segment`` of its subpath, over
    its parameter range ``[t_start, t_end]``; its largest deviation is reached at
    ``t_at_max_deviation``."""

    segment: IntArray
    t_start: FloatArray
    t_end: FloatArray
    t_at_max_deviation: FloatArray


class SubpathCurve:
    """A subpath's source in the piece parameter ``g ∈ [0, pieces]`` (the
    :class:`~arcspline.geometry.curves.Curve` protocol): ``g = k + u`` is piece ``k`` at its
    local ``u``."""

    def __init__(
        self, frames: FloatArray, start: Point, end: Point, coordinate_scale: float
    ) -> None:
        self._frames = frames
        self._start, self._end = start, end
        self._coordinate_scale = coordinate_scale

    @property
    def frame(self) -> tuple[float, ...]:
        raise TypeError("a subpath has one frame per piece (see SubpathCurve.frames)")

    @property
    def frames(self) -> FloatArray:
        return self._frames

    @property
    def domain(self) -> tuple[float, float]:
        return (0.0, float(len(self._frames)))

    @property
    def start(self) -> Point:
        return self._start

    @property
    def end_point(self) -> Point:
        return self._end

    @property
    def chord(self) -> float:
        return math.dist(self._start, self._end)

    @property
    def coordinate_scale(self) -> float:
        return self._coordinate_scale

    def _local(self, g: FloatArray) -> tuple[IntArray, FloatArray]:
        last = len(self._frames) - 1
        piece = np.clip(np.floor(g), 0, last).astype(np.int64)
        return piece, g - piece

    def eval(self, u: float | FloatArray) -> FloatArray:
        g = np.asarray(u, dtype=np.float64)
        piece, local = self._local(g.ravel())
        return points(self._frames, piece, local).reshape((*g.shape, 2))

    def _ranges(
        self, u0: FloatArray, u1: FloatArray
    ) -> tuple[IntArray, IntArray, FloatArray, FloatArray]:
        """Each query ``[u0, u1]`` cut at piece boundaries: (query, piece, lo, hi) per part."""
        first, _ = self._local(np.asarray(u0, dtype=np.float64))
        last = np.maximum(first, np.ceil(np.asarray(u1, dtype=np.float64)).astype(np.int64) - 1)
        last = np.minimum(last, len(self._frames) - 1)
        counts = last - first + 1
        query = np.repeat(np.arange(len(first)), counts)
        piece = first[query] + (
            np.arange(len(query)) - np.repeat(np.cumsum(counts) - counts, counts)
        )
        lo = np.clip(np.asarray(u0)[query] - piece, 0.0, 1.0)
        hi = np.clip(np.asarray(u1)[query] - piece, 0.0, 1.0)
        return query, piece, lo, hi

    def line_deviations(
        self, u0: FloatArray, u1: FloatArray, start: FloatArray, end: FloatArray
    ) -> FloatArray:
        query, piece, lo, hi = self._ranges(u0, u1)
        parts = line_deviations(self._frames, piece, lo, hi, start[query], end[query])
        out = np.zeros(len(u0))
        np.maximum.at(out, query, parts)
        return out

    def circle_deviations(
        self,
        u0: FloatArray,
        u1: FloatArray,
        centre: FloatArray,
        r_start: FloatArray,
        r_end: FloatArray,
    ) -> FloatArray:
        query, piece, lo, hi = self._ranges(u0, u1)
        parts = circle_deviations(
            self._frames, piece, lo, hi, centre[query], r_start[query], r_end[query]
        )
        out = np.zeros(len(u0))
        np.maximum.at(out, query, parts)
        return out


@dataclass(frozen=True, slots=True)
class SubpathSpline:
    """One subpath's arc spline (parameter: the piece parameter ``g``), its source curve
    and, per output segment, which input segment it answers for."""

    spline: ArcSpline
    curve: SubpathCurve
    closed: bool
    pieces: FloatArray  # per piece: segment, t0, t1, half angle (split.PIECE_FIELDS)

    def sources(self) -> Source:
        """The input segment and its parameter ``t`` for every output segment."""
        cols = self.spline.table
        g0, g1 = cols[:, COLUMN["u_start"]], cols[:, COLUMN["u_end"]]
        gm = cols[:, COLUMN["u_at_max_deviation"]]
        segment, t0 = self._segment_t(g0, upper=False)
        _, t1 = self._segment_t(g1, upper=True)
        at_segment, tm = self._segment_t(gm, upper=False)
        # A maximum at a piece boundary may read as the next segment's start: take the end
        # of the row's own segment instead.
        tm = np.where(at_segment == segment, tm, 1.0)
        return Source(segment=segment, t_start=t0, t_end=t1, t_at_max_deviation=tm)

    def _segment_t(self, g: FloatArray, *, upper: bool) -> tuple[IntArray, FloatArray]:
        last = len(self.pieces) - 1
        piece = np.clip(np.floor(g), 0, last).astype(np.int64)
        if upper:  # an end at a piece boundary belongs to the piece before
            piece = np.where((g == piece) & (piece > 0), piece - 1, piece)
        u = g - piece
        seg, t0, t1, half = (self.pieces[piece, j] for j in range(4))
        with np.errstate(invalid="ignore", divide="ignore"):
            conic = 0.5 + np.arctan(np.tan(0.5 * half) * (2.0 * u - 1.0)) / half
        fraction = np.where(half > 0.0, conic, u)
        # The ends of a piece are its segment's cut points exactly, so that rows tile.
        t = np.where(u == 1.0, t1, np.where(u == 0.0, t0, t0 + (t1 - t0) * fraction))
        return seg.astype(np.int64), t


@dataclass(frozen=True, slots=True)
class PathSpline:
    """A path's approximation: one :class:`SubpathSpline` per subpath, the statistics over
    all of them, the tolerance and the strategy."""

    subpaths: tuple[SubpathSpline, ...]
    stats: SplineStats
    tolerance: float
    strategy: str

    @property
    def segment_count(self) -> int:
        return sum(len(s.spline) for s in self.subpaths)


#: ``SEGMENT_FIELDS`` in the order :func:`segment_row` writes them.
_ROW_ORDER = (
    "kind", "x0", "y0", "x1", "y1", "x2", "y2", "x3", "y3", "cx", "cy", "rx", "ry",
    "rotation_rad", "start_angle_rad", "sweep_rad", "coordinate_scale",
)  # fmt: skip
assert SEGMENT_FIELDS == _ROW_ORDER
_KIND = {
    Line: float(SEGMENT_KINDS["line"]),
    Quadratic: float(SEGMENT_KINDS["quadratic"]),
    Cubic: float(SEGMENT_KINDS["cubic"]),
    CircularArc: float(SEGMENT_KINDS["arc"]),
    EllipticalArc: float(SEGMENT_KINDS["elliptical_arc"]),
}


def segment_row(segment: Segment) -> tuple[float, ...]:
    """A segment as a row of ``SEGMENT_FIELDS`` (its kind, points and arc parameters; the
    coordinate scale is left 0 for :func:`segment_table`)."""
    (x0, y0), (x3, y3) = segment.start, segment.end
    kind = _KIND[type(segment)]
    if isinstance(segment, Line):
        return (kind, x0, y0, 0.0, 0.0, 0.0, 0.0, x3, y3, *_NO_ARC)
    if isinstance(segment, Quadratic):
        return (kind, x0, y0, *segment.control, 0.0, 0.0, x3, y3, *_NO_ARC)
    if isinstance(segment, Cubic):
        return (kind, x0, y0, *segment.control1, *segment.control2, x3, y3, *_NO_ARC)
    if isinstance(segment, CircularArc):
        rx = ry = segment.radius
        rotation = 0.0
    else:
        rx, ry, rotation = segment.rx, segment.ry, segment.rotation_rad
    return (
        kind, x0, y0, 0.0, 0.0, 0.0, 0.0, x3, y3, *segment.center, rx, ry, rotation,
        segment.start_angle_rad, segment.sweep_rad, 0.0,
    )  # fmt: skip


_NO_ARC = (0.0,) * 8


def segment_table(segments: Sequence[Segment]) -> FloatArray:
    """The segments as rows of ``SEGMENT_FIELDS``, with each one's coordinate scale: the
    largest magnitude of its points (and of its arc's centre plus radius)."""
    table = np.array([segment_row(s) for s in segments], dtype=np.float64)
    with np.errstate(invalid="ignore"):
        reach = np.maximum(table[:, _SEG["rx"]], table[:, _SEG["ry"]])
        table[:, _SEG["coordinate_scale"]] = np.maximum.reduce(
            [
                np.abs(table[:, _SEG["x0"] : _SEG["y3"] + 1]).max(axis=1),
                np.abs(table[:, _SEG["cx"]]) + reach,
                np.abs(table[:, _SEG["cy"]]) + reach,
            ]
        )
    return table


def _check(table: FloatArray, owner: list[tuple[int, int]]) -> None:
    """Numbers the kernels can hold: finite, below ``MAX_MAGNITUDE``; radii > 0; sweeps
    within a full turn. Raises for the first segment that fails, naming it."""
    kind = table[:, _SEG["kind"]]
    arcs = kind >= SEGMENT_KINDS["arc"]
    sweep = np.abs(table[:, _SEG["sweep_rad"]])
    with np.errstate(invalid="ignore"):
        bad_number = ~np.all(np.abs(table) < MAX_MAGNITUDE, axis=1)
        bad_radius = arcs & ~((table[:, _SEG["rx"]] > 0.0) & (table[:, _SEG["ry"]] > 0.0))
        bad_sweep = arcs & ~((sweep > 0.0) & (sweep < 2.0 * math.pi))
    # Each segment starts where the one before it in its subpath ends, to the bit.
    starts, ends = table[1:, _SEG["x0"] : _SEG["y0"] + 1], table[:-1, _SEG["x3"] : _SEG["y3"] + 1]
    same_subpath = np.array([a[0] == b[0] for a, b in itertools.pairwise(owner)], dtype=bool)
    broken = np.concatenate([[False], same_subpath & np.any(starts != ends, axis=1)])
    size = _sizes(table)
    tiny = (size > 0.0) & (size < MIN_SIZE)
    for bad, why in (
        (bad_number, f"has a number that is not finite or beyond ±{MAX_MAGNITUDE:g}"),
        (tiny, f"is smaller than {MIN_SIZE:g} across, too small for double precision"),
        (broken, "does not start where the segment before it ends"),
        (bad_radius, "an arc's radii must be > 0"),
        (bad_sweep, "an arc's sweep must be non-zero and less than a full turn"),
    ):
        if bad.any():
            i, j = owner[int(np.argmax(bad))]
            raise GeometryError(_where(i, j), why)


def _sizes(table: FloatArray) -> FloatArray:
    """Each segment's extent: its control points' largest offset from its start (a line's
    length), or an arc's larger radius."""
    kind = table[:, _SEG["kind"]]
    start = table[:, _SEG["x0"] : _SEG["y0"] + 1]
    used = {  # the control points each kind has, besides its start
        "x1": kind == SEGMENT_KINDS["quadratic"],
        "x2": kind == SEGMENT_KINDS["cubic"],
        "x3": kind < SEGMENT_KINDS["arc"],
    }
    used["x1"] = used["x1"] | used["x2"]
    size = np.where(
        kind >= SEGMENT_KINDS["arc"], np.maximum(table[:, _SEG["rx"]], table[:, _SEG["ry"]]), 0.0
    )
    with np.errstate(invalid="ignore", over="ignore"):
        for name, mask in used.items():
            j = _SEG[name]
            offset = np.abs(table[:, j : j + 2] - start).max(axis=1)
            size = np.where(mask, np.maximum(size, offset), size)
    return size


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
    fit = _strategy(strategy)
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
    _check(table, owner)
    # A strategy that does not need monotone curvature gets fewer cuts; where that fails on
    # a piece (a sharp curvature peak inside it), the path is cut fully and fitted again.
    done = _fit(table, fit, float(tolerance), limits, MONOTONE_PIECES[strategy])
    if not done.ok:
        done = _fit(table, fit, float(tolerance), limits, True)
    bad = np.flatnonzero(done.status != STATUS["ok"])
    if len(bad):
        k = int(bad[0])
        i, j = owner[int(done.pieces[k, 0])]
        raise _refusal(int(done.status[k]), tolerance, _where(i, j), done.frames[k], limits)
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
    for r in np.flatnonzero(is_arc_piece & keep).tolist():
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


def _where(subpath: int, segment: int) -> str:
    return f"path.subpaths[{subpath}].segments[{segment}]"


def _strategy(name: str) -> FitMany:
    try:
        return STRATEGIES[name]
    except (KeyError, TypeError):
        raise GeometryError(
            "strategy", f"unknown strategy {name!r}; choose one of {', '.join(STRATEGIES)}"
        ) from None


def _refusal(
    code: int, tolerance: float, where: str, frame: FloatArray, limits: Limits
) -> GeometryError:
    why = _STATUS_NAME[code]
    if why == "tolerance_floor":
        from .fit.batch import tolerance_floor

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
