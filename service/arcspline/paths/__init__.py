"""Path input: SVG path data and the explicit JSON form, as specs a worker builds into a
:class:`~arcspline.geometry.curves.segments.Path` (and, later, documents)."""

from .specs import PathFromData, PathFromSegments
from .svg_data import parse_path_data

#: A path as a request gives it.
PathSpec = PathFromData | PathFromSegments

__all__ = ["PathFromData", "PathFromSegments", "PathSpec", "parse_path_data"]
