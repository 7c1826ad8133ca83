"""Drawings: SVG and DXF documents read into subpaths in millimetres, joined, ordered and
approximated as one certified path (docs/drawings.md)::

    >>> from arcspline.drawings import DrawingOptions, approximate_drawing, read_svg
    >>> from arcspline.geometry import DEFAULT_LIMITS
    >>> drawing = read_svg(
    ...     '<svg xmlns="http://www.w3.org/2000/svg" width="40mm" height="30mm" '
    ...     'viewBox="0 0 40 30"><circle cx="20" cy="15" r="5"/><text>label</text></svg>')
    >>> len(drawing.elements), drawing.warnings[0].element
    (1, 'text (line 1)')
    >>> result = approximate_drawing(drawing, DrawingOptions(0.01), DEFAULT_LIMITS)
    >>> len(result.toolpaths), result.spline.stats.arc_count
    (1, 2)
"""

from .affine import Affine, SingularMapError, transform_segment, transform_subpath
from .approximate import Budget, DrawingOptions, DrawingResult, approximate_drawing
from .document import DocumentSpec
from .dxf import read_dxf
from .join import Toolpath, join
from .model import (
    MM_PER_UNIT,
    DocumentError,
    DocumentLimits,
    Drawing,
    DrawingWarning,
    Element,
)
from .order import order
from .svg import read_svg
from .tidy import tidy

__all__ = [
    "MM_PER_UNIT",
    "Affine",
    "Budget",
    "DocumentError",
    "DocumentLimits",
    "DocumentSpec",
    "Drawing",
    "DrawingOptions",
    "DrawingResult",
    "DrawingWarning",
    "Element",
    "SingularMapError",
    "Toolpath",
    "approximate_drawing",
    "join",
    "order",
    "read_dxf",
    "read_svg",
    "tidy",
    "transform_segment",
    "transform_subpath",
]
