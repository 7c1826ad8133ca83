"""offset_subpath on exact shapes, measured by the independent oracle."""

from __future__ import annotations

import math

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from arcspline.geometry.curves.segments import CircularArc, Line
from arcspline.geometry.errors import GeometryError
from arcspline.geometry.offset import OffsetOptions, offset_subpath
from arcspline.geometry.spline import Point
from tests.geometry.offset import shapes
from tests.geometry.offset.checks import assert_exact, assert_offset


@pytest.mark.parametrize(("side", "radius"), [("left", 4.0), ("right", 6.0)])
def test_a_circle_offsets_to_the_concentric_circle(side: str, radius: float) -> None:
    circle = shapes.circle((1.0, 2.0), 5.0)  # anticlockwise: its inside is on the left
    out = offset_subpath(circle, True, OffsetOptions(1.0, side))  # type: ignore[arg-type]
    assert out.notes == ()
    (loop,) = out.subpaths
    assert_exact(out.subpaths)
    for arc in loop.segments:
        assert isinstance(arc, CircularArc)
        assert arc.center == (1.0, 2.0)
        assert arc.radius == radius
    assert sum(a.sweep_rad for a in loop.segments) == pytest.approx(2 * math.pi)  # type: ignore[union-attr]


def test_a_square_offset_outside_has_round_corners_of_the_distance() -> None:
    square = shapes.polygon([(0, 0), (4, 0), (4, 4), (0, 4)])
    out = offset_subpath(square, True, OffsetOptions(0.5, "right"))
    (loop,) = out.subpaths
    assert_exact(out.subpaths)
    arcs = [s for s in loop.segments if isinstance(s, CircularArc)]
    assert sorted(a.center for a in arcs) == [(0, 0), (0, 4), (4, 0), (4, 4)]
    assert all(a.radius == 0.5 and a.sweep_rad == pytest.approx(math.pi / 2) for a in arcs)
    assert_offset([square], out.subpaths, 0.5, "right")


def test_a_mitred_square_has_sharp_corners_within_the_limit() -> None:
    square = shapes.polygon([(0, 0), (4, 0), (4, 4), (0, 4)])
    out = offset_subpath(square, True, OffsetOptions(0.5, "right", join="mitre"))
    (loop,) = out.subpaths
    assert_exact(out.subpaths)
    corners = sorted(s.start for s in loop.segments)
    assert corners == [(-0.5, -0.5), (-0.5, 4.5), (4.5, -0.5), (4.5, 4.5)]
    # √2·0.5 from the corner: beyond a limit of 1.2·d the corners are round again
    rounded = offset_subpath(square, True, OffsetOptions(0.5, "right", "mitre", 1.2))
    assert sum(isinstance(s, CircularArc) for s in rounded.subpaths[0].segments) == 4


def test_the_inside_of_a_square_is_the_smaller_square() -> None:
    square = shapes.polygon([(0, 0), (4, 0), (4, 4), (0, 4)])
    out = offset_subpath(square, True, OffsetOptions(1.5, "left"))
    (loop,) = out.subpaths
    assert sorted(s.start for s in loop.segments) == [
        (1.5, 1.5),
        (1.5, 2.5),
        (2.5, 1.5),
        (2.5, 2.5),
    ]
    assert_exact(out.subpaths)


@pytest.mark.parametrize("d", [0.3, 0.9, 1.7])
@pytest.mark.parametrize("side", ["left", "right"])
def test_a_star_with_sharp_concave_tips(d: float, side: str) -> None:
    star = shapes.star(5, 10.0, 4.0)
    out = offset_subpath(star, True, OffsetOptions(d, side))  # type: ignore[arg-type]
    assert len(out.subpaths) == 1
    assert_exact(out.subpaths)
    assert_offset([star], out.subpaths, d, side)  # type: ignore[arg-type]


def test_a_slot_narrower_than_the_tool_is_lost_outside_with_a_note() -> None:
    part = shapes.slotted_square(10.0, 1.0, 5.0)  # the slot is 1 wide and 5 deep
    out = offset_subpath(part, True, OffsetOptions(0.8, "right"))
    assert len(out.subpaths) == 1
    assert_exact(out.subpaths)
    assert [n.kind for n in out.notes] == ["narrow"]
    assert "11" in out.notes[0].message  # the slot's walls and bottom: 5 + 1 + 5
    assert_offset([part], out.subpaths, 0.8, "right")
    # with a thinner tool the slot is followed
    thin = offset_subpath(part, True, OffsetOptions(0.3, "right"))
    assert thin.notes == ()
    assert_offset([part], thin.subpaths, 0.3, "right")


def test_the_inside_of_a_slot_narrower_than_twice_the_tool_vanishes() -> None:
    slot = shapes.polygon([(0, 0), (20, 0), (20, 1.5), (0, 1.5)])
    out = offset_subpath(slot, True, OffsetOptions(0.8, "left"))
    assert out.subpaths == ()
    assert [n.kind for n in out.notes] == ["vanished"]


def test_a_dumbbell_inside_splits_into_two_loops() -> None:
    bell = shapes.dumbbell(2.0, 6.0, 1.0)
    out = offset_subpath(bell, True, OffsetOptions(0.8, "left"))
    assert len(out.subpaths) == 2
    assert {n.kind for n in out.notes} == {"split", "narrow"}
    assert_exact(out.subpaths)
    assert_offset([bell], out.subpaths, 0.8, "left")
    corners = {e.start for e in bell}
    for loop, centre in zip(
        sorted(out.subpaths, key=lambda s: s.segments[0].start), [(0, 0), (6, 0)], strict=True
    ):
        # each disc's inside: an arc of radius 1.2 about its centre, closed across the neck
        # by arcs of radius 0.8 about the neck's corners
        for s in loop.segments:
            assert isinstance(s, CircularArc)
            assert (s.center == centre and s.radius == pytest.approx(1.2)) or (
                s.center in corners and s.radius == 0.8
            )


def test_fillets_tighter_than_the_tool_collapse_into_sharp_corners() -> None:
    part = shapes.rounded_rectangle(10.0, 6.0, 0.5)
    out = offset_subpath(part, True, OffsetOptions(0.8, "left"))
    assert [n.kind for n in out.notes] == ["collapsed"]
    assert "4 arcs" in out.notes[0].message
    (loop,) = out.subpaths
    starts = sorted(c for s in loop.segments for c in s.start)
    assert starts == pytest.approx([0.8, 0.8, 0.8, 0.8, 5.2, 5.2, 9.2, 9.2], abs=1e-12)
    assert_offset([part], out.subpaths, 0.8, "left")


@pytest.mark.parametrize(("side", "pieces"), [("left", 0), ("right", 1)])
def test_an_open_hairpin_is_trimmed_globally(side: str, pieces: int) -> None:
    hairpin = shapes.chained(
        [Line(Point(0, 0), Point(5, 0)), Line(Point(5, 0), Point(5, 0.5)),
         Line(Point(5, 0.5), Point(0, 0.5))],
        closed=False,
    )  # fmt: skip
    out = offset_subpath(hairpin, False, OffsetOptions(0.4, side))  # type: ignore[arg-type]
    assert len(out.subpaths) == pieces
    assert all(not s.closed for s in out.subpaths)
    assert_exact(out.subpaths)
    assert_offset([hairpin], out.subpaths, 0.4, side)  # type: ignore[arg-type]


def test_an_open_zigzag_left_and_right() -> None:
    zigzag = shapes.chained(
        [Line(Point(2.0 * k, 1.5 * (k % 2)), Point(2.0 * k + 2, 1.5 * (1 - k % 2)))
         for k in range(6)],
        closed=False,
    )  # fmt: skip
    for side in ("left", "right"):
        out = offset_subpath(zigzag, False, OffsetOptions(0.6, side))  # type: ignore[arg-type]
        assert_exact(out.subpaths)
        assert_offset([zigzag], out.subpaths, 0.6, side)  # type: ignore[arg-type]


@pytest.mark.parametrize("scale", [1e-6, 1.0, 1e5])
def test_tiny_and_huge_coordinates(scale: float) -> None:
    shift = 1e3 * scale
    star = [
        Line(Point(a.start[0] * scale + shift, a.start[1] * scale - shift),
             Point(a.end[0] * scale + shift, a.end[1] * scale - shift))
        for a in shapes.star(6, 10.0, 5.0)
    ]  # fmt: skip
    d = 0.7 * scale
    for side in ("left", "right"):
        out = offset_subpath(star, True, OffsetOptions(d, side))  # type: ignore[arg-type]
        assert len(out.subpaths) == 1
        assert_exact(out.subpaths)
        assert_offset([star], out.subpaths, d, side, tolerance=1e-9 * shift + 1e-7 * d)  # type: ignore[arg-type]


def test_the_result_runs_in_the_direction_of_travel() -> None:
    cw = shapes.reversed_chain(shapes.circle((0.0, 0.0), 3.0))
    out = offset_subpath(cw, True, OffsetOptions(1.0, "left"))  # left of a clockwise circle: out
    assert all(s.sweep_rad < 0 and s.radius == 4.0 for s in out.subpaths[0].segments)  # type: ignore[union-attr]


@pytest.mark.parametrize(
    ("options", "field"),
    [
        (OffsetOptions(0.0, "left"), "offset.distance"),
        (OffsetOptions(math.inf, "left"), "offset.distance"),
        (OffsetOptions(1.0, "inside"), "offset.side"),
        (OffsetOptions(1.0, "left", mitre_limit=0.5), "offset.mitre_limit"),
        (OffsetOptions(1.0, "left", sliver=-1.0), "offset.sliver"),
    ],
)
def test_bad_options_are_refused_naming_the_field(options: OffsetOptions, field: str) -> None:
    with pytest.raises(GeometryError) as caught:
        offset_subpath(shapes.circle((0, 0), 1.0), True, options)
    assert caught.value.field == field


def test_slivers_are_dropped() -> None:
    bell = shapes.dumbbell(2.0, 6.0, 1.0)
    kept = offset_subpath(bell, True, OffsetOptions(1.8, "left"))
    assert len(kept.subpaths) == 2  # two circles of radius 0.2
    dropped = offset_subpath(bell, True, OffsetOptions(1.8, "left", sliver=0.5))
    assert dropped.subpaths == ()


@settings(max_examples=25, deadline=None)
@given(
    radii=st.lists(st.floats(1.0, 10.0), min_size=5, max_size=14),
    d=st.floats(0.05, 3.0),
    side=st.sampled_from(["left", "right"]),
)
def test_random_star_shaped_polygons(radii: list[float], d: float, side: str) -> None:
    n = len(radii)
    points = [(r * math.cos(2 * math.pi * k / n), r * math.sin(2 * math.pi * k / n))
              for k, r in enumerate(radii)]  # fmt: skip
    polygon = shapes.polygon(points)
    out = offset_subpath(polygon, True, OffsetOptions(d, side))  # type: ignore[arg-type]
    assert_exact(out.subpaths)
    if out.subpaths:
        assert_offset([polygon], out.subpaths, d, side, tolerance=1e-7)  # type: ignore[arg-type]


def test_an_arc_whose_stored_ends_are_a_rounding_off_its_circle_is_offset() -> None:
    # A fitted arc's stored ends may lie 1e-9 (relative) off its circle (the core's own
    # check, segment_table.ARC_RTOL): CadQuery's 1001.dxf has such arcs. Its offset's ends
    # are then that much nearer the neighbouring line than d; the inside must not vanish.
    off = 5e-9  # under 1e-9 × the coordinate scale (15)
    arc = CircularArc(
        Point(10.0, 0.0), Point(10.0, 10.0), Point(10.0, 5.0 + off), 5.0, -0.5 * math.pi, math.pi
    )
    d_shape = [
        Line(Point(0.0, 0.0), Point(10.0, 0.0)),
        arc,
        Line(Point(10.0, 10.0), Point(0.0, 10.0)),
        Line(Point(0.0, 10.0), Point(0.0, 0.0)),
    ]
    result = offset_subpath(d_shape, True, OffsetOptions(1.0, "left"))
    assert len(result.subpaths) == 1, result.notes
    assert_offset([d_shape], result.subpaths, 1.0, "inside")
