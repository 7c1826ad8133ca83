"""Value types of the core: points, segments, statistics and the arc spline itself.

An arc spline is stored by columns (``SegmentColumns``: one numpy array per field, one row
per segment) so that a batch of thousands of spirals never builds a Python object per arc;
``ArcSpline.segments`` gives the friendly per-segment view on demand.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar, Literal, NamedTuple

import numpy as np
import numpy.typing as npt

FloatArray = npt.NDArray[np.float64]
BoolArray = npt.NDArray[np.bool_]
Direction = Literal["ccw", "cw"]


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
    """The segments of one arc spline (or of a whole batch), one row per segment.

    Shapes: ``(n,)`` or ``(n, 2)``, float64 except ``is_arc``. For a line row, ``center`` is
    the chord midpoint, ``radius`` is ``inf`` and ``sweep_rad`` and ``start_angle_rad`` are 0.
    """

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

    def __len__(self) -> int:
        return int(self.is_arc.shape[0])

    def rows(self, begin: int, end: int) -> SegmentColumns:
        """Rows ``begin:end`` as views (no copy)."""
        s = slice(begin, end)
        return SegmentColumns(
            self.is_arc[s],
            self.start[s],
            self.end[s],
            self.center[s],
            self.radius[s],
            self.start_angle_rad[s],
            self.sweep_rad[s],
            self.length[s],
            self.u_start[s],
            self.u_end[s],
            self.max_deviation[s],
            self.u_at_max_deviation[s],
        )

    def segment(self, i: int) -> Segment:
        """Row ``i`` as a value object."""
        start = Point(float(self.start[i, 0]), float(self.start[i, 1]))
        end = Point(float(self.end[i, 0]), float(self.end[i, 1]))
        if not self.is_arc[i]:
            return LineSegment(
                start=start,
                end=end,
                length=float(self.length[i]),
                u_start=float(self.u_start[i]),
                u_end=float(self.u_end[i]),
                max_deviation=float(self.max_deviation[i]),
                u_at_max_deviation=float(self.u_at_max_deviation[i]),
            )
        sweep = float(self.sweep_rad[i])
        return ArcSegment(
            start=start,
            end=end,
            center=Point(float(self.center[i, 0]), float(self.center[i, 1])),
            radius=float(self.radius[i]),
            direction="ccw" if sweep > 0.0 else "cw",
            start_angle_rad=float(self.start_angle_rad[i]),
            sweep_rad=sweep,
            length=float(self.length[i]),
            u_start=float(self.u_start[i]),
            u_end=float(self.u_end[i]),
            max_deviation=float(self.max_deviation[i]),
            u_at_max_deviation=float(self.u_at_max_deviation[i]),
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


class ArcSpline:
    """The result of approximating one spiral: its segments in order, and statistics.

    Immutable: its attributes are read-only properties. The splines of a batch share the
    batch's columns: ``columns`` are views of this spline's rows, made on first use, so a
    batch of thousands makes no per-spline arrays that nobody reads.
    """

    __slots__ = ("_batch", "_begin", "_columns", "_end", "_stats", "_strategy", "_tolerance")

    def __init__(
        self,
        columns: SegmentColumns,
        stats: SplineStats,
        tolerance: float,
        strategy: str,
        rows: tuple[int, int] | None = None,
    ) -> None:
        """The spline of ``columns``, or of ``columns``' rows ``rows = (begin, end)``."""
        self._batch = columns
        if rows is None:
            self._begin, self._end = 0, len(columns)
            self._columns: SegmentColumns | None = columns
        else:
            self._begin, self._end = rows
            self._columns = None
        self._stats = stats
        self._tolerance = tolerance
        self._strategy = strategy

    @property
    def columns(self) -> SegmentColumns:
        if self._columns is None:
            self._columns = self._batch.rows(self._begin, self._end)
        return self._columns

    @property
    def stats(self) -> SplineStats:
        return self._stats

    @property
    def tolerance(self) -> float:
        return self._tolerance

    @property
    def strategy(self) -> str:
        return self._strategy

    @property
    def segments(self) -> tuple[Segment, ...]:
        return tuple(self.columns.segment(i) for i in range(len(self)))

    def __len__(self) -> int:
        return self._end - self._begin

    def __reduce__(self) -> tuple[type[ArcSpline], tuple[SegmentColumns, SplineStats, float, str]]:
        # Pickled with its own rows only (copies of the views), not the whole batch.
        return ArcSpline, (self.columns, self.stats, self.tolerance, self.strategy)

    def __repr__(self) -> str:
        return (
            f"ArcSpline({len(self)} segments, stats={self.stats!r}, "
            f"tolerance={self.tolerance!r}, strategy={self.strategy!r})"
        )
