"""Exact offsets of chains of lines and circular arcs (docs/offsets.md): the tool-centre
paths of a fitted drawing. Points ``(x, y)``, lengths in the drawing's unit, angles in
radians anticlockwise; "left"/"right" seen along the direction of travel."""

from .chain import crossings, elements_of, signed_area
from .distance import chain_distance, segment_distance
from .path import Contours, OffsetPath, contours_of, offset_path
from .subpath import offset_subpath
from .types import Element, Join, OffsetNote, OffsetOptions, Side, SubpathOffset

__all__ = [
    "Contours",
    "Element",
    "Join",
    "OffsetNote",
    "OffsetOptions",
    "OffsetPath",
    "Side",
    "SubpathOffset",
    "chain_distance",
    "contours_of",
    "crossings",
    "elements_of",
    "offset_path",
    "offset_subpath",
    "segment_distance",
    "signed_area",
]
