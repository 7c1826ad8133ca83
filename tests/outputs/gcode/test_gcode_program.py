"""Programs for real approximations, read back independently: every rule of issue 4.

Each test runs over the matrix of cases (tests/gcode/cases.py) × units and decimals × arc
format; the reader (tests/support/gcode_reader.py) rebuilds the path as a controller would.
"""

from __future__ import annotations

import math
import re

import numpy as np
import pytest

from arcspline.outputs.gcode import MIN_RADIUS_ULPS, MIN_SWEEP_RAD
from tests.support import oracle

from . import readback
from .cases import MATRIX, Written, matrix_id, matrix_program

pytestmark = pytest.mark.parametrize("entry", MATRIX, ids=matrix_id)

_AXIS_NUMBER = re.compile(r"([XYZIJR])(\S*)")


def _written(entry: tuple[str, str, int, str]) -> Written:
    return matrix_program(entry)


def test_preamble_states_every_mode_before_the_first_move(entry: tuple[str, str, int, str]) -> None:
    w = _written(entry)
    expected_units = 21 if w.options.units == "mm" else 20
    assert w.program.preamble_modes == {
        "plane": 17,
        "units": expected_units,
        "distance": 90,
        "arc_distance": 91.1,
        "feed_mode": 94,
    }
    assert w.program.preamble_feed == pytest.approx(w.options.feed_rate)
    first = w.program.moves[0]
    assert first.motion == 0, "the tool moves rapidly to the start first"
    assert w.program.ended
    assert w.program.blocks[-1].m == (2,)


def test_every_cut_block_names_its_motion_and_carries_all_its_words(
    entry: tuple[str, str, int, str],
) -> None:
    w = _written(entry)
    for move in w.program.cuts:
        block = move.block
        assert move.explicit_motion, f"modal motion reused: {block.text}"
        assert block.has("X", "Y"), block.text
        if move.motion in (2, 3):
            assert block.has("I", "J") != block.has("R"), block.text
        else:
            assert not ({"I", "J", "R"} & block.words.keys()), block.text
        assert move.feed == pytest.approx(w.options.feed_rate)


def test_numbers_are_plain_decimals_with_the_requested_places(
    entry: tuple[str, str, int, str],
) -> None:
    w = _written(entry)
    lower = w.text.lower()
    assert "nan" not in lower
    assert "inf" not in lower
    plain = re.compile(rf"^-?\d+\.\d{{{w.decimals}}}$")
    for block in w.program.blocks:
        code = block.text.split("(")[0]
        for letter, number in _AXIS_NUMBER.findall(code):
            assert plain.match(number), f"{letter}{number} in {block.text!r}"
            assert not re.fullmatch(r"-0\.0+", number), f"negative zero in {block.text!r}"


def test_path_runs_between_the_rounded_spiral_ends_one_move_per_segment(
    entry: tuple[str, str, int, str],
) -> None:
    w = _written(entry)
    cuts = w.program.cuts
    assert len(cuts) == len(w.spline)
    cp = w.spiral.control_points
    half = 0.5 * w.ulp * (1.0 + 1e-9)
    rapid_to = w.program.moves[0].xy_end
    assert cuts[0].xy_start == rapid_to
    for got, exact in ((cuts[0].xy_start, cp[0]), (cuts[-1].xy_end, cp[3])):
        assert abs(got[0] - exact[0]) <= half
        assert abs(got[1] - exact[1]) <= half
    for move, seg in zip(cuts, w.spline.segments, strict=True):
        for got, exact in ((move.xy_start, seg.start), (move.xy_end, seg.end)):
            assert math.dist(got, exact) <= math.sqrt(2.0) * half, (move.block.text, exact)


def test_arcs_are_read_back_as_the_arcs_they_stand_for(entry: tuple[str, str, int, str]) -> None:
    w = _written(entry)
    for move, seg in zip(w.program.cuts, w.spline.segments, strict=True):
        if move.motion not in (2, 3):
            continue
        assert seg.type == "arc"
        assert move.sweep_rad is not None
        assert move.r_start is not None
        assert move.r_end is not None
        # Never a full circle; the same sense; the same sweep, give or take the rounding.
        assert abs(move.sweep_rad) < math.pi, move.block.text
        assert (move.motion == 3) == (seg.sweep_rad > 0), move.block.text
        assert move.sweep_rad == pytest.approx(seg.sweep_rad, rel=0.05, abs=2 * w.ulp / seg.radius)
        # |r_end − r_start| within one unit in the last place; by the bisector construction
        # within √2·sin(sweep/2) of one.
        bound = w.ulp * min(1.0, math.sqrt(2.0) * math.sin(abs(move.sweep_rad) / 2.0))
        assert abs(move.r_end - move.r_start) <= bound * (1 + 1e-6) + 1e-12 * seg.radius
        if w.options.arc_format == "r":
            # These arcs turn far less than a half circle: R form, positive.
            assert "R" in move.block.words, move.block.text
            assert move.block.words["R"] > 0, move.block.text
        else:
            assert "R" not in move.block.words


def test_arcs_too_small_to_represent_are_cut_as_lines(entry: tuple[str, str, int, str]) -> None:
    w = _written(entry)
    q = w.ulp
    limit = w.spline.tolerance + q
    for move, seg in zip(w.program.cuts, w.spline.segments, strict=True):
        if seg.type != "arc":
            assert move.motion == 1
            continue
        same_ends = move.xy_start == move.xy_end
        if same_ends or abs(seg.sweep_rad) < MIN_SWEEP_RAD or seg.radius < MIN_RADIUS_ULPS * q:
            assert move.motion == 1, move.block.text
            continue
        sagitta = seg.radius * (1.0 - math.cos(seg.sweep_rad / 2.0))
        if sagitta < 0.5 * q:
            if move.motion != 1:
                # Kept as an arc only because its chord would leave the bound.
                chord = readback.chord_deviation_sampled(
                    w.spiral, seg.u_start, seg.u_end, move.xy_start, move.xy_end
                )
                assert chord > limit * (1 - 1e-9), move.block.text
        else:
            assert move.motion in (2, 3), f"a representable arc became {move.block.text}"


def test_read_back_path_stays_within_tolerance_plus_one_unit_in_the_last_place(
    entry: tuple[str, str, int, str],
) -> None:
    w = _written(entry)
    measured = readback.deviation(w.spiral, w.spline, w.program)
    slack = oracle.rounding_slack(np.asarray(w.spiral.control_points))
    assert measured <= w.spline.tolerance + w.ulp + slack
