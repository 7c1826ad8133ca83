"""One arc on the lattice (``encode_arc``).

Arcs of any sweep are built here from a centre, a radius and two angles, rounded as the
writer rounds end points, encoded, and read back by the independent reader.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from arcspline.outputs.gcode import HALF_CIRCLE_MARGIN_DEG, ArcWords, encode_arc
from tests.support import gcode_reader


def _arc(
    centre: tuple[float, float], radius: float, start_deg: float, sweep_deg: float, decimals: int
) -> tuple[tuple[int, int], tuple[int, int]]:
    scale = 10**decimals
    a, b = math.radians(start_deg), math.radians(start_deg + sweep_deg)
    start = (
        round((centre[0] + radius * math.cos(a)) * scale),
        round((centre[1] + radius * math.sin(a)) * scale),
    )
    end = (
        round((centre[0] + radius * math.cos(b)) * scale),
        round((centre[1] + radius * math.sin(b)) * scale),
    )
    return start, end


def _read_back(
    start: tuple[int, int], end: tuple[int, int], words: ArcWords, d: int
) -> gcode_reader.Move:
    def num(k: int) -> str:
        return f"{k / 10**d:.{d}f}"

    tail = (
        f"R{num(words.radius)}"
        if words.radius is not None
        else f"I{num(words.offset[0])} J{num(words.offset[1])}"  # type: ignore[index]
    )
    text = (
        f"G17 G21 G90 G91.1 G94 F100\nG0 X{num(start[0])} Y{num(start[1])}\n"
        f"{'G3' if words.ccw else 'G2'} X{num(end[0])} Y{num(end[1])} {tail}\nM2\n"
    )
    return gcode_reader.read(text).cuts[0]


@pytest.mark.parametrize(
    ("max_sweep_deg", "max_gap_ulps"),
    # Every arc of the method turns by less than 90° (3,000 random arcs: at most 1.0 unit);
    # beyond, the bound is looser.
    [(90.0, 1.05), (170.0, 1.5)],
)
def test_centre_offsets_keep_start_and_end_radii_within_one_unit(
    max_sweep_deg: float, max_gap_ulps: float
) -> None:
    rng = np.random.default_rng(20240611)
    worst = 0.0
    for _ in range(300):
        d = int(rng.integers(3, 7))
        q = 10.0**-d
        centre = tuple(rng.uniform(-500, 500, 2))
        radius = float(10 ** rng.uniform(-1.5, 4))
        sweep = float(rng.choice([-1, 1]) * rng.uniform(0.5, max_sweep_deg))
        start, end = _arc(centre, radius, float(rng.uniform(-180, 180)), sweep, d)
        if start == end:
            continue
        words = encode_arc(start, end, centre, radius, math.radians(sweep), d, "ij")
        move = _read_back(start, end, words, d)
        assert move.r_start is not None
        assert move.r_end is not None
        assert move.sweep_rad is not None
        bound = q * min(1.0, math.sqrt(2) * math.sin(abs(move.sweep_rad) / 2))
        assert abs(move.r_end - move.r_start) <= bound * (1 + 1e-6) + 1e-12 * radius
        assert move.sweep_rad == pytest.approx(math.radians(sweep), abs=1e-3 + 4 * q / radius)
        worst = max(worst, _arc_gap(centre, radius, start, end, move, d) / q)
    # Rounding the end points alone moves the arc by up to √2/2 units.
    assert worst <= max_gap_ulps


def _arc_gap(
    centre: tuple[float, float],
    radius: float,
    start: tuple[int, int],
    end: tuple[int, int],
    move: gcode_reader.Move,
    d: int,
) -> float:
    """Largest distance between the intended arc (through the unrounded ends' angles) and
    the read-back one, both ways, by sampling: each point's distance to the other circle."""
    assert move.centre is not None
    assert move.sweep_rad is not None
    assert move.r_start is not None
    assert move.r_end is not None
    c0, c1 = np.array(centre), np.array(move.centre)
    s = np.array(start) / 10**d
    a1 = math.atan2(s[1] - c1[1], s[0] - c1[0])
    t = np.linspace(0.0, 1.0, 2001)
    ang1 = a1 + t * move.sweep_rad
    r1 = move.r_start + t * (move.r_end - move.r_start)
    read = c1 + r1[:, None] * np.stack([np.cos(ang1), np.sin(ang1)], axis=1)
    a0 = math.atan2(s[1] - c0[1], s[0] - c0[0])
    e = np.array(end) / 10**d
    b0 = math.atan2(e[1] - c0[1], e[0] - c0[0])
    sweep0 = (b0 - a0) % (2 * math.pi) if move.motion == 3 else -((a0 - b0) % (2 * math.pi))
    ang0 = a0 + t * sweep0
    intended = c0 + radius * np.stack([np.cos(ang0), np.sin(ang0)], axis=1)
    to_intended = np.abs(np.hypot(*(read - c0).T) - radius)
    to_read = np.maximum(
        np.abs(np.hypot(*(intended - c1).T) - move.r_start),
        np.abs(np.hypot(*(intended - c1).T) - move.r_end),
    )
    return float(max(to_intended.max(), to_read.max()))


@pytest.mark.parametrize(
    "sweep_deg", [120.0, -150.0, 174.0, 176.0, 179.9, 180.0, -180.0, 183.0, 186.0, 270.0, -300.0]
)
def test_r_form_avoids_half_circles_and_is_negative_past_them(sweep_deg: float) -> None:
    d = 4
    centre, radius = (12.5, -3.25), 7.0
    start, end = _arc(centre, radius, 35.0, sweep_deg, d)
    words = encode_arc(start, end, centre, radius, math.radians(sweep_deg), d, "r")
    near_half = abs(abs(sweep_deg) - 180.0) < HALF_CIRCLE_MARGIN_DEG
    if near_half:
        assert words.radius is None
        assert words.offset is not None
    else:
        assert words.radius is not None
        assert (words.radius < 0) == (abs(sweep_deg) > 180.0)
    move = _read_back(start, end, words, d)
    assert move.sweep_rad == pytest.approx(math.radians(sweep_deg), abs=1e-3)
    assert math.dist(move.centre, centre) < 3 * 10.0**-d  # type: ignore[arg-type]


def test_encode_refuses_coinciding_ends() -> None:
    with pytest.raises(ValueError, match="distinct"):
        encode_arc((5, 5), (5, 5), (0.0, 0.0), 1.0, 0.1, 3)
