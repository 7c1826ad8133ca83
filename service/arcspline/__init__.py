"""arcspline: arc splines for CNC tool paths — circular arcs (and, where an arc would be
numerically flat, lines) that follow a curve within a tolerance, with certified deviations.

The Python API (the HTTP service, the benchmarks and the tests use the same)::

    >>> import arcspline
    >>> spiral = arcspline.Spiral.from_parameters(
    ...     start=(1.5, 3.0), start_tangent=(1.0, 0.0), turn_angle_deg=51.34,
    ...     end_curvature=0.41574)
    >>> spline = arcspline.approximate(spiral, 0.001)
    >>> len(spline), spline.stats.arc_count
    (12, 12)
    >>> spline.stats.max_deviation <= 0.001
    True
    >>> len(arcspline.approximate(spiral, 0.001, strategy="fewest-arcs"))
    7
    >>> path = arcspline.parse_path_data("M 0 0 C 10 0 20 10 30 30 L 40 30 A 5 5 0 0 1 50 30")
    >>> result = arcspline.approximate_path(path, 0.01)
    >>> len(result.subpaths), result.segment_count, result.stats.line_count
    (1, 12, 1)
    >>> result.stats.max_deviation <= 0.01
    True

* **Curves** — :class:`Spiral` (Walton & Meek's cubic Bézier spiral) by its five parameters
  (:meth:`Spiral.from_parameters`) or its four control points
  (:meth:`Spiral.from_control_points`); both validate and raise :class:`GeometryError`.
* **Paths** — :class:`Path` of :class:`Subpath` of segments (:class:`Line`,
  :class:`Quadratic`, :class:`Cubic`, :class:`CircularArc`, :class:`EllipticalArc`), or SVG
  path data through :func:`parse_path_data`; :func:`approximate_path` gives a
  :class:`PathSpline`: one :class:`ArcSpline` per subpath, with each segment's source.
* **Approximation** — :func:`approximate` (one curve; raises :class:`GeometryError`) and
  :func:`approximate_many` (many in one compiled loop; each failure in its place), with a
  strategy from :data:`STRATEGIES` (``"subdivide"``: the paper's method; ``"fewest-arcs"``)
  and :class:`Limits` (segment cap, smallest relative tolerance; :func:`min_tolerance`).
* **Results** — :class:`ArcSpline`: ``segments`` (:class:`ArcSegment`, :class:`LineSegment`),
  ``columns`` (:class:`SegmentColumns`, numpy views), ``table`` (one row per segment,
  :data:`COLUMN`), ``stats`` (:class:`SplineStats`), ``tolerance`` and ``strategy``.
* **Drawings** — ``arcspline.drawings``: SVG and DXF documents read exactly
  (``read_svg``, ``read_dxf``), joined into toolpaths, ordered and approximated within the
  tolerance of the drawing as given (``approximate_drawing``); imported on its own, as it
  loads the document libraries.
* **Outputs** — ``arcspline.outputs``: a G-code program (``outputs.gcode.write_program``), an
  SVG picture (``outputs.svg.render_svg``), DXF and SVG documents (``outputs.dxf``,
  ``outputs.svg_document``) and a drawing's preview (``outputs.drawing_preview``).

Conventions: points are ``(x, y)``; angles in radians unless a name ends in ``_deg``;
anticlockwise is positive; ``u`` is the curve's parameter in ``[0, 1]``. The method, with
every formula the code uses, is in ``docs/method.md``. ``python -m arcspline`` starts the
HTTP service.
"""

from importlib.metadata import PackageNotFoundError, version

from .geometry import (
    COLUMN,
    DEFAULT_LIMITS,
    STRATEGIES,
    STRATEGY_NAMES,
    ArcSegment,
    ArcSpline,
    CircularArc,
    Cubic,
    EllipticalArc,
    GeometryError,
    Limits,
    Line,
    LineSegment,
    Path,
    PathSpline,
    Point,
    Quadratic,
    Segment,
    SegmentColumns,
    Spiral,
    SplineStats,
    Subpath,
    approximate,
    approximate_many,
    approximate_path,
    min_tolerance,
)

try:
    __version__ = version("arcspline")
except PackageNotFoundError:  # pragma: no cover - running from a source tree
    __version__ = "0+unknown"

from .paths import parse_path_data

__all__ = [
    "COLUMN",
    "DEFAULT_LIMITS",
    "STRATEGIES",
    "STRATEGY_NAMES",
    "ArcSegment",
    "ArcSpline",
    "CircularArc",
    "Cubic",
    "EllipticalArc",
    "GeometryError",
    "Limits",
    "Line",
    "LineSegment",
    "Path",
    "PathSpline",
    "Point",
    "Quadratic",
    "Segment",
    "SegmentColumns",
    "Spiral",
    "SplineStats",
    "Subpath",
    "__version__",
    "approximate",
    "approximate_many",
    "approximate_path",
    "min_tolerance",
    "parse_path_data",
]
