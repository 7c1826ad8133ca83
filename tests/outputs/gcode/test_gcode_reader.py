"""The independent reader on hand-written programs: what it rebuilds, and what it refuses.

(Its arc semantics are also compared with LinuxCNC's own in test_gcode_rs274.py.)
"""

from __future__ import annotations

import math

import pytest

from tests.support.gcode_reader import GcodeSyntaxError, read

PREAMBLE = "G17 G21 G90 G91.1 G94 F300\n"


def test_blocks_words_comments_and_line_numbers() -> None:
    program = read(
        "(header: one comment)\n"
        "N5 G17 G20 G90 G91.1 G94 F12.5 (modes)\n"
        "N10 G0 X1 Y-2.5 ; rapid\n"
        "N15 G1 X2.0 Y-2.5\n"
        "N20 X3\n"
        "N25 M2\n"
    )
    assert program.comments == ["header: one comment", "modes", " rapid"]
    assert program.preamble_modes == {
        "plane": 17,
        "units": 20,
        "distance": 90,
        "arc_distance": 91.1,
        "feed_mode": 94,
    }
    assert program.preamble_feed == 12.5
    assert [b.number for b in program.blocks] == [None, 5, 10, 15, 20, 25]
    rapid, line, modal = program.moves
    assert (rapid.motion, rapid.xy_end, rapid.feed) == (0, (1.0, -2.5), None)
    assert (line.motion, line.xy_start, line.xy_end, line.feed) == (
        1,
        (1.0, -2.5),
        (2.0, -2.5),
        12.5,
    )
    assert line.explicit_motion
    assert (modal.motion, modal.xy_end, modal.explicit_motion) == (1, (3.0, -2.5), False)
    assert program.ended
    assert [m.block.number for m in program.cuts] == [15, 20]


def test_arc_centres_from_offsets_absolute_centres_and_radii() -> None:
    program = read(
        PREAMBLE + "G0 X1 Y0\n"
        "G3 X0 Y1 I-1 J0\n"  # quarter circle about the origin, anticlockwise
        "G90.1\n"
        "G2 X1 Y0 I0 J0\n"  # back, clockwise, centre given absolutely
        "G3 X-1 Y0 R-1\n"  # 270° about the origin: the major arc
        "G2 X0 Y1 R1\n"  # minor clockwise arc: centre right of the chord (the origin)
        "M2\n"
    )
    a, b, c, d = program.cuts
    assert a.centre == pytest.approx((0.0, 0.0))
    assert a.sweep_rad == pytest.approx(math.pi / 2)
    assert b.centre == pytest.approx((0.0, 0.0))
    assert b.sweep_rad == pytest.approx(-math.pi / 2)
    assert c.centre == pytest.approx((0.0, 0.0), abs=1e-12)
    assert c.sweep_rad == pytest.approx(math.pi)  # (1,0) → (−1,0) is a half circle either way
    assert d.centre == pytest.approx((0.0, 0.0), abs=1e-12)
    assert d.sweep_rad == pytest.approx(-math.pi / 2)
    assert (a.r_start, a.r_end) == pytest.approx((1.0, 1.0))


def test_major_arc_by_negative_radius() -> None:
    (arc,) = read(PREAMBLE + "G0 X1 Y0\nG3 X0 Y-1 R-1\nM2\n").cuts
    assert arc.centre == pytest.approx((0.0, 0.0), abs=1e-12)
    assert arc.sweep_rad == pytest.approx(3 * math.pi / 2)


def test_coinciding_ends_read_as_a_full_circle() -> None:
    (arc,) = read(PREAMBLE + "G0 X1 Y0\nG2 X1 Y0 I-1 J0\nM2\n").cuts
    assert arc.sweep_rad == pytest.approx(-2 * math.pi)


@pytest.mark.parametrize(
    ("line", "reason"),
    [
        ("G1 X1 Y2 X3", "X twice"),
        ("G1 Xnan Y0", "cannot read"),
        ("G1 Xinf Y0", "cannot read"),
        ("G1 X1e3 Y0", "unsupported word E"),
        ("G1 X1 Y0 (unclosed", "unclosed"),
        ("G1 X1 Y0 (a (nested) comment)", "nested"),
        ("G4", "unknown G4"),
        ("G4 P1", "unsupported word P"),
        ("G1 G2 X1 Y1 I1 J0", "two G codes of one modal group"),
        ("G2 X1 Y1", "either I/J or R"),
        ("G2 X1 Y1 I1 J0 R1", "either I/J or R"),
        ("G1 X1 Y1 I1", "straight move"),
        ("G91 G1 X1 Y1", "only G17 G90"),
        ("M3", "unknown M3"),
        ("X1 N5 Y1", "N must come first"),
        ("G3 X0 Y4 R1", "too small"),
    ],
)
def test_refuses_what_a_controller_would(line: str, reason: str) -> None:
    with pytest.raises(GcodeSyntaxError, match=reason):
        read(PREAMBLE + "G0 X0 Y0\n" + line + "\nM2\n")


def test_refuses_feed_moves_without_a_feed_and_code_after_the_end() -> None:
    with pytest.raises(GcodeSyntaxError, match="no feed rate"):
        read("G17 G21 G90 G94\nG0 X0 Y0\nG1 X1 Y0\nM2\n")
    with pytest.raises(GcodeSyntaxError, match="after the program end"):
        read(PREAMBLE + "G0 X0 Y0\nM2\nG0 X1 Y1\n")
