"""LinuxCNC's own interpreter accepts every program the tests write, and reads each move as
the independent reader does.

``rs274`` runs with its strictest arc check (``tight.ini``: start and end radius within
0.001 mm / 0.00004" unless within 0.1 %). It is fetched and cached by
``scripts/fetch-rs274.sh`` (see tests/conftest.py); these tests never skip.
"""

from __future__ import annotations

import math
from typing import Any

import pytest

from tests.support import gcode_reader
from tests.support.rs274 import Rs274, Verdict

from .cases import MATRIX, matrix_id, program

#: rs274 prints coordinates with 4 decimals.
PRINTED = 0.5e-4 + 1e-9
FULL = {
    "safe_z": 5.0,
    "cut_z": -1.0,
    "plunge_feed_rate": 250.0,
    "line_numbers": True,
    "comments": True,
}


def _assert_same_moves(verdict: Verdict, read: gcode_reader.Program) -> None:
    """Every motion LinuxCNC sends matches the reader's move: kind, end, arc centre, sense."""
    canon = [
        c for c in verdict.canon if c.name in ("STRAIGHT_TRAVERSE", "STRAIGHT_FEED", "ARC_FEED")
    ]
    assert len(canon) == len(read.moves)
    kinds = {"STRAIGHT_TRAVERSE": (0,), "STRAIGHT_FEED": (1,), "ARC_FEED": (2, 3)}
    for command, move in zip(canon, read.moves, strict=True):
        assert move.motion in kinds[command.name], (command, move.block.text)
        values = command.numbers()
        if command.name == "ARC_FEED":
            end_x, end_y, centre_x, centre_y, turn, z = values[:6]
            assert move.centre is not None
            assert centre_x == pytest.approx(move.centre[0], abs=PRINTED), move.block.text
            assert centre_y == pytest.approx(move.centre[1], abs=PRINTED), move.block.text
            assert turn == (1 if move.motion == 3 else -1)
        else:
            end_x, end_y, z = values[:3]
        assert (end_x, end_y, z) == pytest.approx(move.end, abs=PRINTED), move.block.text


@pytest.mark.parametrize("variant", [{}, FULL], ids=["plain", "z-numbers-comments"])
@pytest.mark.parametrize("entry", MATRIX, ids=matrix_id)
def test_rs274_accepts_the_program_and_reads_it_alike(
    rs274: Rs274, entry: tuple[str, str, int, str], variant: dict[str, Any]
) -> None:
    name, units, decimals, fmt = entry
    w = program(name, units=units, decimals=decimals, arc_format=fmt, **variant)
    verdict = rs274.run(w.text)
    assert verdict.accepted, verdict.describe()
    _assert_same_moves(verdict, w.program)


@pytest.mark.parametrize("sweep_deg", [90.0, 178.0, 183.0, 270.0, -300.0])
@pytest.mark.parametrize("form", ["R", "IJ"])
def test_rs274_reads_r_and_ij_arcs_of_any_sweep_as_the_reader_does(
    rs274: Rs274, sweep_deg: float, form: str
) -> None:
    # Hand-written arcs about (2, 1) of radius 3, from angle 20°: the reader's R and I/J
    # semantics (side of the chord, negative R, turning sense) against LinuxCNC's.
    a, b = math.radians(20.0), math.radians(20.0 + sweep_deg)
    sx, sy = 2 + 3 * math.cos(a), 1 + 3 * math.sin(a)
    ex, ey = 2 + 3 * math.cos(b), 1 + 3 * math.sin(b)
    code = "G3" if sweep_deg > 0 else "G2"
    tail = (
        f"R{-3 if abs(sweep_deg) > 180 else 3}" if form == "R" else f"I{2 - sx:.6f} J{1 - sy:.6f}"
    )
    text = (
        f"G17 G21 G90 G91.1 G94 F100\nG0 X{sx:.6f} Y{sy:.6f}\n"
        f"{code} X{ex:.6f} Y{ey:.6f} {tail}\nM2\n"
    )
    read = gcode_reader.read(text)
    verdict = rs274.run(text)
    assert verdict.accepted, verdict.describe()
    _assert_same_moves(verdict, read)
    assert read.cuts[0].sweep_rad == pytest.approx(math.radians(sweep_deg), abs=1e-5)


def _with_last_arc_end_pushed_out(written: gcode_reader.Program, by: float) -> str:
    """The program with its last arc's end moved radially outwards by ``by``."""
    arc = [m for m in written.cuts if m.motion in (2, 3)][-1]
    assert arc.centre is not None
    ex, ey = arc.xy_end
    r = math.hypot(ex - arc.centre[0], ey - arc.centre[1])
    nx = ex + by * (ex - arc.centre[0]) / r
    ny = ey + by * (ey - arc.centre[1]) / r
    words = arc.block.text.split()
    words[1], words[2] = f"X{nx:.4f}", f"Y{ny:.4f}"
    lines = [b.text for b in written.blocks]
    lines[arc.block.line - 1] = " ".join(words)
    return "\n".join(lines) + "\n"


def test_rs274_rejects_an_arc_whose_radii_differ(rs274: Rs274) -> None:
    written = program("sharp", units="mm", decimals=4).program
    verdict = rs274.run(_with_last_arc_end_pushed_out(written, 0.05))
    assert not verdict.accepted
    assert verdict.returncode != 0
    assert any("Radius to end of arc differs" in e for e in verdict.errors), verdict.describe()


def test_tight_limit_rejects_a_mismatch_just_over_it_and_accepts_one_under(rs274: Rs274) -> None:
    # Radii differing by 0.0015 mm on a 0.5 mm arc (0.3 %): LinuxCNC's default tolerance
    # (0.028 mm) would let it through; the tight one (0.001 mm) is in force. 0.0009 passes.
    over = "G17 G21 G90 G91.1 G94 F100\nG0 X0 Y0\nG2 X1 Y0 I0.50075 J0\nM2\n"
    under = "G17 G21 G90 G91.1 G94 F100\nG0 X0 Y0\nG2 X1 Y0 I0.50045 J0\nM2\n"
    assert not rs274.run(over).accepted
    assert rs274.run(under).accepted


def test_an_error_printed_with_exit_code_zero_is_still_a_rejection(rs274: Rs274) -> None:
    # In "continue" mode rs274 prints the error and exits 0; the verdict must not be fooled.
    bad = "G17 G21 G90 G91.1 G94 F100\nG0 X0 Y0\nG1 X1 Y0 Q7\nM2\n"
    verdict = rs274.run(bad, continue_on_error=True)
    assert verdict.returncode == 0
    assert verdict.errors
    assert not verdict.accepted
    missing_end = "G17 G21 G90 G91.1 G94 F100\nG0 X0 Y0\nG1 X1 Y0\n"
    assert not rs274.run(missing_end).accepted
