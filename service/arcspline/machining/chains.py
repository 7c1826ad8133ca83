"""Chains of lines and circular arcs, cut and turned exactly (docs/machining.md §2).

A chain is a sequence of :class:`Line`/:class:`CircularArc` whose each ``start`` is the
previous ``end`` bit for bit; a closed chain's last ``end`` is its first ``start``. Every
operation here keeps that: a cut point is computed once and used as the end of one piece and
the start of the next; an arc is cut at an angle (its pieces keep its centre and radius), a
line at a point; reversing swaps the ends and negates an arc's sweep.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

from arcspline.geometry import CircularArc, Line
from arcspline.geometry.offset.table import length as length
from arcspline.geometry.offset.table import point_at as point_at

Element = Line | CircularArc
Chain = tuple[Element, ...]


def chain_length(chain: Sequence[Element]) -> float:
    return math.fsum(length(e) for e in chain)


def tangent_at(element: Element, t: float) -> tuple[float, float]:
    """The unit direction of travel at fraction ``t``."""
    if isinstance(element, Line):
        (x0, y0), (x1, y1) = element.start, element.end
        d = math.hypot(x1 - x0, y1 - y0)
        return ((x1 - x0) / d, (y1 - y0) / d)
    angle = element.start_angle_rad + t * element.sweep_rad
    turn = 1.0 if element.sweep_rad > 0.0 else -1.0
    return (-turn * math.sin(angle), turn * math.cos(angle))


def split(element: Element, t: float) -> tuple[Element, Element]:
    """``element`` cut at fraction ``t`` (``0 < t < 1``): a line at its point, an arc at the
    angle ``start_angle + t·sweep``; the two pieces share the cut point bit for bit."""
    cut = point_at(element, t)
    if isinstance(element, Line):
        return Line(element.start, cut), Line(cut, element.end)
    first = element.sweep_rad * t
    return (
        CircularArc(
            element.start, cut, element.center, element.radius, element.start_angle_rad, first
        ),
        CircularArc(
            cut,
            element.end,
            element.center,
            element.radius,
            element.start_angle_rad + first,
            element.sweep_rad - first,
        ),
    )


def reversed_element(element: Element) -> Element:
    """The same points travelled the other way."""
    if isinstance(element, Line):
        return Line(element.end, element.start)
    return CircularArc(
        element.end,
        element.start,
        element.center,
        element.radius,
        element.start_angle_rad + element.sweep_rad,
        -element.sweep_rad,
    )


def reversed_chain(chain: Sequence[Element]) -> Chain:
    """The chain travelled backwards (still chained bit for bit)."""
    return tuple(reversed_element(e) for e in reversed(chain))


def rotated(chain: Sequence[Element], first: int) -> Chain:
    """A closed chain begun at its element ``first``."""
    return (*chain[first:], *chain[:first])


def split_at_lengths(
    chain: Sequence[Element], positions: Sequence[float], snap: float
) -> tuple[Chain, list[int]]:
    """``chain`` cut at each arc-length position (ascending, from its start), and for each
    position the index of the element that starts there in the result. A position within
    ``snap`` of a joint uses the joint, so no piece shorter than ``snap`` is made."""
    out: list[Element] = []
    starts: list[int] = []
    pending = list(positions)
    travelled = 0.0
    for element in chain:
        size = length(element)
        rest = element
        begun = travelled
        while pending and pending[0] <= begun + size + snap:
            at = pending.pop(0) - begun
            if at <= snap:
                starts.append(len(out))
                continue
            if at >= size - snap:
                pending.insert(0, begun + size)  # the joint after this element
                break
            fraction = at / size
            head, rest = split(rest, fraction)
            out.append(head)
            starts.append(len(out))
            # What is left is measured from the cut on.
            begun += length(head)
            size = length(rest)
        out.append(rest)
        travelled += length(element)
    starts += [len(out)] * len(pending)
    return tuple(out), starts
