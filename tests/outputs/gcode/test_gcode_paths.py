"""Programs for whole paths (``write_parts``): LinuxCNC's ``rs274`` at its strictest accepts
each and reads every move as the independent reader does; one program per path, a rapid to
each subpath (retract and plunge for a 2.5-D cut), one cut per segment ending at the path's
points to the decimals, and the path read back within tolerance plus one unit in the last
place of the source, measured by the path oracle.

The path mixes lines, a cubic, a quadratic, circular arcs (a half circle, a large clockwise
arc) and a rotated elliptical arc in two subpaths, the first closed.
"""

from __future__ import annotations

import itertools
import math
from functools import cache
from typing import Any

import pytest

from arcspline.geometry import PathSpline, approximate_path
from arcspline.outputs.gcode import GcodeOptions
from arcspline.outputs.gcode.program import write_parts
from arcspline.paths import parse_path_data
from tests.support import gcode_reader, path_oracle
from tests.support.rs274 import Rs274

from .readback import radius_mismatch
from .test_gcode_rs274 import _assert_same_moves

PATH = (
    "M 0 0 C 10 0 20 10 30 30 L 40 30 A 5 5 0 0 1 50 30 Z "
    "M 60 0 A 8 4 30 0 1 80 10 L 90 0 A 6 6 0 1 0 100 0 Q 105 10 110 0"
)
TOLERANCE = 0.05
FEED = 1200.0
Z_CUT: dict[str, Any] = {
    "safe_z": 5.0,
    "cut_z": -1.0,
    "plunge_feed_rate": 250.0,
    "line_numbers": True,
    "comments": True,
}
PRECISIONS = [("mm", 3), ("mm", 4), ("inch", 4), ("inch", 5)]
COARSE = [("mm", 3), ("inch", 4)]
MATRIX = [
    (strategy, units, decimals, fmt, z)
    for strategy in ("subdivide", "fewest-arcs")
    for units, decimals in PRECISIONS
    for fmt in ("ij", "r")
    for z in (False, True)
]


def _id(entry: tuple[str, str, int, str, bool]) -> str:
    strategy, units, decimals, fmt, z = entry
    return f"{strategy}-{units}{decimals}-{fmt}-{'z' if z else 'plain'}"


@cache
def _result(strategy: str) -> PathSpline:
    return approximate_path(parse_path_data(PATH), TOLERANCE, strategy)


def _program(entry: tuple[str, str, int, str, bool]) -> tuple[PathSpline, GcodeOptions, str]:
    strategy, units, decimals, fmt, z = entry
    settings: dict[str, Any] = {"units": units, "decimals": decimals, "arc_format": fmt}
    options = GcodeOptions(feed_rate=FEED, **settings, **(Z_CUT if z else {}))
    result = _result(strategy)
    text = write_parts([(s.spline, s.curve) for s in result.subpaths], options)
    return result, options, text


def _groups(program: gcode_reader.Program) -> list[list[gcode_reader.Move]]:
    """The moves from each rapid in XY (to a subpath's start) up to the next."""
    groups: list[list[gcode_reader.Move]] = []
    for move in program.moves:
        if move.motion == 0 and move.block.has("X", "Y"):
            groups.append([])
        if groups:
            groups[-1].append(move)
    return groups


@pytest.mark.parametrize("entry", MATRIX, ids=_id)
def test_rs274_accepts_a_path_program_and_reads_it_as_the_reader_does(
    rs274: Rs274, entry: tuple[str, str, int, str, bool]
) -> None:
    _, options, text = _program(entry)
    program = gcode_reader.read(text)
    verdict = rs274.run(text)
    assert verdict.accepted, verdict.describe()
    _assert_same_moves(verdict, program)
    ends = [c for c in verdict.canon if c.name == "PROGRAM_END"]
    assert len(ends) == 1
    assert sum(c.name == "ARC_FEED" for c in verdict.canon) == sum(
        m.motion in (2, 3) for m in program.cuts
    )
    # rs274 at its strictest: start and end radius of each arc within 0.001 mm (0.00004").
    tight = 0.001 if options.units == "mm" else 0.00004
    assert radius_mismatch(program.cuts) <= tight


@pytest.mark.parametrize("entry", MATRIX, ids=_id)
def test_one_program_with_a_rapid_to_each_subpath_and_its_cuts_at_the_paths_points(
    entry: tuple[str, str, int, str, bool],
) -> None:
    result, options, text = _program(entry)
    program = gcode_reader.read(text)
    z = entry[4]
    ulp = 10.0**-options.resolved_decimals
    half = 0.5 * ulp * (1 + 1e-9)
    assert [b.m for b in program.blocks if b.m] == [(2,)]
    assert program.blocks[-1].m == (2,)
    assert program.preamble_modes["units"] == (21 if options.units == "mm" else 20)
    source = parse_path_data(PATH)
    groups = _groups(program)
    assert len(groups) == len(result.subpaths) == len(source.subpaths) == 2
    for sub, src, (rapid, *rest) in zip(result.subpaths, source.subpaths, groups, strict=True):
        start, end = src.segments[0].start, src.segments[-1].end
        assert rapid.xy_end == pytest.approx(tuple(start), abs=half)
        cuts = [m for m in rest if m.is_cut]
        assert len(cuts) == len(sub.spline)
        assert cuts[0].xy_start == rapid.xy_end
        assert cuts[-1].xy_end == pytest.approx(tuple(end), abs=half)
        if src.closed:
            assert cuts[-1].xy_end == cuts[0].xy_start
        for a, b in itertools.pairwise(cuts):
            assert a.xy_end == b.xy_start
        for move, seg in zip(cuts, sub.spline.segments, strict=True):
            assert math.dist(move.xy_end, seg.end) <= math.sqrt(2) * half, move.block.text
            if move.motion in (2, 3):
                assert seg.type == "arc"
                assert (move.motion == 3) == (seg.sweep_rad > 0), move.block.text
        assert all(m.feed == FEED for m in cuts)
        if z:
            # Retract, rapid, plunge at the plunge feed, cut at cut_z.
            assert rapid.start[2] == rapid.end[2] == options.safe_z
            plunge = rest[0]
            assert plunge.motion == 1
            assert plunge.xy_start == plunge.xy_end == rapid.xy_end
            assert (plunge.start[2], plunge.end[2]) == (options.safe_z, options.cut_z)
            assert plunge.feed == options.plunge_feed_rate
            assert all(m.start[2] == m.end[2] == options.cut_z for m in cuts)
            assert rest[-1].motion == 0  # the retract before the next rapid, or the last
            assert rest[-1].end[2] == options.safe_z
            assert not rest[-1].block.has("X")
            assert not rest[-1].block.has("Y")
        else:
            assert all(m.start[2] == m.end[2] == 0.0 for m in [rapid, *rest])
    if z:
        retracts = [m for m in program.moves if m.motion == 0 and not m.block.has("X")]
        assert len(retracts) == len(result.subpaths) + 1
        assert program.moves[-1] is retracts[-1]
        assert program.moves[0] is retracts[0]
    else:
        assert not any(b.has("Z") for b in program.blocks)
    header = [c for c in program.comments if c.startswith("arc spline:")]
    if options.comments:
        assert header == [
            f"arc spline: {result.stats.arc_count} arcs, {result.stats.line_count} lines, "
            f"max deviation {result.stats.max_deviation:.6g} {options.units}, 2 paths"
        ]


@pytest.mark.parametrize(
    "entry",
    # The coarsest decimals of each unit, I/J without Z and R with Z.
    [e for e in MATRIX if (e[1], e[2]) in COARSE and (e[3] == "r") == e[4]],
    ids=_id,
)
def test_the_program_read_back_stays_within_tolerance_plus_one_unit_in_the_last_place(
    entry: tuple[str, str, int, str, bool],
) -> None:
    result, options, text = _program(entry)
    program = gcode_reader.read(text)
    ulp = 10.0**-options.resolved_decimals
    source = parse_path_data(PATH)
    for sub, src, (_, *rest) in zip(
        result.subpaths, source.subpaths, _groups(program), strict=True
    ):
        cuts = [m for m in rest if m.is_cut]
        owners = sub.sources().segment.tolist()
        moves = [_as_output(m, j) for m, j in zip(cuts, owners, strict=True)]
        measured = path_oracle.union_hausdorff(src, moves, samples=129).hausdorff
        slack = path_oracle.rounding_slack(120.0)
        assert measured + 0.5 * radius_mismatch(cuts) <= TOLERANCE + ulp + slack, measured


def _as_output(move: gcode_reader.Move, source_segment: int) -> dict[str, Any]:
    """A read-back move in the fields the path oracle reads (an arc at its mean radius: a
    controller cuts between the two, so half their difference is added to what is measured)."""
    out: dict[str, Any] = {
        "type": "line",
        "start": move.xy_start,
        "end": move.xy_end,
        "source_segment": source_segment,
    }
    if move.motion in (2, 3):
        assert move.centre is not None
        assert move.r_start is not None
        assert move.r_end is not None
        out.update(
            type="arc",
            center=move.centre,
            radius=0.5 * (move.r_start + move.r_end),
            direction="ccw" if move.motion == 3 else "cw",
            sweep_rad=move.sweep_rad,
        )
    return out


@pytest.mark.parametrize(("units", "r"), [("mm", 0.0005), ("inch", 0.00002)])
def test_an_arc_too_small_for_the_controller_is_cut_as_a_line(
    rs274: Rs274, units: str, r: float
) -> None:
    # A half circle of radius r (in the program's unit): LinuxCNC refuses arcs whose radius is
    # below 0.00005 in (1.27 µm) as zero-radius; its chord is within tolerance.
    path = parse_path_data(f"M 0 0 L 1 0 A {r} {r} 0 0 1 {1 + 2 * r} 0 L 2 0")
    result = approximate_path(path, 0.01)
    spline, curve = result.subpaths[0].spline, result.subpaths[0].curve
    assert spline.stats.arc_count >= 1
    program = write_parts([(spline, curve)], GcodeOptions(feed_rate=FEED, units=units))
    verdict = rs274.run(program)
    assert verdict.accepted, verdict.describe()
    read = gcode_reader.read(program)
    assert all(move.motion == 1 for move in read.cuts)
