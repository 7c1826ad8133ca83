"""The optional parts of a program: 2.5-D moves, line numbers, the comment header, and arcs
turned into lines on request (``min_arc_length``, ``max_radius``)."""

from __future__ import annotations

import re

import numpy as np
import pytest

from tests.support import oracle

from . import readback
from .cases import program


def test_two_and_a_half_d_retracts_rapids_plunges_cuts_and_retracts() -> None:
    w = program("paper-cw", safe_z=5.0, cut_z=-1.5, plunge_feed_rate=150.0)
    moves = w.program.moves
    retract, rapid, plunge, *cuts, last = moves
    assert (retract.motion, retract.block.words) == (0, {"Z": 5.0})
    assert rapid.motion == 0
    assert rapid.block.words.keys() == {"X", "Y"}
    assert rapid.end[2] == 5.0
    assert (plunge.motion, plunge.block.words) == (1, {"Z": -1.5, "F": 150.0})
    assert plunge.xy_end == rapid.xy_end
    assert len(cuts) == len(w.spline)
    assert all(m.is_cut and m.end[2] == -1.5 and m.feed == 1200.0 for m in cuts)
    assert cuts[0].block.words["F"] == 1200.0, "the first cut restores the cutting feed"
    assert all("F" not in m.block.words for m in cuts[1:])
    assert (last.motion, last.block.words) == (0, {"Z": 5.0})
    assert w.program.ended


def test_without_depths_the_program_never_moves_z() -> None:
    w = program("paper")
    assert all("Z" not in b.words for b in w.program.blocks)
    assert w.program.moves[0].motion == 0
    assert w.program.moves[0].block.words.keys() == {"X", "Y"}


def test_plunge_feed_defaults_to_the_cutting_feed() -> None:
    w = program("paper", safe_z=2.0, cut_z=0.0)
    plunge = w.program.moves[2]
    assert plunge.block.words == {"Z": 0.0}
    assert plunge.feed == 1200.0


def test_line_numbers_count_every_block_and_skip_comment_lines() -> None:
    w = program("paper", line_numbers=True, comments=True, safe_z=3.0, cut_z=-1.0)
    numbers = [b.number for b in w.program.blocks if b.g or b.m or b.words]
    assert numbers == [10 * k for k in range(1, len(numbers) + 1)]
    header = [b for b in w.program.blocks if not (b.g or b.m or b.words)]
    assert header
    assert all(b.number is None for b in header)


def test_comment_header_states_tolerance_strategy_counts_and_deviations() -> None:
    w = program("paper", units="mm", decimals=3, comments=True)
    text = " ".join(w.program.comments)
    stats = w.spline.stats
    assert f"tolerance {w.spline.tolerance:g} mm" in text
    assert f"strategy {w.spline.strategy}" in text
    assert f"{stats.arc_count} arcs, {stats.line_count} lines" in text
    arcs = sum(m.motion in (2, 3) for m in w.program.cuts)
    assert (
        f"{len(w.program.cuts)} moves, {arcs} arcs G2 G3, {len(w.program.cuts) - arcs} lines G1"
        in text
    )
    spline_dev = float(re.search(r"max deviation ([0-9.e-]+) mm", text).group(1))  # type: ignore[union-attr]
    assert spline_dev == pytest.approx(stats.max_deviation, rel=1e-5)
    stated = float(re.search(r"from the curve ([0-9.e-]+) mm", text).group(1))  # type: ignore[union-attr]
    assert stats.max_deviation - w.ulp <= stated <= w.spline.tolerance + w.ulp
    # The stated figure is the writer's own measurement; the oracle's agrees to the rounding.
    measured = readback.deviation(w.spiral, w.spline, w.program)
    assert measured == pytest.approx(stated, abs=0.1 * w.ulp)


def test_no_comments_unless_asked() -> None:
    assert "(" not in program("paper").text
    assert ";" not in program("paper").text


@pytest.mark.parametrize(
    "options",
    [{"max_radius": 10.0}, {"min_arc_length": 0.3}, {"max_radius": 10.0, "min_arc_length": 0.3}],
    ids=lambda o: "+".join(o),
)
def test_arcs_become_lines_on_request_only_where_the_chord_keeps_the_tolerance(
    options: dict[str, float],
) -> None:
    w = program("paper", units="mm", decimals=4, **options)
    tol = w.spline.tolerance
    converted = kept = 0
    for move, seg in zip(w.program.cuts, w.spline.segments, strict=True):
        requested = seg.radius > options.get("max_radius", np.inf) or seg.length < options.get(
            "min_arc_length", 0.0
        )
        if not requested:
            assert move.motion in (2, 3), move.block.text
            continue
        chord = readback.chord_deviation_sampled(
            w.spiral, seg.u_start, seg.u_end, seg.start, seg.end
        )
        if move.motion == 1:
            converted += 1
            assert chord <= tol * (1 + 1e-9), move.block.text
        else:
            kept += 1
            assert chord > tol * (1 - 1e-9), move.block.text
    assert converted, "the case should exercise both outcomes"
    assert kept, "the case should exercise both outcomes"
    measured = readback.deviation(w.spiral, w.spline, w.program)
    assert measured <= tol + w.ulp + oracle.rounding_slack(np.asarray(w.spiral.control_points))
