"""write_machining(): programs read back by the independent reader, measured by the offset
oracle, and run through LinuxCNC's rs274 at its strictest (fixture ``rs274``)."""

from __future__ import annotations

import itertools
import math
import pickle
from collections.abc import Sequence

import pytest

from arcspline.geometry import DEFAULT_LIMITS
from arcspline.machining import Machined, MachiningOptions, Tabs, machine, write_machining
from arcspline.outputs.gcode import GcodeError, GcodeOptions
from tests.support import offset_oracle as oracle
from tests.support.gcode_reader import Move, read
from tests.support.rs274 import Canon, Rs274

from .oracle_view import contours
from .shapes import circle, fitted, rectangle, square_with_two_holes

RADIUS = 3.0
SIDES: list[oracle.Side | None] = ["outside", "inside", "inside"]
#: Rounding of the words (q = 1e-4 at 4 decimals) plus the fit's tolerance (0.001).
WORDS_TOL = 1e-4 + 1e-3 + 1e-9
GCODE = GcodeOptions(1000.0, safe_z=5.0, cut_z=-3.0, step_down=1.5, plunge_feed_rate=200.0)


def _program(options: MachiningOptions, gcode: GcodeOptions = GCODE) -> tuple[Machined, str]:
    machined = machine(square_with_two_holes(), options, DEFAULT_LIMITS)
    return machined, write_machining(machined, gcode)


def _segments(moves: Sequence[Move]) -> list[oracle.OSeg]:
    """The XY cut moves below the stock top as oracle segments (arcs as the reader's
    controller computes them)."""
    out = []
    for m in moves:
        if not m.is_cut or m.end[2] >= 0.0 or m.xy_start == m.xy_end:
            continue
        if m.motion == 1:
            out.append(oracle.OSeg("line", m.xy_start, m.xy_end))
        else:
            assert m.centre is not None
            assert m.r_start is not None
            assert m.sweep_rad is not None
            out.append(oracle.OSeg("arc", m.xy_start, m.xy_end, m.centre, m.r_start, m.sweep_rad))
    return out


def _canon_segments(canon: Sequence[Canon]) -> list[oracle.OSeg]:
    """rs274's own tool-centre moves (what it sends the machine, compensation applied)."""
    out = []
    here = (0.0, 0.0, 0.0)
    for c in canon:
        if c.name == "STRAIGHT_TRAVERSE":
            x, y, z = c.numbers()[:3]
        elif c.name == "STRAIGHT_FEED":
            x, y, z = c.numbers()[:3]
            if z < 0.0 and (x, y) != here[:2]:
                out.append(oracle.OSeg("line", here[:2], (x, y)))
        elif c.name == "ARC_FEED":
            x, y, cx, cy, turn, z = c.numbers()[:6]
            a0 = math.atan2(here[1] - cy, here[0] - cx)
            a1 = math.atan2(y - cy, x - cx)
            sweep = (a1 - a0) % (2 * math.pi) if turn > 0 else -((a0 - a1) % (2 * math.pi))
            r = math.hypot(here[0] - cx, here[1] - cy)
            if z < 0.0:
                out.append(oracle.OSeg("arc", here[:2], (x, y), (cx, cy), r, sweep))
        else:
            continue
        here = (x, y, z)
    return out


VARIANTS = {
    "plunge": (MachiningOptions(6.0), GCODE),
    "ramp": (MachiningOptions(6.0, entry="ramp"), GCODE),
    "tabs": (MachiningOptions(6.0, tabs=Tabs(4, 3.0, 1.0)), GCODE),
    "conventional": (MachiningOptions(6.0, direction="conventional", entry="ramp"), GCODE),
    "r words, 3 decimals, numbered": (
        MachiningOptions(6.0, tabs=Tabs(3, 2.0, 2.0), join="mitre"),
        GcodeOptions(
            800.0,
            decimals=3,
            arc_format="r",
            line_numbers=True,
            comments=True,
            safe_z=2.0,
            cut_z=-2.5,
        ),
    ),
    "no leads": (MachiningOptions(6.0, lead_radius=0.0), GCODE),
}


@pytest.mark.parametrize("name", VARIANTS)
def test_computed_programs_are_accepted_and_keep_the_tool_radius(name: str, rs274: Rs274) -> None:
    options, gcode = VARIANTS[name]
    _machined, text = _program(options, gcode)
    verdict = rs274.run(text)
    assert verdict.accepted, verdict.describe()
    program = read(text)
    assert program.ended
    spline = square_with_two_holes()
    report = oracle.check_offset(contours(spline), [_segments(program.moves)], RADIUS, SIDES)
    assert report.ok(RADIUS, WORDS_TOL), report.describe()
    # rs274's own reading of the program agrees.
    canon = oracle.check_offset(contours(spline), [_canon_segments(verdict.canon)], RADIUS, SIDES)
    assert canon.ok(RADIUS, WORDS_TOL), canon.describe()


@pytest.mark.parametrize(
    "options",
    [
        MachiningOptions(6.0, compensation="controller"),
        MachiningOptions(6.0, compensation="controller", direction="conventional", entry="ramp"),
        MachiningOptions(6.0, compensation="controller", tabs=Tabs(4, 3.0, 1.0), lead_radius=4.0),
    ],
    ids=["G41.1", "G42.1 ramp", "G41.1 tabs"],
)
def test_controller_programs_cut_the_tool_radius_as_rs274_compensates_them(
    options: MachiningOptions, rs274: Rs274
) -> None:
    _machined, text = _program(options)
    verdict = rs274.run(text)
    assert verdict.accepted, verdict.describe()
    spline = square_with_two_holes()
    # The tool centre as the controller computes it, measured by the oracle.
    report = oracle.check_offset(contours(spline), [_canon_segments(verdict.canon)], RADIUS, SIDES)
    assert report.ok(RADIUS, WORDS_TOL), report.describe()
    lines = text.splitlines()
    code = "G41.1" if options.direction == "climb" else "G42.1"
    on = [k for k, t in enumerate(lines) if t.startswith(code)]
    off = [k for k, t in enumerate(lines) if t == "G40"]
    assert off[0] == 1  # cancelled in the preamble
    off = off[1:]
    assert len(on) == len(off) == 3 * 2  # three paths, two passes each
    for k in on:
        assert lines[k] == f"{code} D6.0000"
        assert lines[k - 1].startswith("G0 X")  # at safe Z, above the stock
        assert lines[k + 1].startswith("G1 X")  # the straight entry move
        rapid, entry = read("\n".join(["G17 G21 G90 G94 F1", lines[k - 1], lines[k + 1]])).moves
        assert math.dist(rapid.xy_end, entry.xy_end) > RADIUS
        assert lines[k + 2].startswith("G1 Z")  # down only after compensation is on
    for k in off:
        assert lines[k - 1] == "G0 Z5.0000"
        assert lines[k + 1].startswith("G1 X")


def test_controller_program_naming_a_tool_of_the_table(rs274: Rs274) -> None:
    # rs274's tool table holds T1 of diameter 0.125 (inch): a program in inches uses it.
    inch = fitted(rectangle(0, 0, 3, 2), circle(0.75, 1.0, 0.3), rectangle(1.75, 0.6, 2.5, 1.4))
    options = MachiningOptions(0.125, compensation="controller", tool_number=1)
    machined = machine(inch, options, DEFAULT_LIMITS)
    text = write_machining(
        machined, GcodeOptions(40.0, units="inch", safe_z=0.2, cut_z=-0.1, step_down=0.05)
    )
    assert "G41 D1" in text.splitlines()
    verdict = rs274.run(text)
    assert verdict.accepted, verdict.describe()
    report = oracle.check_offset(contours(inch), [_canon_segments(verdict.canon)], 0.0625, SIDES)
    assert report.ok(0.0625, 1e-5 + 1e-3), report.describe()


def _passes(machined: Machined, text: str) -> list[tuple[int, list[Move]]]:
    """The program's passes: (tool path index, its moves from the rapid to its start on)."""
    starts = [sub.spline.segments[0].start for sub in machined.programmed.subpaths]
    program = read(text)
    passes: list[tuple[int, list[Move]]] = []
    for m in program.moves:
        if m.motion == 0 and m.xy_start != m.xy_end:
            k = min(range(len(starts)), key=lambda i: math.dist(starts[i], m.xy_end))
            assert math.dist(starts[k], m.xy_end) < 1e-4
            passes.append((k, []))
        elif passes:
            passes[-1][1].append(m)
    return passes


def test_plunges_and_pass_levels() -> None:
    machined, text = _program(MachiningOptions(6.0))
    passes = _passes(machined, text)
    assert [k for k, _ in passes] == [0, 0, 1, 1, 2, 2]  # every pass of a path first
    for n, (_, moves) in enumerate(passes):
        level = -1.5 if n % 2 == 0 else -3.0
        plunge = moves[0]
        assert plunge.motion == 1
        assert plunge.xy_start == plunge.xy_end
        assert plunge.end[2] == level
        assert plunge.feed == 200.0
        cuts = [m for m in moves if m.is_cut]
        assert {m.end[2] for m in cuts} == {level}
        assert {m.feed for m in cuts} == {1000.0}
        assert cuts[0].xy_start == plunge.xy_end


def test_the_ramp_descends_along_the_lead_in_arc() -> None:
    machined, text = _program(MachiningOptions(6.0, entry="ramp"))
    for n, (k, moves) in enumerate(_passes(machined, text)):
        level = -1.5 if n % 2 == 0 else -3.0
        down = moves[0]
        assert down.motion == 1
        assert down.end[2] == 0.0  # the stock top
        lead = [
            m
            for m, role in zip(
                [m for m in moves if m.is_cut], machined.programmed_roles[k], strict=True
            )
            if role == "lead_in"
        ]
        assert lead
        assert all(m.motion in (2, 3) for m in lead)  # a helix
        zs = [lead[0].start[2]] + [m.end[2] for m in lead]
        assert zs[0] == 0.0
        assert zs[-1] == level
        assert all(b < a for a, b in itertools.pairwise(zs))


def test_tabs_lift_the_tool_on_passes_below_their_top() -> None:
    tabs = Tabs(4, 3.0, 1.0)
    machined, text = _program(MachiningOptions(6.0, tabs=tabs))
    outline = next(k for k, p in enumerate(machined.contours) if p.cut == "outside")
    passes = [moves for k, moves in _passes(machined, text) if k == outline]
    first, last = passes
    assert {m.end[2] for m in first if m.is_cut} == {-1.5}  # above the tab top -2
    on_tab = [m for m in last if m.is_cut and m.end[2] == -2.0]
    low = [m for m in last if m.is_cut and m.end[2] == -3.0]
    assert low
    length = sum(
        math.dist(m.xy_start, m.xy_end)
        if m.motion == 1
        else abs(m.sweep_rad or 0.0) * (m.r_start or 0.0)
        for m in on_tab
    )
    assert length == pytest.approx(tabs.count * (tabs.width + 6.0), abs=1e-3)
    lifts = [m for m in last if not m.is_cut and m.motion == 1]
    # plunge, then up and down at each of the four tabs
    assert [m.end[2] for m in lifts] == [-3.0] + [-2.0, -3.0] * 4
    assert all(m.feed == 200.0 for m in lifts)


def test_leads_join_the_cut_without_a_corner() -> None:
    machined, text = _program(MachiningOptions(6.0))
    for k, moves in _passes(machined, text):
        cuts = [m for m in moves if m.is_cut]
        roles = machined.programmed_roles[k]
        segs = _segments(cuts)
        assert len(segs) == len(roles)
        joints = oracle.corners(segs, closed=False, angle_deg=0.01)
        assert 1 not in joints
        assert len(segs) - 1 not in joints


def test_header_comments_name_the_tool_and_the_paths() -> None:
    spline = fitted(rectangle(0, 0, 30, 30), circle(15, 15, 3.2))
    machined = machine(spline, MachiningOptions(6.0, entry="ramp"), DEFAULT_LIMITS)
    text = write_machining(machined, GcodeOptions(1000.0, safe_z=5.0, cut_z=-3.0, comments=True))
    comments = read(text).comments
    assert "tool diameter 6 mm, computed tool-centre paths" in comments
    assert any(c.startswith("path 1: toolpath 1, inside, climb, anticlockwise") for c in comments)
    assert any(c.startswith("warning: toolpath 1: no lead arc") for c in comments)
    assert any(c.startswith("warning: toolpath 1: no lead-in arc to ramp") for c in comments)


def test_a_program_needs_its_depths() -> None:
    machined = machine(square_with_two_holes(), MachiningOptions(6.0), DEFAULT_LIMITS)
    with pytest.raises(GcodeError) as caught:
        write_machining(machined, GcodeOptions(1000.0))
    assert caught.value.field == "cut_z"


def test_tabs_reaching_safe_z_are_refused() -> None:
    machined = machine(
        square_with_two_holes(), MachiningOptions(6.0, tabs=Tabs(2, 2.0, 9.0)), DEFAULT_LIMITS
    )
    with pytest.raises(GcodeError) as caught:
        write_machining(machined, GCODE)
    assert caught.value.field == "cut_z"


def test_a_machined_result_crosses_a_process_boundary() -> None:
    # The HTTP workers send results back pickled; the program written from the copy is the
    # same program.
    machined = machine(
        square_with_two_holes(), MachiningOptions(6.0, tabs=Tabs(2, 2.0, 1.0)), DEFAULT_LIMITS
    )
    copy = pickle.loads(pickle.dumps(machined))
    assert write_machining(copy, GCODE) == write_machining(machined, GCODE)
