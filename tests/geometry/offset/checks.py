"""Checks on offset results that do not use the code under test: exact chaining, arcs whose
stored ends agree with their centre, radius and angles (the core's own input check), and
the oracle's two-way distance measure (tests/support/offset_oracle.py)."""

from __future__ import annotations

import itertools
import math
from collections.abc import Sequence

from arcspline.geometry.curves.segments import CircularArc, Line, Subpath
from arcspline.geometry.offset import Element
from arcspline.geometry.segment_table import check, segment_table
from tests.support import offset_oracle as oracle


def assert_exact(subpaths: Sequence[Subpath]) -> None:
    """Lines and arcs only, chained bit for bit (a closed loop's last end its first start),
    no zero-length element, 0 < |sweep| < 2π, and the core's input check passes."""
    for sub in subpaths:
        segments = sub.segments
        assert segments
        for a, b in itertools.pairwise(segments):
            assert a.end == b.start
        if sub.closed:
            assert segments[-1].end == segments[0].start
        for s in segments:
            assert isinstance(s, Line | CircularArc)
            assert s.start != s.end or isinstance(s, CircularArc)
            if isinstance(s, CircularArc):
                assert 0.0 < abs(s.sweep_rad) < 2.0 * math.pi
                assert s.radius > 0.0
    owner = [(i, j) for i, sub in enumerate(subpaths) for j in range(len(sub.segments))]
    if owner:
        check(segment_table([s for sub in subpaths for s in sub.segments]), owner)


def measure(
    contours: Sequence[Sequence[Element]],
    subpaths: Sequence[Subpath],
    distance: float,
    side: oracle.SideSpec,
) -> oracle.OffsetReport:
    return oracle.check_offset(
        [oracle.from_core(c) for c in contours],
        [oracle.from_core(s.segments) for s in subpaths],
        distance,
        side,
    )


def assert_offset(
    contours: Sequence[Sequence[Element]],
    subpaths: Sequence[Subpath],
    distance: float,
    side: oracle.SideSpec,
    tolerance: float = 1e-7,
) -> oracle.OffsetReport:
    """The tool path keeps ``distance`` clear of every contour and reaches every reachable
    contour point (oracle), within ``tolerance``."""
    report = measure(contours, subpaths, distance, side)
    assert report.ok(distance, tolerance), report.describe()
    return report
