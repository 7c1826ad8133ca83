"""Shared helpers of the SVG reader's tests: the small trap files (tests/data/svg/), segment
ends rounded for comparison with hand values, and arcs sampled from their own parameters."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from arcspline.drawings.model import Drawing
from arcspline.drawings.svg import read_svg
from arcspline.geometry.curves.segments import CircularArc, EllipticalArc, Segment
from arcspline.geometry.segment_table import check, segment_table

DATA = Path(__file__).resolve().parents[1] / "data" / "svg"
SVG_OPEN = '<svg xmlns="http://www.w3.org/2000/svg" width="10" height="10">'


def read(name: str, **options: object) -> Drawing:
    """The data file ``name`` read, with the accounting checked."""
    drawing = read_svg((DATA / name).read_bytes(), **options)  # type: ignore[arg-type]
    assert drawing.elements_in == len(drawing.elements) + drawing.skipped
    return drawing


def ends(drawing: Drawing) -> list[tuple[tuple[float, float], ...]]:
    """Each element's segment ends, rounded to 1e-12 mm (the hand values are decimal)."""
    return [
        tuple(
            (round(p[0], 12) + 0.0, round(p[1], 12) + 0.0)
            for s in e.subpath.segments
            for p in (s.start, s.end)
        )
        for e in drawing.elements
    ]


def sample(segment: CircularArc | EllipticalArc, n: int = 64) -> np.ndarray:
    """Points of an arc from its own centre, radii, rotation and angles."""
    rx, ry, rot = (
        (segment.radius, segment.radius, 0.0)
        if isinstance(segment, CircularArc)
        else (segment.rx, segment.ry, segment.rotation_rad)
    )
    phi = segment.start_angle_rad + segment.sweep_rad * np.linspace(0.0, 1.0, n)
    ex, ey = rx * np.cos(phi), ry * np.sin(phi)
    cx, cy = segment.center
    return np.column_stack(
        [cx + math.cos(rot) * ex - math.sin(rot) * ey, cy + math.sin(rot) * ex + math.cos(rot) * ey]
    )


def assert_checked(segments: list[Segment]) -> None:
    """The segments pass the segment table's checks (arcs consistent, ends joined)."""
    check(segment_table(segments), [(0, j) for j in range(len(segments))])
