"""Putting chains of lines and arcs together exactly: each element starting bit for bit
where the one before ends, tiny elements merged away (docs/offsets.md §5)."""

from __future__ import annotations

import math
from collections.abc import Sequence

from ..curves.segments import CircularArc, Line
from ..spline import Point
from .shapes import movable
from .table import length
from .types import Element


def _set_start(e: Element, point: Point) -> Element:
    return e._replace(start=point) if isinstance(e, CircularArc) else Line(point, e.end)


def _set_end(e: Element, point: Point) -> Element:
    return e._replace(end=point) if isinstance(e, CircularArc) else Line(e.start, point)


def attach(chain: list[Element], nxt: Element) -> None:
    """Append ``nxt`` so that it starts where ``chain`` ends, exactly: the end that may move
    (a line's, or an arc's by a hair) moves; otherwise a connecting line bridges the gap."""
    if not chain:
        chain.append(nxt)
        return
    prev = chain[-1]
    if prev.end == nxt.start:
        chain.append(nxt)
        return
    gap = math.dist(prev.end, nxt.start)
    if movable(nxt, gap):
        chain.append(_set_start(nxt, Point(*prev.end)))
    elif movable(prev, gap):
        chain[-1] = _set_end(prev, Point(*nxt.start))
        chain.append(nxt)
    else:
        chain.extend([Line(Point(*prev.end), Point(*nxt.start)), nxt])


def close(chain: list[Element]) -> None:
    """Make the chain's last end its first start exactly."""
    first, last = chain[0], chain[-1]
    if last.end == first.start:
        return
    gap = math.dist(last.end, first.start)
    if movable(last, gap):
        chain[-1] = _set_end(last, Point(*first.start))
    elif movable(first, gap):
        chain[0] = _set_start(first, Point(*last.end))
    else:
        chain.append(Line(Point(*last.end), Point(*first.start)))


def without_tiny(chain: Sequence[Element], tiny: float, closed: bool) -> list[Element]:
    """The chain with elements shorter than ``tiny`` merged into their neighbours where an
    end may move that far (module docstring), chained exactly again."""
    out: list[Element] = []
    for e in chain:
        if length(e) < tiny and out and _absorbable(out[-1], e):
            # drop e: the next element attaches to the end before it
            continue
        attach(out, e)
    if closed and len(out) > 1:
        if length(out[-1]) < tiny and movable(out[-2], length(out[-1])):
            out.pop()
        close(out)
    return [e for e in out if e.start != e.end] if len(out) > 1 else out


def _absorbable(prev: Element, e: Element) -> bool:
    return movable(prev, length(e) + math.dist(prev.end, e.start))
