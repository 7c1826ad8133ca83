"""Machining programs: a drawing's contours cut with an end mill (docs/machining.md).

Pure: the standard library, numpy, ``arcspline.geometry`` and ``arcspline.outputs``. Lengths
are in the drawing's unit; angles in radians, anticlockwise positive; the spindle turns
clockwise (``M3``).

Modules, one concept each: :mod:`.options` (the options, validated), :mod:`.chains` (lines
and arcs cut and turned exactly), :mod:`.nesting` (which contour lies inside which),
:mod:`.sides` (cut side and direction), :mod:`.leads` (start points and lead arcs),
:mod:`.tabs`, :mod:`.contour` (one contour's tool paths), :mod:`.order` (cutting order),
:mod:`.plan` (:func:`machine`) and
:mod:`.program` (:func:`write_machining`).
"""

from .options import Compensation, Cut, Direction, Entry, MachiningOptions, Tabs, check
from .plan import Machined, Role, machine
from .program import write_machining
from .sides import CutPlan

__all__ = [
    "Compensation",
    "Cut",
    "CutPlan",
    "Direction",
    "Entry",
    "Machined",
    "MachiningOptions",
    "Role",
    "Tabs",
    "check",
    "machine",
    "write_machining",
]
