"""The result of approximating a path: one arc spline per subpath, each with the source it
follows (docs/method.md §11).

Each subpath's result is an :class:`~arcspline.geometry.spline.ArcSpline` whose parameter
``u`` is the *piece parameter* ``g = k + u_k`` (piece ``k`` of the subpath, local ``u_k``),
paired with a :class:`SubpathCurve` that evaluates and measures the source in that parameter
(what the G-code planner and the preview need); :meth:`SubpathSpline.sources` turns ``g``
into the input segment and its own parameter ``t``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from .measure import circle_deviations, line_deviations, points
from .spline import COLUMN, ArcSpline, FloatArray, Point, SplineStats

IntArray = npt.NDArray[np.int64]


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
