"""The offset oracle against answers worked out by hand: exact distances to lines and arcs,
the broad phase against brute-force sampling, offsets of a circle, a square (round, mitre,
chamfered and inside), a slot narrower than the tool, open contours, and wrong offsets that
it must reject."""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pytest

from arcspline.geometry.curves.segments import CircularArc, Line
from arcspline.geometry.spline import Point
from tests.support.offset_oracle import (
    OSeg,
    SegmentIndex,
    arc,
    check_each,
    check_offset,
    circle,
    corners,
    distance_to,
    from_core,
    from_json,
    line,
    polygon,
    signed_area,
)

#: Accuracy the oracle promises on its reported extremes, relative to the drawing's size.
RTOL = 1e-9

# -- exact distances ------------------------------------------------------------------------


def test_distance_to_a_line_segment_is_the_clamped_projection() -> None:
    seg = [line((0, 0), (10, 0))]
    points = np.array([[5, 3], [-3, 4], [13, -4], [0, 0], [10, 0], [7, -2]])
    # Beside the segment: |y|; beyond its ends: the distance to the end (3-4-5 triangles).
    assert distance_to(points, seg).tolist() == [3, 5, 5, 0, 0, 2]


def test_distance_to_an_arc_is_radial_inside_its_sweep_else_to_an_end() -> None:
    quarter = [arc((0, 0), 5, 0.0, math.pi / 2)]  # from (5, 0) anticlockwise to (0, 5)
    points = np.array([[3, 4], [6, 8], [0, 0], [-3, -4], [5, -3], [-3, 5]])
    expected = [0.0, 5.0, 5.0, math.hypot(8, 4), 3.0, 3.0]
    assert distance_to(points, quarter) == pytest.approx(expected, abs=1e-12)
    # The same arc run clockwise (from (0, 5) to (5, 0)) is the same set of points.
    backwards = [arc((0, 0), 5, math.pi / 2, -math.pi / 2)]
    assert distance_to(points, backwards) == pytest.approx(expected, abs=1e-12)


def test_distance_to_a_full_circle_is_the_radial_gap() -> None:
    rng = np.random.default_rng(7)
    points = rng.uniform(-30, 30, (5000, 2))
    got = distance_to(points, circle((1.0, -2.0), 10.0))
    expected = np.abs(np.hypot(points[:, 0] - 1.0, points[:, 1] + 2.0) - 10.0)
    assert np.max(np.abs(got - expected)) <= 1e-12


def _random_segments(rng: np.random.Generator, n: int) -> list[OSeg]:
    segs = []
    for k in range(n):
        x, y = rng.uniform(0, 100, 2)
        if k % 2:
            segs.append(line((x, y), (x + rng.normal(0, 5), y + rng.normal(0, 5))))
        else:
            sweep = rng.uniform(-2 * math.pi, 2 * math.pi)
            segs.append(arc((x, y), rng.uniform(0.1, 8), rng.uniform(-math.pi, math.pi), sweep))
    return segs


def _sampled_distance(points: np.ndarray, segs: list[OSeg], n: int) -> tuple[np.ndarray, float]:
    """Min distance to ``n`` points on each segment (by its own parametrisation), and the
    largest gap between consecutive samples (the sampled distance exceeds the exact one by
    at most half of it)."""
    best = np.full(len(points), np.inf)
    gap = 0.0
    t = np.linspace(0.0, 1.0, n)
    for s in segs:
        if s.kind == "line":
            xy = np.asarray(s.start) + t[:, None] * (np.asarray(s.end) - np.asarray(s.start))
        else:
            theta = s.start_angle_rad + t * s.sweep_rad
            xy = np.asarray(s.centre) + s.radius * np.stack([np.cos(theta), np.sin(theta)], -1)
        gap = max(gap, float(np.max(np.hypot(*np.diff(xy, axis=0).T))))
        d = np.hypot(points[:, None, 0] - xy[None, :, 0], points[:, None, 1] - xy[None, :, 1])
        best = np.minimum(best, d.min(axis=1))
    return best, gap


def test_the_broad_phase_finds_the_nearest_segment_near_and_far() -> None:
    rng = np.random.default_rng(11)
    segs = _random_segments(rng, 300)
    # Near the segments, outside the grid, and very far (through the coarser grids).
    points = np.concatenate(
        [rng.uniform(-10, 110, (400, 2)), rng.uniform(-400, 500, (100, 2)), [[1e5, -3e4]]]
    )
    exact = SegmentIndex(segs).distance(points)
    sampled, gap = _sampled_distance(points, segs, 2001)
    assert np.all(exact <= sampled + 1e-12)
    assert np.all(sampled <= exact + gap / 2 + 1e-12)


def test_the_broad_phase_copes_with_a_single_point_and_a_line_of_segments() -> None:
    dot = [line((3, 4), (3, 4))]
    assert distance_to(np.array([[0, 0]]), dot).tolist() == [5]
    row = [line((x, 0), (x + 1, 0)) for x in range(50)]  # a box of zero height
    assert distance_to(np.array([[25.5, 2], [-3, 4], [60, 0]]), row).tolist() == [2, 5, 10]


# -- readers ----------------------------------------------------------------------------------


def test_from_core_and_from_json_read_the_same_segments() -> None:
    core: list[Any] = [
        Line(Point(0.0, 0.0), Point(10.0, 0.0)),
        CircularArc(
            Point(10.0, 0.0), Point(10.0, 10.0), Point(10.0, 5.0), 5.0, -math.pi / 2, math.pi
        ),
    ]
    answer: list[dict[str, Any]] = [
        {"type": "line", "start": [0.0, 0.0], "end": [10.0, 0.0]},
        {
            "type": "arc",
            "start": [10.0, 0.0],
            "end": [10.0, 10.0],
            "center": [10.0, 5.0],
            "radius": 5.0,
            "direction": "ccw",
            "start_angle_rad": -math.pi / 2,
            "sweep_rad": math.pi,
        },
    ]
    assert from_core(core) == from_json(answer)
    assert from_json(answer)[1].start_angle_rad == pytest.approx(-math.pi / 2)
    assert from_json(answer)[1].point(0.5) == pytest.approx((15.0, 5.0))
    with pytest.raises(ValueError, match="neither"):
        from_json([{"type": "spline", "start": [0, 0], "end": [1, 1]}])


def test_signed_area_counts_the_arcs_circular_segments() -> None:
    assert signed_area(circle((3, 4), 2.0)) == pytest.approx(4 * math.pi)
    assert signed_area(circle((3, 4), 2.0, anticlockwise=False)) == pytest.approx(-4 * math.pi)
    assert signed_area(polygon([(0, 0), (10, 0), (10, 10), (0, 10)])) == pytest.approx(100)


# -- offsets with known answers ---------------------------------------------------------------


def _rounded_square(side: float, d: float) -> list[OSeg]:
    """The outside offset of the anticlockwise square ``[0, side]²`` by ``d``: its sides
    pushed out by ``d``, joined by quarter arcs of radius ``d`` about its corners."""
    s, q = side, math.pi / 2
    return [
        line((0, -d), (s, -d)),
        arc((s, 0), d, -q, q),
        line((s + d, 0), (s + d, s)),
        arc((s, s), d, 0.0, q),
        line((s, s + d), (0, s + d)),
        arc((0, s), d, q, q),
        line((-d, s), (-d, 0)),
        arc((0, 0), d, 2 * q, q),
    ]


SQUARE = polygon([(0, 0), (10, 0), (10, 10), (0, 10)])


def test_a_circle_and_its_offset_circle_are_d_apart_both_ways() -> None:
    for r, d in ((10.0, 1.0), (0.5, 3.0), (1000.0, 0.25)):
        report = check_offset([circle((5, -7), r)], [circle((5, -7), r + d)], d)
        assert report.closest_mm == pytest.approx(d, rel=RTOL)
        assert report.farthest_mm == pytest.approx(d, rel=RTOL)
        assert report.ok(d, 1e-6 * d), report.describe()
        assert report.reachable == report.samples  # all of a circle's outside is reachable


def test_a_clockwise_contour_has_the_same_outside() -> None:
    report = check_offset([circle((0, 0), 10, anticlockwise=False)], [circle((0, 0), 11)], 1.0)
    assert report.ok(1.0, 1e-9), report.describe()
    inside = check_offset(
        [circle((0, 0), 10, anticlockwise=False)], [circle((0, 0), 9)], 1.0, "inside"
    )
    assert inside.ok(1.0, 1e-9), inside.describe()


def test_a_square_and_its_rounded_offset() -> None:
    path = _rounded_square(10.0, 1.0)
    assert [s.kind for s in path] == ["line", "arc"] * 4
    report = check_offset([SQUARE], [path], 1.0)
    assert report.closest_mm == pytest.approx(1.0, rel=RTOL)
    assert report.farthest_mm == pytest.approx(1.0, rel=RTOL)
    assert report.ok(1.0, 1e-9)
    assert corners(path, closed=True) == []
    assert corners(SQUARE, closed=True) == [0, 1, 2, 3]
    assert corners(SQUARE, closed=False) == [1, 2, 3]


def test_a_mitred_offset_is_accepted_and_a_chamfered_one_gouges() -> None:
    mitre = polygon([(-1, -1), (11, -1), (11, 11), (-1, 11)])
    assert check_offset([SQUARE], [mitre], 1.0).ok(1.0, 1e-9)
    # Cutting each corner off at 45°: the chamfer passes 1/√2 from the square's corner.
    chamfer = polygon([(0, -1), (10, -1), (11, 0), (11, 10), (10, 11), (0, 11), (-1, 10), (-1, 0)])
    report = check_offset([SQUARE], [chamfer], 1.0)
    assert report.closest_mm == pytest.approx(1 / math.sqrt(2), rel=RTOL)
    assert not report.ok(1.0, 1e-3)


def test_an_inside_offset_leaves_the_corners_unreached() -> None:
    inner = polygon([(1, 1), (9, 1), (9, 9), (1, 9)])
    report = check_offset([SQUARE], [inner], 1.0, "inside")
    assert report.closest_mm == pytest.approx(1.0, rel=RTOL)
    assert report.farthest_mm == pytest.approx(1.0, rel=1e-6)
    assert report.ok(1.0, 1e-6), report.describe()
    # Within d of each corner along either side the tool's disc would cut the other side.
    assert report.reachable < report.samples
    # The same path as an outside offset is everywhere on the wrong side.
    assert not check_offset([SQUARE], [inner], 1.0, "outside").ok(1.0, 0.1)


def test_too_small_and_too_large_offsets_are_rejected() -> None:
    contour = [circle((0, 0), 10.0)]
    near = check_offset(contour, [circle((0, 0), 10.9)], 1.0)
    assert near.closest_mm == pytest.approx(0.9, rel=RTOL)
    assert not near.ok(1.0, 0.01)
    far = check_offset(contour, [circle((0, 0), 11.1)], 1.0)
    assert far.farthest_mm == pytest.approx(1.1, rel=RTOL)
    assert not far.ok(1.0, 0.01)
    assert "1.1" in far.describe()


def test_a_missing_path_leaves_a_contour_unreached() -> None:
    two = [circle((0, 0), 5.0), circle((30, 0), 5.0)]
    report = check_offset(two, [circle((0, 0), 6.0)], 1.0)
    assert report.closest_mm == pytest.approx(1.0, rel=RTOL)
    # The far side of the second circle, (35, 0), is 35 − 6 from the first path.
    assert report.farthest_mm == pytest.approx(35 - 6, rel=RTOL)
    assert not report.ok(1.0, 0.01)
    # Asked only about the first contour, the same path is right (the second still constrains).
    only_first = check_offset(
        two, [circle((0, 0), 6.0)], 1.0, lambda k: "outside" if k == 0 else None
    )
    assert only_first.ok(1.0, 1e-9), only_first.describe()
    assert check_offset(two, [circle((0, 0), 6.0)], 1.0, ["outside", None]) == only_first


def _slot_part(width: float) -> list[OSeg]:
    """A 20 × 10 block with a slot of ``width`` cut 8 deep into the middle of its top side
    (anticlockwise)."""
    a, b = 10 - width / 2, 10 + width / 2
    return polygon([(0, 0), (20, 0), (20, 10), (b, 10), (b, 2), (a, 2), (a, 10), (0, 10)])


def _bridging_path(width: float, d: float) -> list[OSeg]:
    """The outside offset of :func:`_slot_part` by ``d > width/2``: round corners, and over
    the slot the arcs about its two top corners meeting at ``(10, 10 + √(d² − (w/2)²))``."""
    a, b = 10 - width / 2, 10 + width / 2
    h = math.sqrt(d * d - (width / 2) ** 2)
    meet_right = math.atan2(h, -width / 2)  # seen from (b, 10)
    meet_left = math.atan2(h, width / 2)  # seen from (a, 10)
    return [
        line((0, -d), (20, -d)),
        arc((20, 0), d, -math.pi / 2, math.pi / 2),
        line((20 + d, 0), (20 + d, 10)),
        arc((20, 10), d, 0.0, math.pi / 2),
        line((20, 10 + d), (b, 10 + d)),
        arc((b, 10), d, math.pi / 2, meet_right - math.pi / 2),
        arc((a, 10), d, meet_left, math.pi / 2 - meet_left),
        line((a, 10 + d), (0, 10 + d)),
        arc((0, 10), d, math.pi / 2, math.pi / 2),
        line((-d, 10), (-d, 0)),
        arc((0, 0), d, math.pi, math.pi / 2),
    ]


def test_the_bottom_of_a_slot_narrower_than_the_tool_is_unreachable() -> None:
    part, path = _slot_part(2.0), _bridging_path(2.0, 1.5)
    assert corners(path, closed=True) == [6]  # only where the two arcs meet over the slot
    report = check_offset([part], [path], 1.5)
    assert report.closest_mm == pytest.approx(1.5, rel=RTOL)
    assert report.farthest_mm == pytest.approx(1.5, rel=RTOL)
    assert report.ok(1.5, 1e-9), report.describe()
    # The slot's walls and bottom (18 of the part's 66 mm of outline) are not reachable.
    assert report.reachable / report.samples < 0.9


def test_a_slot_wider_than_the_tool_must_be_cut() -> None:
    # With a 4 mm slot and d = 1.5 the tool fits: a path that only spans the slot's mouth
    # leaves the middle of its walls (y = 5) 6.5 from the path (y = 11.5 and y = −1.5).
    part = _slot_part(4.0)
    bridge = polygon(
        [(0, -1.5), (20, -1.5), (21.5, 0), (21.5, 10), (20, 11.5), (0, 11.5), (-1.5, 10), (-1.5, 0)]
    )
    report = check_offset([part], [bridge], 1.5)
    assert report.farthest_mm == pytest.approx(6.5, rel=RTOL)
    assert report.farthest_at[1] == pytest.approx(5.0, rel=RTOL)
    assert not report.ok(1.5, 0.01)


def test_open_contours_are_cut_left_or_right() -> None:
    edge = [line((0, 0), (10, 0)), arc((10, 5), 5, -math.pi / 2, math.pi / 2)]  # turns left
    left = [line((0, 1), (10, 1)), arc((10, 5), 4, -math.pi / 2, math.pi / 2)]
    right = [line((0, -1), (10, -1)), arc((10, 5), 6, -math.pi / 2, math.pi / 2)]
    assert check_offset([edge], [left], 1.0, "left").ok(1.0, 1e-9)
    assert check_offset([edge], [right], 1.0, "right").ok(1.0, 1e-9)
    wrong = check_offset([edge], [left], 1.0, "right")
    # The wrong side is as far from every contour point: only the tool centres give it away.
    assert wrong.closest_mm == pytest.approx(1.0, rel=RTOL)
    assert wrong.farthest_mm == pytest.approx(1.0, rel=RTOL)
    assert wrong.centre_gap_mm == pytest.approx(2.0, rel=RTOL)
    assert not wrong.ok(1.0, 0.01)
    assert wrong.ok(1.0, 0.01, sided=False)
    with pytest.raises(ValueError, match="contour 0: outside needs a closed contour"):
        check_offset([edge], [left], 1.0, "outside")


def test_bad_arguments_are_refused() -> None:
    with pytest.raises(ValueError, match="2 sides for 1 contours"):
        check_offset([SQUARE], [SQUARE], 1.0, ["outside", "inside"])
    with pytest.raises(ValueError, match="must be finite"):
        check_offset([SQUARE], [SQUARE], math.nan)
    with pytest.raises(ValueError, match="is not outside"):
        check_offset([SQUARE], [SQUARE], 1.0, "around")  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="no segments"):
        distance_to(np.zeros((1, 2)), [])


def test_the_inside_of_a_circle_is_not_its_outside() -> None:
    # r − d and r + d are both d from every point of the circle; the tool centres are not.
    report = check_offset([circle((0, 0), 10.0)], [circle((0, 0), 9.0)], 1.0, "outside")
    assert report.closest_mm == pytest.approx(1.0, rel=RTOL)
    assert report.farthest_mm == pytest.approx(1.0, rel=RTOL)
    assert report.centre_gap_mm == pytest.approx(2.0, rel=RTOL)
    assert not report.ok(1.0, 0.01)
    assert check_offset([circle((0, 0), 10.0)], [circle((0, 0), 9.0)], 1.0, "inside").ok(1.0, 1e-9)


def test_check_each_measures_every_contour_against_its_own_paths_only() -> None:
    # Two circles 1.5 apart: each one's offset by 1 comes within 0.5 of the other.
    contours = [circle((0, 0), 5.0), circle((11.5, 0), 5.0)]
    paths = [circle((0, 0), 6.0), circle((11.5, 0), 6.0)]
    together = check_offset(contours, paths, 1.0)
    assert together.closest_mm == pytest.approx(0.5, rel=RTOL)
    each = check_each(contours, paths, [0, 1], 1.0)
    assert each.ok(1.0, 1e-9), each.describe()
    # Paths given in any order; a contour without a path is found, at its own place.
    assert check_each(contours, paths[::-1], [1, 0], 1.0) == each
    missing = check_each(contours, paths[:1], [0], 1.0)
    assert missing.farthest_mm > 4.0  # another contour's path is more than 4·d away
    assert math.hypot(missing.farthest_at[0] - 11.5, missing.farthest_at[1]) == pytest.approx(5.0)
    too_close = check_each(contours, [circle((0, 0), 5.5), paths[1]], [0, 1], 1.0)
    assert too_close.closest_mm == pytest.approx(0.5, rel=RTOL)
    assert math.hypot(*too_close.closest_at) == pytest.approx(5.5)
    with pytest.raises(ValueError, match="1 origins for 2 paths"):
        check_each(contours, paths, [0], 1.0)
