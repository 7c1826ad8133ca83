"""The result of an approximation: the arc spline, its segments and its statistics.

The segments of a spline are rows of a float64 table, one row per segment, whose columns are
:data:`FIELDS` (the compiled kernels write them directly, ``fit/batch.pyx``). A batch of
thousands of spirals therefore makes no Python object per arc: each :class:`ArcSpline` is a
view of its rows, and :attr:`ArcSpline.columns`, :attr:`ArcSpline.segments` and
:meth:`ArcSpline.values` give friendlier forms of the same numbers on demand.

Conventions: points are ``[x, y]``; angles are radians, anticlockwise positive; ``u`` is the
spiral's Bézier parameter. A line row (where an arc would be numerically flat) has ``is_arc``
0, its chord midpoint as ``center``, ``radius`` ``inf`` and ``start_angle_rad`` and
``sweep_rad`` 0.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar, Literal, NamedTuple

import numpy as np
import numpy.typing as npt

from .fit.batch import FIELDS, STATS_FIELDS

FloatArray = npt.NDArray[np.float64]
BoolArray = npt.NDArray[np.bool_]
Direction = Literal["ccw", "cw"]

#: Column of each field in a segment table (``FIELDS`` of the kernels, in their order).
COLUMN: dict[str, int] = {name: j for j, name in enumerate(FIELDS)}
_STATS = {name: j for j, name in enumerate(STATS_FIELDS)}


class Point(NamedTuple):
    """A point of the plane (serialises as ``[x, y]``)."""

    x: float
    y: float


@dataclass(frozen=True, slots=True)
class ArcSegment:
    """A circular arc of the spline.

    ``sweep_rad`` is signed (anticlockwise positive) and agrees with ``direction``;
    ``start_angle_rad`` is the polar angle of ``start`` about ``center``. ``u_start`` and
    ``u_end`` are the spiral parameters the arc covers, ``max_deviation`` the largest distance
    between that piece of the spiral and the arc, reached at ``u_at_max_deviation``.
    """

    type: ClassVar[Literal["arc"]] = "arc"
    start: Point
    end: Point
    center: Point
    radius: float
    direction: Direction
    start_angle_rad: float
    sweep_rad: float
    length: float
    u_start: float
    u_end: float
    max_deviation: float
    u_at_max_deviation: float


@dataclass(frozen=True, slots=True)
class LineSegment:
    """A straight segment, used where an arc would be numerically flat."""

    type: ClassVar[Literal["line"]] = "line"
    start: Point
    end: Point
    length: float
    u_start: float
    u_end: float
    max_deviation: float
    u_at_max_deviation: float


Segment = ArcSegment | LineSegment


@dataclass(frozen=True, slots=True)
class SegmentColumns:
    """The segments of one arc spline by column: views of its table, shapes ``(n,)`` or
    ``(n, 2)`` (``is_arc`` is a boolean copy)."""

    is_arc: BoolArray
    start: FloatArray
    end: FloatArray
    center: FloatArray
    radius: FloatArray
    start_angle_rad: FloatArray
    sweep_rad: FloatArray
    length: FloatArray
    u_start: FloatArray
    u_end: FloatArray
    max_deviation: FloatArray
    u_at_max_deviation: FloatArray

    @classmethod
    def of(cls, table: FloatArray) -> SegmentColumns:
        c = COLUMN
        return cls(
            is_arc=table[:, c["is_arc"]] != 0.0,
            start=table[:, c["start_x"] : c["start_y"] + 1],
            end=table[:, c["end_x"] : c["end_y"] + 1],
            center=table[:, c["center_x"] : c["center_y"] + 1],
            radius=table[:, c["radius"]],
            start_angle_rad=table[:, c["start_angle_rad"]],
            sweep_rad=table[:, c["sweep_rad"]],
            length=table[:, c["length"]],
            u_start=table[:, c["u_start"]],
            u_end=table[:, c["u_end"]],
            max_deviation=table[:, c["max_deviation"]],
            u_at_max_deviation=table[:, c["u_at_max_deviation"]],
        )

    def __len__(self) -> int:
        return int(self.is_arc.shape[0])


def segment(row: list[float]) -> Segment:
    """One table row (plain values, as :meth:`ArcSpline.values` gives them) as a value."""
    c = COLUMN
    start = Point(row[c["start_x"]], row[c["start_y"]])
    end = Point(row[c["end_x"]], row[c["end_y"]])
    if not row[c["is_arc"]]:
        return LineSegment(
            start=start,
            end=end,
            length=row[c["length"]],
            u_start=row[c["u_start"]],
            u_end=row[c["u_end"]],
            max_deviation=row[c["max_deviation"]],
            u_at_max_deviation=row[c["u_at_max_deviation"]],
        )
    sweep = row[c["sweep_rad"]]
    return ArcSegment(
        start=start,
        end=end,
        center=Point(row[c["center_x"]], row[c["center_y"]]),
        radius=row[c["radius"]],
        direction="ccw" if sweep > 0.0 else "cw",
        start_angle_rad=row[c["start_angle_rad"]],
        sweep_rad=sweep,
        length=row[c["length"]],
        u_start=row[c["u_start"]],
        u_end=row[c["u_end"]],
        max_deviation=row[c["max_deviation"]],
        u_at_max_deviation=row[c["u_at_max_deviation"]],
    )


@dataclass(frozen=True, slots=True)
class SplineStats:
    """Summary of one arc spline.

    ``deviation_ratio`` is ``max_deviation / tolerance``; ``mean_segment_deviation`` is the
    mean of the per-segment maxima. ``min_radius``/``max_radius`` are ``None`` when the
    spline has no arcs.
    """

    arc_count: int
    line_count: int
    max_deviation: float
    u_at_max_deviation: float
    deviation_ratio: float
    mean_segment_deviation: float
    spiral_length: float
    spline_length: float
    min_radius: float | None
    max_radius: float | None

    @property
    def segment_count(self) -> int:
        return self.arc_count + self.line_count

    @classmethod
    def of(cls, row: list[float], tolerance: float) -> SplineStats:
        """The statistics in a kernel's stats row (``STATS_FIELDS``)."""
        s = _STATS
        arcs = int(row[s["arc_count"]])
        max_deviation = row[s["max_deviation"]]
        return cls(
            arc_count=arcs,
            line_count=int(row[s["line_count"]]),
            max_deviation=max_deviation,
            u_at_max_deviation=row[s["u_at_max_deviation"]],
            deviation_ratio=max_deviation / tolerance,
            mean_segment_deviation=row[s["mean_segment_deviation"]],
            spiral_length=row[s["spiral_length"]],
            spline_length=row[s["spline_length"]],
            min_radius=row[s["min_radius"]] if arcs else None,
            max_radius=row[s["max_radius"]] if arcs else None,
        )


class ArcSpline:
    """An arc spline: its segments in order (a table of rows, :data:`COLUMN`), its
    statistics, the tolerance it was made for and the strategy that made it.

    Immutable. A batch's splines are views of the batch's tables, made on first use; the
    public constructor takes a spline's own table.
    """

    __slots__ = ("_begin", "_block", "_end", "_index", "_stats", "_strategy", "_tolerance")

    def __init__(
        self, table: FloatArray, stats: SplineStats, tolerance: float, strategy: str
    ) -> None:
        self._block, self._begin, self._end = table, 0, int(table.shape[0])
        self._stats: SplineStats | FloatArray = stats
        self._index = -1
        self._tolerance = tolerance
        self._strategy = strategy

    @classmethod
    def _of_batch(
        cls,
        block: FloatArray,
        begin: int,
        end: int,
        stats: FloatArray,
        index: int,
        tolerance: float,
        strategy: str,
    ) -> ArcSpline:
        """The spline of rows ``begin:end`` of a batch's ``block``, whose statistics are row
        ``index`` of the batch's ``stats`` array (read on first use)."""
        spline = cls.__new__(cls)
        spline._block, spline._begin, spline._end = block, begin, end
        spline._stats, spline._index = stats, index
        spline._tolerance, spline._strategy = tolerance, strategy
        return spline

    @property
    def table(self) -> FloatArray:
        """The segments, one row each (columns :data:`COLUMN`); read it, do not change it."""
        return self._block[self._begin : self._end]

    @property
    def columns(self) -> SegmentColumns:
        return SegmentColumns.of(self.table)

    def values(self) -> list[list[float]]:
        """Every row as plain Python floats (what a JSON encoder takes as it is)."""
        rows: list[list[float]] = self.table.tolist()
        return rows

    @property
    def stats(self) -> SplineStats:
        if not isinstance(self._stats, SplineStats):
            self._stats = SplineStats.of(self._stats[self._index].tolist(), self._tolerance)
        return self._stats

    @property
    def tolerance(self) -> float:
        return self._tolerance

    @property
    def strategy(self) -> str:
        return self._strategy

    @property
    def segments(self) -> tuple[Segment, ...]:
        return tuple(segment(row) for row in self.values())

    def __len__(self) -> int:
        return self._end - self._begin

    def __reduce__(self) -> tuple[type[ArcSpline], tuple[FloatArray, SplineStats, float, str]]:
        # Pickled with its own rows only (a copy of the view), not the whole batch's table.
        return ArcSpline, (self.table.copy(), self.stats, self.tolerance, self.strategy)

    def __repr__(self) -> str:
        return (
            f"ArcSpline({len(self)} segments, stats={self.stats!r}, "
            f"tolerance={self.tolerance!r}, strategy={self.strategy!r})"
        )
