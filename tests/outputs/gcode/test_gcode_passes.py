"""Depth passes (``GcodeOptions.step_down``): passes at Z −step, −2·step, … down to exactly
``cut_z``, read back by the independent reader; a closed part plunges in place between passes,
an open one retracts and goes back to its start; rs274 at its strictest accepts them; and
without passes (or with one) the program is the same as before, byte for byte."""

from __future__ import annotations

import math
from functools import cache
from typing import Any

import pytest

from arcspline.geometry import PathSpline, approximate_path
from arcspline.outputs.gcode import GcodeError, GcodeOptions
from arcspline.outputs.gcode.program import write_parts
from arcspline.paths import parse_path_data
from tests.support import gcode_reader
from tests.support.rs274 import Rs274

# A closed square, then an open half circle.
PATH = "M 0 0 L 10 0 L 10 10 L 0 10 Z M 20 0 A 5 5 0 0 1 30 0"
DEPTHS: dict[str, Any] = {"safe_z": 5.0, "cut_z": -1.2, "plunge_feed_rate": 100.0}


@cache
def _result() -> PathSpline:
    return approximate_path(parse_path_data(PATH), 0.01, "subdivide")


def _write(**settings: Any) -> str:
    options = GcodeOptions(feed_rate=600.0, **settings)
    return write_parts([(s.spline, s.curve) for s in _result().subpaths], options)


def _plunges(program: gcode_reader.Program) -> list[gcode_reader.Move]:
    return [m for m in program.moves if m.motion == 1 and not m.is_cut]


def test_passes_step_down_to_exactly_cut_z_and_cut_every_path_at_each() -> None:
    text = _write(**DEPTHS, step_down=0.5, decimals=3)
    program = gcode_reader.read(text)
    plunges = _plunges(program)
    # Hand-computed: 1.2 in steps of 0.5 is 0.5, 1.0, then the remainder to 1.2.
    assert [m.end[2] for m in plunges] == [-0.5, -1.0, -1.2, -0.5, -1.0, -1.2]
    assert all(m.feed == 100.0 for m in plunges)
    assert all(m.xy_start == m.xy_end for m in plunges)
    square, arc = (len(s.spline) for s in _result().subpaths)
    cuts = program.cuts
    assert len(cuts) == 3 * square + 3 * arc
    # Each pass cuts at its own depth and repeats the first pass's moves exactly.
    passes = [cuts[k * square : (k + 1) * square] for k in range(3)]
    passes += [cuts[3 * square + k * arc : 3 * square + (k + 1) * arc] for k in range(3)]
    for group, z in zip(passes, [-0.5, -1.0, -1.2] * 2, strict=True):
        assert all(m.start[2] == m.end[2] == z for m in group)
        assert all(m.feed == 600.0 for m in group)
    for first, later in ((passes[0], passes[1:3]), (passes[3], passes[4:6])):
        for group in later:
            assert [(m.xy_end, m.motion) for m in group] == [(m.xy_end, m.motion) for m in first]


def test_a_closed_part_plunges_in_place_and_an_open_one_goes_back_to_its_start() -> None:
    program = gcode_reader.read(_write(**DEPTHS, step_down=0.5))
    rapids = [m for m in program.moves if m.motion == 0]
    xy_rapids = [m for m in rapids if m.block.has("X")]
    # One rapid to the square's start; three to the half circle's start (one per pass).
    assert [m.xy_end for m in xy_rapids] == [(0.0, 0.0)] + [(20.0, 0.0)] * 3
    assert all(m.start[2] == m.end[2] == 5.0 for m in xy_rapids)
    z_order = [round(m.end[2], 6) for m in program.moves if not m.is_cut]
    assert z_order == [
        5.0, 5.0, -0.5, -1.0, -1.2,  # square: retract, rapid, three plunges in place
        5.0, 5.0, -0.5, 5.0, 5.0, -1.0, 5.0, 5.0, -1.2,  # arc: retract, rapid, plunge ×3
        5.0,  # final retract
    ]  # fmt: skip
    square_cuts = [m for m in program.cuts if m.xy_end[0] <= 10.0]
    # The square's passes start where the one before ended: the corner it closes on.
    assert square_cuts[-1].xy_end == (0.0, 0.0)


def test_the_header_says_how_many_passes() -> None:
    text = _write(**DEPTHS, step_down=0.5, comments=True, decimals=3)
    program = gcode_reader.read(text)
    assert (
        "depth: 3 passes of at most 0.500 mm down to Z-1.200, "
        "every pass of a path before the next path"
    ) in program.comments
    single = gcode_reader.read(_write(**DEPTHS, step_down=2.0, comments=True))
    assert not any(c.startswith("depth:") for c in single.comments)


def test_without_passes_the_program_is_unchanged_byte_for_byte() -> None:
    # Written out by hand from the options: a retract, rapid, plunge, one line, retract.
    parts = approximate_path(parse_path_data("M 1 2 L 4 6"), 0.01, "subdivide").subpaths
    options = GcodeOptions(feed_rate=600.0, safe_z=5.0, cut_z=-1.0, decimals=3)
    assert write_parts([(s.spline, s.curve) for s in parts], options) == (
        "G17 G21 G90 G91.1 G94 F600\n"
        "G0 Z5.000\nG0 X1.000 Y2.000\nG1 Z-1.000\nG1 X4.000 Y6.000\nG0 Z5.000\nM2\n"
    )
    # One pass (a step as deep as the cut) writes the program without step_down.
    assert _write(**DEPTHS) == _write(**DEPTHS, step_down=1.2) == _write(**DEPTHS, step_down=9)


def test_a_step_dividing_the_depth_ends_exactly_at_cut_z() -> None:
    program = gcode_reader.read(_write(safe_z=2.0, cut_z=-0.9, step_down=0.3, decimals=4))
    assert [m.end[2] for m in _plunges(program)][:4] == [-0.3, -0.6, -0.9, -0.3]


@pytest.mark.parametrize(
    "settings",
    [
        {"units": "mm", "decimals": 3, "arc_format": "ij"},
        {"units": "mm", "decimals": 4, "arc_format": "r", "line_numbers": True},
        {"units": "inch", "decimals": 5, "arc_format": "ij", "comments": True},
    ],
    ids=["mm3-ij", "mm4-r-numbers", "inch5-ij-comments"],
)
def test_rs274_at_its_strictest_accepts_programs_with_passes(
    rs274: Rs274, settings: dict[str, Any]
) -> None:
    text = _write(**DEPTHS, step_down=0.5, **settings)
    verdict = rs274.run(text)
    assert verdict.accepted, verdict.describe()
    # rs274 reports a feed along Z to each pass depth (in the program's units).
    plunges = list(_plunges(gcode_reader.read(text)))
    feeds = [c for c in verdict.canon if c.name == "STRAIGHT_FEED"]
    assert len(plunges) == 6
    z_seen = {round(c.numbers()[2], 6) for c in feeds}
    for z in (-0.5, -1.0, -1.2):
        assert any(math.isclose(v, z, abs_tol=1e-6) for v in z_seen), (z, z_seen)


@pytest.mark.parametrize(
    ("settings", "field", "words"),
    [
        ({"step_down": 0.5}, "step_down", "safe_z and cut_z"),
        ({**DEPTHS, "step_down": 0.0}, "step_down", "> 0"),
        ({**DEPTHS, "step_down": -1.0}, "step_down", "> 0"),
        ({**DEPTHS, "step_down": math.nan}, "step_down", "finite"),
        ({**DEPTHS, "step_down": True}, "step_down", "finite"),
        ({**DEPTHS, "step_down": 1e-5, "decimals": 3}, "step_down", "one unit"),
        ({"safe_z": 5.0, "cut_z": 0.0, "step_down": 0.5}, "cut_z", "below the stock top"),
        ({"safe_z": 5.0, "cut_z": 1.0, "step_down": 0.5}, "cut_z", "below the stock top"),
        ({"safe_z": 5.0, "cut_z": -10.0, "step_down": 0.001}, "step_down", "10000 passes"),
        # rapids at safe_z would run through the stock
        ({"safe_z": -1.0, "cut_z": -3.0, "step_down": 1.0}, "safe_z", "above the stock top"),
        ({"safe_z": 0.0, "cut_z": -3.0, "step_down": 1.0}, "safe_z", "above the stock top"),
    ],
)
def test_bad_step_downs_are_refused_naming_the_field(
    settings: dict[str, Any], field: str, words: str
) -> None:
    with pytest.raises(GcodeError) as caught:
        GcodeOptions(feed_rate=600.0, **settings)
    assert caught.value.field == field
    assert words in caught.value.message


@pytest.mark.parametrize(
    ("step", "cut_z", "first_ulps"),
    [(0.29, -1.0, -2900), (0.00015, -0.001, -1), (0.00006, -0.001, None)],
)
def test_a_pass_is_never_deeper_than_the_step(
    step: float, cut_z: float, first_ulps: int | None
) -> None:
    # The step is rounded down to the last decimal (4 in mm): 0.00015 cuts 0.0001 a pass;
    # 0.29 stays 0.29 (its binary value is 0.28999999999999998); 0.00006 is below one unit.
    settings: dict[str, Any] = {"safe_z": 5.0, "cut_z": cut_z, "step_down": step}
    if first_ulps is None:
        with pytest.raises(GcodeError, match="one unit"):
            GcodeOptions(feed_rate=600.0, **settings)
        return
    assert GcodeOptions(feed_rate=600.0, **settings).pass_levels[0] == first_ulps


def test_a_thousand_passes_are_allowed() -> None:
    options = GcodeOptions(feed_rate=600.0, safe_z=5.0, cut_z=-1.0, step_down=0.001, decimals=3)
    assert len(options.pass_levels) == 1000
    assert options.pass_levels[-1] == -1000
