"""The pure geometry core: standard library and numpy only, no web imports.

Conventions, stated once: points and vectors are ``(..., 2)`` float64 arrays or
:class:`Point`; angles are radians unless the name ends in ``_deg``; anticlockwise is
positive (signed sweeps, signed curvature); ``u`` is the spiral's Bézier parameter in
``[0, 1]``. The method is Walton & Meek (1996), restated in
``shared/spec/walton-meek-1996.md``; section numbers (§) in docstrings refer to it.
"""

from .approximate import (
    DEFAULT_LIMITS,
    STRATEGIES,
    Limits,
    Strategy,
    approximate,
    approximate_many,
    min_tolerance,
)
from .errors import GeometryError
from .spiral import Spiral
from .types import ArcSegment, ArcSpline, LineSegment, Point, Segment, SegmentColumns, SplineStats

__all__ = [
    "DEFAULT_LIMITS",
    "STRATEGIES",
    "ArcSegment",
    "ArcSpline",
    "GeometryError",
    "Limits",
    "LineSegment",
    "Point",
    "Segment",
    "SegmentColumns",
    "Spiral",
    "SplineStats",
    "Strategy",
    "approximate",
    "approximate_many",
    "min_tolerance",
]
