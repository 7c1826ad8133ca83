"""The pure geometry core: standard library, numpy and its own compiled kernels; no web
imports.

Conventions, stated once: points are ``(..., 2)`` float64 arrays or :class:`Point`; angles
are radians unless the name ends in ``_deg``; anticlockwise is positive (signed sweeps,
signed curvature); ``u`` is a curve's parameter in ``[0, 1]``. The method is Walton & Meek
(1996), restated with every formula the code uses in ``docs/method.md``; section numbers (§)
in docstrings refer to it.

Layout: ``curves/`` (curve types, path segments, pieces and their cuts), ``fit/``
(strategies, compiled), ``maths/`` (roots, polynomials, quadrature), ``deviation`` (the
certificate), ``measure`` (pieces against lines and circles), ``spline.py`` (results),
``segment_table.py``, ``paths.py`` and ``path_spline.py`` (whole paths: their input
table, their approximation, its result), ``limits.py``, ``errors.py``, ``approximate.py``
(the entry points).
"""

from .approximate import approximate, approximate_many
from .curves import Curve, CurveSpec, Spiral, SpiralFromControlPoints, SpiralFromParameters
from .curves.segments import CircularArc, Cubic, EllipticalArc, Line, Path, Quadratic, Subpath
from .errors import GeometryError
from .fit import STRATEGIES, StrategyName
from .limits import DEFAULT_LIMITS, Limits, min_tolerance
from .path_spline import PathSpline, SubpathSpline
from .paths import approximate_path
from .spline import (
    COLUMN,
    ArcSegment,
    ArcSpline,
    LineSegment,
    Point,
    Segment,
    SegmentColumns,
    SplineStats,
)

#: The strategy names (a registry's keys), for messages and schemas.
STRATEGY_NAMES: tuple[str, ...] = tuple(STRATEGIES)

__all__ = [
    "COLUMN",
    "DEFAULT_LIMITS",
    "STRATEGIES",
    "STRATEGY_NAMES",
    "ArcSegment",
    "ArcSpline",
    "CircularArc",
    "Cubic",
    "Curve",
    "CurveSpec",
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
    "SpiralFromControlPoints",
    "SpiralFromParameters",
    "SplineStats",
    "StrategyName",
    "Subpath",
    "SubpathSpline",
    "approximate",
    "approximate_many",
    "approximate_path",
    "min_tolerance",
]
