"""Tabs: evenly spaced spans of width + tool diameter, cut exactly."""

from __future__ import annotations

import math

import pytest

from arcspline.machining import Tabs
from arcspline.machining.chains import chain_length, length
from arcspline.machining.tabs import fits, tab_span, with_tabs

from .shapes import circle, rectangle


def test_tabs_sit_evenly_and_take_width_plus_diameter() -> None:
    loop = rectangle(0, 0, 40, 20)  # 120 long
    tabs = Tabs(3, 4.0, 1.0)
    assert tab_span(tabs, 6.0) == 10.0
    assert fits(120.0, tabs, 6.0)
    pieces, on_tab = with_tabs(loop, tabs, 6.0, 1e-9)
    assert pieces[0].start == loop[0].start
    assert pieces[-1].end == loop[-1].end
    runs, travelled, start = [], 0.0, None
    for piece, tab in zip(pieces, on_tab, strict=True):
        if tab and start is None:
            start = travelled
        if not tab and start is not None:
            runs.append((start, travelled))
            start = None
        travelled += math.dist(piece.start, piece.end)
    assert len(runs) == 3
    for k, (a, b) in enumerate(runs):
        assert b - a == pytest.approx(10.0)
        assert 0.5 * (a + b) == pytest.approx((k + 0.5) * 40.0)


def test_tabs_on_arcs_cut_at_angles() -> None:
    loop = circle(0.0, 0.0, 10.0)
    tabs = Tabs(4, 2.0, 1.0)
    pieces, on_tab = with_tabs(loop, tabs, 3.0, 1e-9)
    assert sum(on_tab) >= 4
    total = sum(length(p) for p, t in zip(pieces, on_tab, strict=True) if t)
    assert total == pytest.approx(4 * 5.0)
    assert chain_length(pieces) == pytest.approx(2 * math.pi * 10.0)


def test_too_many_tabs_do_not_fit() -> None:
    assert not fits(30.0, Tabs(3, 4.0, 1.0), 6.0)
