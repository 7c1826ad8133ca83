"""Holding tabs: where the tool rises over the material it leaves (docs/machining.md §6).

``count`` tabs are spaced evenly along a contour's tool path (its lead arcs excluded): tab
``k`` is centred at ``(k + ½)·L/count`` from the start, so none sits where the leads join.
A tab leaves ``width`` of material standing; the tool centre passes at the tool radius from
the material on either side of it, so it rises over ``width + tool diameter`` of its path.
The path is cut exactly at both ends of every tab (:func:`.chains.split_at_lengths`) and
those pieces are marked, for the program to lift the tool over them on the passes below the
tab top.
"""

from __future__ import annotations

from collections.abc import Sequence

from .chains import Chain, Element, chain_length, split_at_lengths
from .options import Tabs


def tab_span(tabs: Tabs, tool_diameter: float) -> float:
    """How much of the tool path one tab takes: its width plus the tool diameter."""
    return float(tabs.width) + float(tool_diameter)


def fits(loop_length: float, tabs: Tabs, tool_diameter: float) -> bool:
    """Whether ``tabs.count`` tabs fit along a path of ``loop_length`` with cut between them."""
    return tabs.count * tab_span(tabs, tool_diameter) < loop_length


def with_tabs(
    loop: Sequence[Element], tabs: Tabs, tool_diameter: float, snap: float
) -> tuple[Chain, tuple[bool, ...]]:
    """``loop`` cut at both ends of every tab, and which of its pieces lie on a tab (the
    caller checks :func:`fits` first)."""
    total = chain_length(loop)
    pitch = total / tabs.count
    half = 0.5 * tab_span(tabs, tool_diameter)
    positions = []
    for k in range(tabs.count):
        centre = (k + 0.5) * pitch
        positions += [centre - half, centre + half]
    pieces, starts = split_at_lengths(loop, positions, snap)
    on_tab = [False] * len(pieces)
    for k in range(tabs.count):
        for i in range(starts[2 * k], starts[2 * k + 1]):
            on_tab[i] = True
    return pieces, tuple(on_tab)
