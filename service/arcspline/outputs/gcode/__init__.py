"""An arc spline as a G-code program that real controllers accept (RS-274/NGC, XY plane).

The program states its modes (``G17 G20|G21 G90 G91.1 G94 F…``), moves rapidly to the
spiral's start (retracting to ``safe_z`` and plunging to ``cut_z`` first, for a 2.5-D cut),
cuts one block per segment of the arc spline and ends with ``M2``.

Rounding, which is where controllers reject programs, follows fixed rules:

* Every coordinate is a whole number of units in the last place, ``q = 10^-decimals``. The
  joints between segments are rounded first, once each, so consecutive blocks meet exactly
  and the path starts and ends at the spiral's rounded end points.
* An arc's centre is chosen for the *rounded* end points: on their perpendicular bisector
  (where start and end radii agree), the point whose circle fits the true arc best
  (minimax over a few points of it, starting from the bisector point nearest the true
  centre); then, of the lattice points within ``q`` of it, one whose start and end radii
  agree within ``q·min(1, √2·sin(|sweep|/2))`` and whose circle fits best. ``I``/``J`` is
  that point minus the rounded start. Every block repeats its G word and carries both ``X``
  and ``Y`` and both ``I`` and ``J`` (or ``R``).
* An arc a controller could take for a full circle is cut as ``G1``: its rounded ends
  coincide, its sweep is below :data:`MIN_SWEEP_RAD`, or its radius is below
  :data:`MIN_RADIUS_ULPS` units in the last place. An arc the precision cannot tell from its
  chord (sagitta below ``q/2``) is cut as ``G1`` too, unless that line would leave the
  bound below while the arc keeps it. ``min_arc_length`` and ``max_radius`` turn further
  arcs into lines, but only where the chord stays within the tolerance of the spiral
  (measured exactly by the curve, ``Curve.line_deviations``).
* ``R`` form uses ``R`` only away from half circles (:data:`HALF_CIRCLE_MARGIN_DEG`), negative
  beyond 180°; other arcs keep ``I``/``J`` (``G91.1`` is in every preamble for that reason).

Every block is then measured against its piece of the spiral, exactly (the extrema of the
distance are roots of a polynomial in the spiral parameter), and takes the first of its
candidate forms (line or arc, as above; ``R``, then ``I``/``J``, then the chord) whose
read-back path stays within ``tolerance + q`` of the spiral. When none does, or the spiral's
coordinates exceed :data:`MAX_COORDINATE`, :class:`GcodeError` says so (``decimals`` too few
for the tolerance, or ``spiral`` too large). No number that is not finite reaches the text:
every number is formatted from an integer count of units in the last place.

Modules: :mod:`.options` (the options and :class:`GcodeError`), :mod:`.lattice` (rounding to
units in the last place, fixed-point text), :mod:`.arcs` (the words of one arc), :mod:`.plan`
(the choice and exact check of every block), :mod:`.program` (the text).
"""

from .arcs import HALF_CIRCLE_MARGIN_DEG, MAX_ARC_WORD, ArcWords, encode_arc
from .options import (
    ARC_FORMATS,
    DEFAULT_DECIMALS,
    MAX_COORDINATE,
    MAX_DECIMALS,
    MIN_DECIMALS,
    UNITS,
    ArcFormat,
    GcodeError,
    GcodeOptions,
    Units,
)
from .plan import MIN_RADIUS_ULPS, MIN_SWEEP_RAD
from .program import MAX_LINE_NUMBER, WRITER, write_program

__all__ = [
    "ARC_FORMATS",
    "DEFAULT_DECIMALS",
    "HALF_CIRCLE_MARGIN_DEG",
    "MAX_ARC_WORD",
    "MAX_COORDINATE",
    "MAX_DECIMALS",
    "MAX_LINE_NUMBER",
    "MIN_DECIMALS",
    "MIN_RADIUS_ULPS",
    "MIN_SWEEP_RAD",
    "UNITS",
    "WRITER",
    "ArcFormat",
    "ArcWords",
    "GcodeError",
    "GcodeOptions",
    "Units",
    "encode_arc",
    "write_program",
]
