"""machine(): sides, directions, order, leads, tabs and refusals, checked against the
independent offset oracle (tests/support/offset_oracle.py)."""

from __future__ import annotations

import math
from pathlib import Path
from typing import Literal

import pytest

from arcspline.drawings import DrawingOptions, approximate_drawing, read_svg
from arcspline.geometry import DEFAULT_LIMITS, CircularArc, GeometryError, Line, PathSpline, Point
from arcspline.machining import Machined, MachiningOptions, Tabs, machine
from tests.support import offset_oracle as oracle

from .oracle_view import contours, crosses_itself, segments
from .shapes import (
    circle,
    dumbbell,
    fitted,
    polygon,
    rectangle,
    square_with_two_holes,
    star,
)

#: The tool paths are exact offsets of exact lines and arcs: only rounding separates them.
TOL = 1e-7
TEXT_SVG = Path("/work/shared/corpus/svg/domoszlai__juicy-gcode__testtext.svg")


def _check(
    spline: PathSpline, machined: Machined, radius: float, sides: oracle.SideSpec
) -> oracle.OffsetReport:
    paths = contours(machined.spline)
    report = oracle.check_offset(contours(spline), paths, radius, sides)
    assert report.ok(radius, TOL), report.describe()
    return report


def _rows(machined: Machined, k: int, role: str) -> list[oracle.OSeg]:
    segs = segments(machined.spline.subpaths[k].spline)
    return [s for s, r in zip(segs, machined.roles[k], strict=True) if r == role]


def test_square_with_two_holes_auto_climb() -> None:
    spline = square_with_two_holes()
    machined = machine(spline, MachiningOptions(6.0), DEFAULT_LIMITS)
    plans = machined.contours
    assert [p.source for p in plans[:2]] in ([1, 2], [2, 1])  # holes before the outline
    assert plans[2].source == 0
    by_source = {p.source: p for p in plans}
    assert by_source[0].cut == "outside"
    assert by_source[0].depth == 0
    assert (by_source[1].cut, by_source[2].cut) == ("inside", "inside")
    assert by_source[1].depth == by_source[2].depth == 1
    # Climb with M3: outside clockwise, holes anticlockwise, measured on the cut rows.
    for k, plan in enumerate(plans):
        area = oracle.signed_area(_rows(machined, k, "cut"))
        assert (area < 0) == (plan.cut == "outside"), (plan, area)
        assert plan.clockwise == (plan.cut == "outside")
    _check(spline, machined, 3.0, ["outside", "inside", "inside"])
    assert machined.warnings == ()
    assert machined.source_max_deviation == spline.stats.max_deviation


def test_conventional_reverses_every_loop() -> None:
    spline = square_with_two_holes()
    machined = machine(spline, MachiningOptions(6.0, direction="conventional"), DEFAULT_LIMITS)
    for k, plan in enumerate(machined.contours):
        area = oracle.signed_area(_rows(machined, k, "cut"))
        assert (area > 0) == (plan.cut == "outside")
    _check(spline, machined, 3.0, ["outside", "inside", "inside"])


def test_the_rapid_length_runs_from_the_origin_through_every_path() -> None:
    machined = machine(square_with_two_holes(), MachiningOptions(6.0), DEFAULT_LIMITS)
    here, total = (0.0, 0.0), 0.0
    for sub in machined.spline.subpaths:
        segs = segments(sub.spline)
        total += math.dist(here, segs[0].start)
        here = segs[-1].end
    assert machined.rapid_length == pytest.approx(total, rel=1e-12)


def test_leads_are_tangent_quarter_arcs_on_the_waste_side() -> None:
    spline = square_with_two_holes()
    machined = machine(spline, MachiningOptions(6.0, lead_radius=2.0), DEFAULT_LIMITS)
    everything = [s for c in contours(spline) for s in c]
    for k, roles in enumerate(machined.roles):
        assert roles[0] == "lead_in"
        assert roles[-1] == "lead_out"
        segs = segments(machined.spline.subpaths[k].spline)
        # No corner where a lead joins the cut (G1 continuity), measured by the oracle.
        joints = oracle.corners(segs, closed=False)
        assert 1 not in joints
        assert len(segs) - 1 not in joints
        for lead in (segs[0], segs[-1]):
            assert lead.kind == "arc"
            assert abs(lead.sweep_rad) == pytest.approx(math.pi / 2)
            assert lead.radius <= 2.0 + 1e-12
        # The free ends are in the waste, farther from every contour than the tool radius.
        free = oracle.distance_to([segs[0].start, segs[-1].end], everything)
        assert min(free) > 3.0
    _check(spline, machined, 3.0, ["outside", "inside", "inside"])


def test_no_lead_fits_a_hole_barely_larger_than_the_tool() -> None:
    spline = fitted(rectangle(0, 0, 30, 30), circle(15, 15, 3.2))
    machined = machine(spline, MachiningOptions(6.0), DEFAULT_LIMITS)
    hole = next(k for k, p in enumerate(machined.contours) if p.source == 1)
    assert set(machined.roles[hole]) == {"cut"}
    assert [source for source, _ in machined.warnings] == [1]
    assert "no lead arc" in machined.warnings[0][1]
    _check(spline, machined, 3.0, ["outside", "inside"])


def test_a_slot_narrower_than_the_tool_is_left_with_a_warning() -> None:
    # A plate with a 4 mm slot cut into it from the top edge; a 6 mm tool cannot enter it.
    outline = polygon([(0, 0), (40, 0), (40, 30), (22, 30), (22, 10), (18, 10), (18, 30), (0, 30)])
    spline = fitted(outline)
    machined = machine(spline, MachiningOptions(6.0), DEFAULT_LIMITS)
    assert machined.warnings
    assert all(source == 0 for source, _ in machined.warnings)
    report = _check(spline, machined, 3.0, "outside")
    assert report.reachable < report.samples  # the slot's walls are not reachable


@pytest.mark.parametrize("radius", [2.5, 3.0])  # smaller than the tool, and exactly its size
def test_a_hole_not_larger_than_the_tool_is_left_uncut_and_named(radius: float) -> None:
    spline = fitted(rectangle(0, 0, 30, 30), circle(15, 15, radius))
    machined = machine(spline, MachiningOptions(6.0), DEFAULT_LIMITS)
    assert [p.source for p in machined.contours] == [0]
    ((source, words),) = machined.warnings
    assert source == 1
    assert "does not fit" in words
    assert "left uncut" in words
    _check(spline, machined, 3.0, ["outside", None])
    # Alone, with nothing else to cut, it is refused.
    with pytest.raises(GeometryError) as caught:
        machine(fitted(circle(15, 15, radius)), MachiningOptions(6.0, cut="inside"))
    assert caught.value.field == "path.subpaths[0]"
    assert caught.value.kind == "tool_too_large"


@pytest.mark.parametrize("cut", ["outside", "inside"])
def test_a_star_with_sharp_concave_tips(cut: Literal["outside", "inside"]) -> None:
    spline = fitted(star(0.0, 0.0, 30.0, 12.0))
    machined = machine(spline, MachiningOptions(4.0, cut=cut), DEFAULT_LIMITS)
    assert {p.cut for p in machined.contours} == {cut}
    _check(spline, machined, 2.0, cut)


def test_mitre_joins_keep_the_tool_clear_too() -> None:
    spline = fitted(star(0.0, 0.0, 30.0, 12.0))
    machined = machine(spline, MachiningOptions(4.0, join="mitre"), DEFAULT_LIMITS)
    report = oracle.check_offset(contours(spline), contours(machined.spline), 2.0, "outside")
    assert report.closest_mm >= 2.0 - TOL, report.describe()


def test_an_open_contour_is_cut_on_its_line() -> None:
    line = (Line(Point(0.0, 0.0), Point(10.0, 0.0)), Line(Point(10.0, 0.0), Point(10.0, 5.0)))
    spline = fitted(rectangle(-5, -5, 20, 20), line, closed=[True, False])
    machined = machine(spline, MachiningOptions(2.0), DEFAULT_LIMITS)
    open_k = next(k for k, p in enumerate(machined.contours) if p.source == 1)
    assert machined.contours[open_k].cut == "on"
    assert machined.contours[open_k].clockwise is None
    assert machined.contours[open_k].depth == 1
    assert open_k == 0  # inside the rectangle: cut first
    got = segments(machined.spline.subpaths[open_k].spline)
    assert [(s.start, s.end) for s in got] == [
        ((0.0, 0.0), (10.0, 0.0)),
        ((10.0, 0.0), (10.0, 5.0)),
    ]


@pytest.mark.parametrize("cut", ["inside", "outside"])
def test_an_open_contour_with_a_side_is_refused(cut: Literal["outside", "inside"]) -> None:
    line = (Line(Point(0.0, 0.0), Point(10.0, 0.0)),)
    spline = fitted(rectangle(-5, -5, 20, 20), line, closed=[True, False])
    with pytest.raises(GeometryError) as caught:
        machine(spline, MachiningOptions(2.0, cut=cut), DEFAULT_LIMITS)
    assert caught.value.field == "path.subpaths[1]"


def test_a_crossing_contour_with_a_side_is_refused() -> None:
    bow_tie = polygon([(0, 0), (10, 10), (10, 0), (0, 10)])
    spline = fitted(rectangle(-20, -20, 30, 30), bow_tie)
    with pytest.raises(GeometryError) as caught:
        machine(spline, MachiningOptions(2.0), DEFAULT_LIMITS)
    assert caught.value.field == "path.subpaths[1]"
    assert caught.value.kind == "crossing"
    on = machine(spline, MachiningOptions(2.0, cut="on"), DEFAULT_LIMITS)
    assert {p.cut for p in on.contours} == {"on"}


def test_tabs_are_even_spans_of_width_plus_diameter_on_outside_paths_only() -> None:
    spline = square_with_two_holes()
    machined = machine(spline, MachiningOptions(6.0, tabs=Tabs(4, 3.0, 1.0)), DEFAULT_LIMITS)
    for k, plan in enumerate(machined.contours):
        roles = machined.roles[k]
        if plan.cut != "outside":
            assert "tab" not in roles
            continue
        segs = segments(machined.spline.subpaths[k].spline)
        runs, start, travelled = [], None, 0.0
        for seg, role in zip(segs, roles, strict=True):
            if role == "lead_in":
                continue
            if role == "tab" and start is None:
                start = travelled
            if role != "tab" and start is not None:
                runs.append((start, travelled))
                start = None
            travelled += seg.length
        loop = sum(s.length for s, r in zip(segs, roles, strict=True) if r in ("cut", "tab"))
        assert len(runs) == 4
        for n, (a, b) in enumerate(runs):
            assert b - a == pytest.approx(9.0, abs=1e-9)
            assert 0.5 * (a + b) == pytest.approx((n + 0.5) * loop / 4, abs=1e-9)
    _check(spline, machined, 3.0, ["outside", "inside", "inside"])


def test_controller_mode_refuses_a_concave_arc_tighter_than_the_tool() -> None:
    # A plate whose top edge has a half-round bite of radius 4 into it.
    bite = CircularArc(Point(24.0, 40.0), Point(16.0, 40.0), Point(20.0, 40.0), 4.0, 0.0, -math.pi)
    outline = (
        Line(Point(0.0, 0.0), Point(40.0, 0.0)),
        Line(Point(40.0, 0.0), Point(40.0, 40.0)),
        Line(Point(40.0, 40.0), Point(24.0, 40.0)),
        bite,
        Line(Point(16.0, 40.0), Point(0.0, 40.0)),
        Line(Point(0.0, 40.0), Point(0.0, 0.0)),
    )
    spline = fitted(outline)
    with pytest.raises(GeometryError) as caught:
        machine(spline, MachiningOptions(10.0, compensation="controller"), DEFAULT_LIMITS)
    assert caught.value.field == "path.subpaths[0]"
    assert caught.value.kind == "tool_too_large"
    computed = machine(spline, MachiningOptions(10.0), DEFAULT_LIMITS)
    _check(spline, computed, 5.0, "outside")
    fine = machine(spline, MachiningOptions(6.0, compensation="controller"), DEFAULT_LIMITS)
    _check(spline, fine, 3.0, "outside")


def test_controller_mode_programs_the_contours_and_keeps_the_tool_paths() -> None:
    spline = square_with_two_holes()
    machined = machine(spline, MachiningOptions(6.0, compensation="controller"), DEFAULT_LIMITS)
    _check(spline, machined, 3.0, ["outside", "inside", "inside"])
    # The programmed cut rows lie on the contours themselves.
    every = [s for c in contours(spline) for s in c]
    for k, roles in enumerate(machined.programmed_roles):
        segs = segments(machined.programmed.subpaths[k].spline)
        cut = [s for s, r in zip(segs, roles, strict=True) if r == "cut"]
        points = [s.point(t) for s in cut for t in (0.0, 0.3, 0.7)]
        assert max(oracle.distance_to(points, every)) < 1e-9
        assert machined.approaches[k] is not None


def test_controller_mode_needs_leads() -> None:
    with pytest.raises(GeometryError) as caught:
        machine(
            square_with_two_holes(),
            MachiningOptions(6.0, compensation="controller", lead_radius=0.0),
            DEFAULT_LIMITS,
        )
    assert caught.value.field == "machining.lead_radius"


def _text() -> PathSpline:
    drawing = read_svg(TEXT_SVG.read_bytes())
    return approximate_drawing(drawing, DrawingOptions(0.01), DEFAULT_LIMITS).spline


def test_text_outlines_closed_over_themselves_by_a_hair_are_cut() -> None:
    # "TEST" in a decorative font: letters T, E, S, T, one outline each. The joined outlines
    # of E and S close with a spike of 0.2 µm that crosses back over the outline (found by
    # the polygon test): a drawing's rounding, far below the tolerance, cut out before the
    # offset and counted in the bound — not a figure eight to refuse.
    spline = _text()
    crossing = [i for i, c in enumerate(contours(spline)) if crosses_itself(c)]
    assert crossing == [1, 2]
    machined = machine(spline, MachiningOptions(0.8, tabs=Tabs(2, 1.0, 0.5)), DEFAULT_LIMITS)
    assert [p.cut for p in machined.contours] == ["outside"] * 4
    # The bound grows by half the longest loop cut out, which is under twice the tolerance.
    moved = machined.source_max_deviation - spline.stats.max_deviation
    assert 0.0 < moved < spline.tolerance
    # Against the fitted outlines (spikes included) the tool keeps its radius less what the
    # cut moved them; 1e-6 is rounding.
    report = oracle.check_offset(contours(spline), contours(machined.spline), 0.4, "outside")
    assert report.ok(0.4, moved + 1e-6), report.describe()
    on = machine(spline, MachiningOptions(0.8, cut="on"), DEFAULT_LIMITS)
    assert len(on.contours) == 4


def test_a_hole_whose_neck_is_narrower_than_the_tool_splits_in_two_paths() -> None:
    spline = fitted(rectangle(0, 0, 60, 40), dumbbell(15.0, 45.0, 20.0, 6.0, 2.0))
    machined = machine(spline, MachiningOptions(6.0), DEFAULT_LIMITS)
    sources = [p.source for p in machined.contours]
    assert sources == [1, 1, 0]
    assert machined.warnings
    assert {source for source, _ in machined.warnings} == {1}
    for k in (0, 1):
        assert machined.roles[k][0] == "lead_in"
        assert machined.roles[k][-1] == "lead_out"
    report = _check(spline, machined, 3.0, ["outside", "inside"])
    assert report.reachable < report.samples  # the neck's walls
    with pytest.raises(GeometryError) as caught:
        machine(spline, MachiningOptions(6.0, compensation="controller"), DEFAULT_LIMITS)
    assert caught.value.field == "path.subpaths[1]"
    assert caught.value.kind == "tool_too_large"


def test_an_island_in_a_hole_is_a_part_again() -> None:
    plate, hole, island = rectangle(0, 0, 80, 60), circle(40, 30, 22), rectangle(34, 24, 46, 36)
    spline = fitted(island, plate, hole)
    machined = machine(spline, MachiningOptions(4.0), DEFAULT_LIMITS)
    assert [(p.source, p.cut, p.depth) for p in machined.contours] == [
        (0, "outside", 2),
        (2, "inside", 1),
        (1, "outside", 0),
    ]
    _check(spline, machined, 2.0, ["outside", "outside", "inside"])


def _half_circles(
    cx: float, cy: float, r: float, half_chord: float | None = None
) -> tuple[CircularArc, CircularArc]:
    """A circle as SVG's <circle> comes: two clockwise half arcs, ends exactly on a line
    (``half_chord`` from the centre: the reader's rounding may leave it an ulp off ``r``)."""
    h = r if half_chord is None else half_chord
    a, b = Point(cx + h, cy), Point(cx - h, cy)
    return (
        CircularArc(a, b, Point(cx, cy), r, 0.0, -math.pi),
        CircularArc(b, a, Point(cx, cy), r, math.pi, -math.pi),
    )


@pytest.mark.parametrize("hole", ["svg", "svg as read", "two", "three"])
def test_a_round_hole_drawn_as_few_arcs(hole: str) -> None:
    # The two neighbours of a circle in two halves share both their joints.
    shape = {
        "svg": _half_circles(0.0, 55.0, 8.0),
        # abey79__vpype__percent_size_viewbox.svg as read: the ends 2 ulps inside the radius.
        "svg as read": _half_circles(
            0.0, 52.916666666666664, 10.583333333333334, 10.583333333333332
        ),
        "two": circle(0, 55, 8, ccw=False, parts=2),
        "three": circle(0, 55, 8, ccw=False, parts=3),
    }[hole]
    spline = fitted(rectangle(-20, 35, 20, 75), shape)
    machined = machine(spline, MachiningOptions(6.0), DEFAULT_LIMITS)
    assert [(p.source, p.cut) for p in machined.contours] == [(1, "inside"), (0, "outside")]
    _check(spline, machined, 3.0, ["outside", "inside"])
