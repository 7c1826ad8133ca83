"""Value types of the core: points, segments, statistics and the arc spline itself.

An arc spline is stored by columns (``SegmentColumns``: one numpy array per field, one row
per segment) so that a batch of thousands of spirals never builds a Python object per arc;
``ArcSpline.segments`` gives the friendly per-segment view on demand.
"""

from __future__ import annotations

from collections.abc import Sequence
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


#: One segment's fields as plain Python values, in the order of :class:`SegmentColumns`' fields
#: (``is_arc``, ``start``, ``end``, ``center``, ``radius``, ``start_angle_rad``, ``sweep_rad``,
#: ``length``, ``u_start``, ``u_end``, ``max_deviation``, ``u_at_max_deviation``; points as
#: ``[x, y]`` lists): what a JSON encoder takes as it is, with no numpy scalar or per-segment
#: object in between. A plain tuple, not a named one: a batch makes thousands, and a named
#: tuple costs several times as much to make. The lists belong to the spline: read them, do
#: not change them.
SegmentValues = tuple[
    bool,
    list[float],
    list[float],
    list[float],
    float,
    float,
    float,
    float,
    float,
    float,
    float,
    float,
]


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

    @classmethod
    def from_values(cls, values: Sequence[SegmentValues]) -> SegmentColumns:
        """The columns of these rows (the inverse of :meth:`values`)."""
        if not values:
            points = (np.empty((0, 2)) for _ in range(3))
            return cls(np.empty(0, dtype=bool), *points, *(np.empty(0) for _ in range(8)))
        c = list(zip(*values, strict=True))
        return cls(np.array(c[0], dtype=bool), *map(np.array, c[1:]))

    def values(self) -> list[SegmentValues]:
        """Every row as plain Python values: one ``tolist`` per column, not per value."""
        return list(
            zip(
                self.is_arc.tolist(),
                self.start.tolist(),
                self.end.tolist(),
                self.center.tolist(),
                self.radius.tolist(),
                self.start_angle_rad.tolist(),
                self.sweep_rad.tolist(),
                self.length.tolist(),
                self.u_start.tolist(),
                self.u_end.tolist(),
                self.max_deviation.tolist(),
                self.u_at_max_deviation.tolist(),
                strict=True,
            )
        )

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
    batch of thousands makes no per-spline arrays that nobody reads. A spline assembled in
    floats holds plain ``SegmentValues`` instead, and makes its columns on first use.
    """

    __slots__ = (
        "_batch",
        "_begin",
        "_columns",
        "_end",
        "_stats",
        "_strategy",
        "_tolerance",
        "_values",
    )

    def __init__(
        self,
        columns: SegmentColumns | list[SegmentValues],
        stats: SplineStats,
        tolerance: float,
        strategy: str,
        rows: tuple[int, int] | None = None,
    ) -> None:
        """The spline of ``columns`` (or of its rows ``rows = (begin, end)``), or of rows of
        plain values."""
        self._columns: SegmentColumns | None = None
        self._values: list[SegmentValues] | None = None
        self._batch: SegmentColumns | None = None
        if rows is not None:  # a batch's spline: the common case, thousands at a time
            assert not isinstance(columns, list)
            self._batch = columns
            self._begin, self._end = rows
        else:
            if isinstance(columns, list):
                self._values = columns
            else:
                self._batch = self._columns = columns
            self._begin, self._end = 0, len(columns)
        self._stats = stats
        self._tolerance = tolerance
        self._strategy = strategy

    @property
    def columns(self) -> SegmentColumns:
        if self._columns is None:
            if self._batch is None:
                assert self._values is not None
                self._columns = SegmentColumns.from_values(self._values)
            else:
                self._columns = self._batch.rows(self._begin, self._end)
        return self._columns

    def u_end(self, i: int) -> float:
        """The spiral parameter where segment ``i`` ends, read where it is kept (no columns
        or values made for one number)."""
        if self._values is not None:
            return self._values[i][9]
        assert self._batch is not None
        return float(self._batch.u_end[self._begin + i])

    def values(self) -> list[SegmentValues]:
        """The segments as plain Python values (``SegmentValues``), in order."""
        if self._values is not None:
            return self._values
        # Not kept: a batch's splines would hold millions of Python objects for the
        # collector to walk, where the encoder needs each list once.
        return self.columns.values()

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
