"""Drawings: SVG and DXF documents read into subpaths in millimetres (docs/drawings.md)."""

from .affine import Affine, SingularMapError, transform_segment, transform_subpath
from .model import (
    MM_PER_UNIT,
    DocumentError,
    DocumentLimits,
    Drawing,
    DrawingWarning,
    Element,
)

__all__ = [
    "MM_PER_UNIT",
    "Affine",
    "DocumentError",
    "DocumentLimits",
    "Drawing",
    "DrawingWarning",
    "Element",
    "SingularMapError",
    "transform_segment",
    "transform_subpath",
]
