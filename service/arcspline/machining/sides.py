"""Which side of each contour the tool cuts, and which way it travels (docs/machining.md §4).

``auto`` cuts a closed contour outside when an even number of closed contours surround it (a
part's outline) and inside when an odd number do (a hole in it; an island in a hole is a part
again); an open contour has no inside and is cut on its line.

With the spindle turning clockwise (``M3``), climb milling keeps the tool on the *left* of its
travel (the cutting edge meets the material at its thickest chip first): an outside contour
then runs clockwise about the part, an inside contour anticlockwise. Conventional milling is
the reverse. A contour cut on its line runs as an outside one would (closed) or as drawn
(open).
"""

from __future__ import annotations

from typing import Literal, NamedTuple

from arcspline.geometry import GeometryError

from .options import Cut, Direction

Side = Literal["outside", "inside", "on"]


class CutPlan(NamedTuple):
    """How one output subpath cuts: its ``source`` subpath, the side of it the tool is on,
    the milling ``direction``, the source's nesting ``depth`` and, for a closed one, whether
    the tool path runs ``clockwise`` (``None`` for an open contour)."""

    source: int
    cut: Side
    direction: Direction
    depth: int
    clockwise: bool | None


def cut_side(cut: Cut, closed: bool, depth: int, index: int) -> Side:
    """The side to cut contour ``index`` on; an open contour asked for a side is refused."""
    if not closed:
        if cut in ("inside", "outside"):
            raise GeometryError(
                f"path.subpaths[{index}]",
                f"is open, so it has no {cut}: cut it 'on' its line, or close it",
            )
        return "on"
    if cut == "auto":
        return "outside" if depth % 2 == 0 else "inside"
    return cut


def tool_on_left(direction: Direction) -> bool:
    """Climb milling with a clockwise spindle keeps the tool left of its travel."""
    return direction == "climb"


def runs_clockwise(side: Side, direction: Direction) -> bool:
    """The travel sense of a closed contour's tool path: left of travel is outside for a
    clockwise loop, inside for an anticlockwise one."""
    outside = side != "inside"
    return outside == tool_on_left(direction)
