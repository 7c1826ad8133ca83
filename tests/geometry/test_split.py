"""Cutting a path's segments into pieces (``curves/split.pyx``), checked by our own numbers.

Every check recomputes what a piece must be from the segment's own definition, in numpy:
Bézier curvature ``κ = B'×B''/‖B'‖³`` on samples (one sign and monotone on each piece: no
interior inflection or curvature extremum), the tangent's turn (at most a right angle), the
ellipse's vertices (multiples of π/2 in its own angle), and the source's points, against the
world points of each piece's frame (``measure.points``). The pieces of a segment tile its
``[0, 1]``, share their end points bit for bit and start and end at the segment's own.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

from arcspline.geometry import Spiral
from arcspline.geometry.curves.segments import (
    CircularArc,
    Cubic,
    EllipticalArc,
    Line,
    Quadratic,
    Segment,
)
from arcspline.geometry.curves.split import PIECE_FIELDS, split
from arcspline.geometry.fit.batch import FRAME_FIELDS, PIECE_KINDS
from arcspline.geometry.measure import points
from arcspline.geometry.segment_table import segment_row
from arcspline.geometry.spline import Point

EPS = float(np.finfo(np.float64).eps)
F = {name: j for j, name in enumerate(FRAME_FIELDS)}
P = {name: j for j, name in enumerate(PIECE_FIELDS)}
HALF_PI = 0.5 * math.pi

PROPERTY = settings(
    max_examples=40,
    deadline=None,
    derandomize=True,
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.filter_too_much],
)


def cut(*segments: Segment, max_pieces: int = 100_000) -> tuple[np.ndarray, np.ndarray]:
    """The frame and piece tables of ``segments`` (in order)."""
    table = np.array([segment_row(s) for s in segments], dtype=np.float64)
    frames, pieces = split(table, max_pieces)
    assert frames is not None
    assert pieces is not None
    return frames, pieces


def pt(x: float, y: float) -> Point:
    return Point(float(x), float(y))


# -- our own Bézier ----------------------------------------------------------------------


def control_points(segment: Quadratic | Cubic) -> np.ndarray:
    return np.array(_bezier_points(segment), dtype=np.float64)


def _bezier_points(segment: Quadratic | Cubic) -> list[Point]:
    if isinstance(segment, Quadratic):
        return [segment.start, segment.control, segment.end]
    return [segment.start, segment.control1, segment.control2, segment.end]


def bernstein(cp: np.ndarray, t: np.ndarray) -> np.ndarray:
    """``Σ C(n,i)·tⁱ(1−t)ⁿ⁻ⁱ·Pᵢ`` at each ``t``: shape ``(len(t), 2)``."""
    n = len(cp) - 1
    t = np.asarray(t, dtype=np.float64)[:, None]
    return sum(math.comb(n, i) * t**i * (1 - t) ** (n - i) * cp[i] for i in range(n + 1))


def derivative(cp: np.ndarray, t: np.ndarray, order: int = 1) -> np.ndarray:
    n = len(cp) - 1
    return math.perm(n, order) * bernstein(np.diff(cp, n=order, axis=0), t)


def curvature(cp: np.ndarray, t: np.ndarray) -> np.ndarray:
    d1, d2 = derivative(cp, t), derivative(cp, t, 2)
    with np.errstate(divide="ignore", invalid="ignore"):  # a cusp: not finite, reported
        return (d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0]) / np.hypot(d1[:, 0], d1[:, 1]) ** 3


def _one_way(values: np.ndarray, slack: float) -> bool:
    """Whether ``values`` never goes below ``-slack`` or never above ``slack``."""
    return bool(np.all(values >= -slack) or np.all(values <= slack))


# -- checks shared by the examples and the properties -----------------------------------


def check_tiling(pieces: np.ndarray, segment: int = 0) -> None:
    """The pieces of ``segment`` tile its ``[0, 1]`` exactly, in order."""
    mine = pieces[pieces[:, P["segment"]] == segment]
    t0, t1 = mine[:, P["t0"]], mine[:, P["t1"]]
    assert t0[0] == 0.0
    assert t1[-1] == 1.0
    assert np.array_equal(t1[:-1], t0[1:])
    assert np.all(t0 < t1)


def check_shared_ends(frames: np.ndarray, start: Point, end: Point) -> None:
    """Piece ``k`` ends where piece ``k + 1`` starts, bit for bit; the first starts at the
    segment's start, the last ends at its end."""
    assert (frames[0, F["x0"]], frames[0, F["y0"]]) == tuple(start)
    assert (frames[-1, F["end_x"]], frames[-1, F["end_y"]]) == tuple(end)
    assert np.array_equal(frames[:-1, [F["end_x"], F["end_y"]]], frames[1:, [F["x0"], F["y0"]]])


def check_bezier(segment: Quadratic | Cubic, frames: np.ndarray, pieces: np.ndarray) -> None:
    """Every check of the pieces of one (non-degenerate) Bézier segment."""
    cp = control_points(segment)
    scale = float(np.max(np.abs(cp)))
    check_tiling(pieces, int(pieces[0, P["segment"]]))
    check_shared_ends(frames, segment.start, segment.end)
    assert np.all(pieces[:, P["half_angle_rad"]] == 0.0)
    assert np.all(frames[:, F["kind"]] == PIECE_KINDS["fit"])
    u = np.linspace(0.0, 1.0, 17)
    for k, (t0, t1) in enumerate(pieces[:, [P["t0"], P["t1"]]]):
        # The frame reproduces the source piece (u ↦ t linearly).
        world = points(frames, np.full(len(u), k), u)
        expect = bernstein(cp, t0 + (t1 - t0) * u)
        assert np.max(np.abs(world - expect)) <= 256 * EPS * scale, f"piece {k}"
        check_piece_shape(cp, t0, t1)


def check_piece_shape(cp: np.ndarray, t0: float, t1: float) -> None:
    """Inside ``(t0, t1)``: curvature of one sign, monotone, and a turn of at most π/2."""
    t = t0 + (t1 - t0) * np.linspace(0.0, 1.0, 203)[1:-1]
    kappa = curvature(cp, t)
    assert np.all(np.isfinite(kappa)), f"[{t0}, {t1}]: a cusp inside"
    slack = 1e-9 * float(np.max(np.abs(kappa))) + 1e-300
    assert _one_way(kappa, slack), f"[{t0}, {t1}] has an inflection inside"
    assert _one_way(np.diff(kappa), slack), f"[{t0}, {t1}] has a curvature extremum inside"
    d = derivative(cp, t)
    turn = np.sum(np.abs(np.diff(np.unwrap(np.arctan2(d[:, 1], d[:, 0])))))
    assert turn <= HALF_PI + 1e-6, f"[{t0}, {t1}] turns {turn} rad"


# -- lines and points --------------------------------------------------------------------


@pytest.mark.parametrize(
    "line",
    [
        Line(pt(0, 0), pt(10, 0)),
        Line(pt(-3.25, 7.5), pt(1e-3, -2e3)),
        Line(pt(1e140, -1e140), pt(-1e140, 1e140)),
        Line(pt(1e-140, 0), pt(0, 1e-140)),
    ],
    ids=["axis", "diagonal", "huge", "tiny"],
)
def test_a_line_is_one_line_piece(line: Line) -> None:
    frames, pieces = cut(line)
    assert len(pieces) == 1
    assert frames[0, F["kind"]] == PIECE_KINDS["line"]
    assert tuple(pieces[0]) == (0.0, 0.0, 1.0, 0.0)
    check_shared_ends(frames, line.start, line.end)


@pytest.mark.parametrize(
    "segment",
    [
        Line(pt(3, 4), pt(3, 4)),
        Quadratic(pt(3, 4), pt(3, 4), pt(3, 4)),
        Cubic(pt(-1, 2), pt(-1, 2), pt(-1, 2), pt(-1, 2)),
    ],
    ids=["line", "quadratic", "cubic"],
)
def test_a_single_point_has_no_pieces(segment: Segment) -> None:
    frames, pieces = cut(segment)
    assert len(frames) == len(pieces) == 0


def test_pieces_name_their_segment_in_a_table_of_several() -> None:
    segments = [
        Line(pt(0, 0), pt(10, 0)),
        Line(pt(10, 0), pt(10, 0)),  # a point: no piece, but it keeps its index
        Cubic(pt(10, 0), pt(20, 0), pt(20, 10), pt(10, 10)),
        Line(pt(10, 10), pt(0, 10)),
    ]
    frames, pieces = cut(*segments)
    owners = pieces[:, P["segment"]].astype(int).tolist()
    assert owners[0] == 0
    assert owners[-1] == 3
    assert 1 not in owners
    assert owners == sorted(owners)
    check_tiling(pieces, 2)
    mine = pieces[:, P["segment"]] == 2
    check_bezier(segments[2], frames[mine], pieces[mine])  # type: ignore[arg-type]


def test_more_pieces_than_allowed_is_none() -> None:
    # An S curve with two loops' worth of turning: several pieces.
    s_curve = Cubic(pt(0, 0), pt(30, 40), pt(70, -10), pt(100, 20))
    _, pieces = cut(s_curve)
    n = len(pieces)
    assert n >= 3
    frames, again = split(np.array([segment_row(s_curve)]), n)
    assert frames is not None
    assert np.array_equal(again, pieces)
    assert split(np.array([segment_row(s_curve)]), n - 1) == (None, None)


# -- Béziers: named cases ----------------------------------------------------------------


NAMED_BEZIERS = {
    "inflection": Cubic(pt(0, 0), pt(30, 40), pt(70, -10), pt(100, 20)),
    "two inflections": Cubic(pt(0, 0), pt(10, 10), pt(10, -10), pt(0, 0.5)),
    "loop": Cubic(pt(0, 0), pt(10, 10), pt(-3, 10), pt(7, 0)),
    "cusp": Cubic(pt(0, 0), pt(10, 10), pt(0, 10), pt(10, 0)),
    "U turn": Cubic(pt(0, 0), pt(10, 0), pt(10, 10), pt(0, 10)),
    "spiral": Cubic(  # Walton & Meek's Table 1 spiral: monotone curvature, one piece
        *(
            pt(*p)
            for p in Spiral.from_parameters(
                start=(1.5, 3.0),
                start_tangent=(1.0, 0.0),
                turn_angle_deg=51.34,
                end_curvature=0.41574,
            ).control_points
        )
    ),
    "arc-like": Cubic(pt(1, 0), pt(1, 0.5523), pt(0.5523, 1), pt(0, 1)),
    "first two coincide": Cubic(pt(0, 0), pt(0, 0), pt(10, 10), pt(10, 0)),
    "middle two coincide": Cubic(pt(0, 0), pt(10, 5), pt(10, 5), pt(0, 10)),
    "last two coincide": Cubic(pt(0, 0), pt(10, 0), pt(10, 10), pt(10, 10)),
    "parabola": Quadratic(pt(0, 0), pt(5, 10), pt(10, 0)),
    "lopsided parabola": Quadratic(pt(0, 0), pt(40, 3), pt(1, 2)),
}


@pytest.mark.parametrize("segment", NAMED_BEZIERS.values(), ids=NAMED_BEZIERS.keys())
def test_bezier_pieces_have_monotone_curvature_of_one_sign(segment: Quadratic | Cubic) -> None:
    check_bezier(segment, *cut(segment))


def test_the_spiral_is_one_piece() -> None:
    _, pieces = cut(NAMED_BEZIERS["spiral"])
    assert len(pieces) == 1


def test_a_cusp_and_the_inflection_of_an_s_curve_are_cut_where_they_are() -> None:
    # Cusp: B'(1/2) = 0 exactly.
    _, pieces = cut(NAMED_BEZIERS["cusp"])
    assert np.min(np.abs(pieces[:, P["t1"]] - 0.5)) < 1e-9
    # Inflection of the S curve: the root of B'×B'' in (0, 1), by numpy on a fine grid.
    s_curve = NAMED_BEZIERS["inflection"]
    cp = control_points(s_curve)
    t = np.linspace(0, 1, 200_001)
    kappa = curvature(cp, t)
    roots = t[1:][np.sign(kappa[1:]) != np.sign(kappa[:-1])]
    assert len(roots) == 1
    _, pieces = cut(s_curve)
    assert np.min(np.abs(pieces[:-1, P["t1"]] - roots[0])) < 1e-5


def test_a_parabola_is_cut_at_its_vertex() -> None:
    # The vertex (curvature maximum) is where B'·B'' = 0; with B' = 2(a + t·b): t = −a·b/b·b.
    quad = NAMED_BEZIERS["lopsided parabola"]
    cp = control_points(quad)
    a, b = cp[1] - cp[0], cp[2] - 2 * cp[1] + cp[0]
    vertex = -float(a @ b) / float(b @ b)
    assert 0 < vertex < 1
    _, pieces = cut(quad)
    assert np.min(np.abs(pieces[:-1, P["t1"]] - vertex)) < 1e-9


@pytest.mark.parametrize(
    ("xs", "turning"),
    [
        ((0.0, 10.0, -5.0, 5.0), ((5 - math.sqrt(5)) / 10, (5 + math.sqrt(5)) / 10)),
        ((0.0, 2.0, 2.0, 0.0), (0.5,)),  # out and back along one ray
        ((0.0, 3.0, 6.0, 9.0), ()),  # evenly spaced: x(t) = 9t
    ],
    ids=["doubles back twice", "out and back", "uniform"],
)
@pytest.mark.parametrize("direction", [(1.0, 0.0), (3.0, 4.0), (-5.0, 2.0)])
def test_a_straight_bezier_is_cut_where_it_turns_back(
    xs: tuple[float, ...], turning: tuple[float, ...], direction: tuple[float, float]
) -> None:
    cp = [pt(x * direction[0], x * direction[1]) for x in xs]
    frames, pieces = cut(Cubic(*cp))
    check_tiling(pieces)
    check_shared_ends(frames, cp[0], cp[-1])
    inner = pieces[:-1, P["t1"]]
    assert len(inner) == len(turning)
    assert np.allclose(inner, turning, rtol=0, atol=1e-12)
    # Each piece runs one way along the line.
    ax = np.asarray(direction) / np.hypot(*direction)
    cpa = np.array(cp)
    for t0, t1 in pieces[:, [P["t0"], P["t1"]]]:
        s = bernstein(cpa, np.linspace(t0, t1, 101)) @ ax
        assert _one_way(np.diff(s), 1e-12)


# -- Béziers: properties -----------------------------------------------------------------

grid = st.integers(-8, 8).map(float)
wide = st.floats(-100.0, 100.0, allow_nan=False, allow_infinity=False)
coordinate = st.one_of(grid, wide)


@st.composite
def cubics(draw: st.DrawFn) -> Cubic:
    return Cubic(*(pt(draw(coordinate), draw(coordinate)) for _ in range(4)))


@st.composite
def quadratics(draw: st.DrawFn) -> Quadratic:
    return Quadratic(*(pt(draw(coordinate), draw(coordinate)) for _ in range(3)))


def _well_posed(segment: Quadratic | Cubic) -> bool:
    """Not straight and without a near-cusp that sampling cannot resolve: the speed stays
    above 1e-3 of the control polygon's size, or is exactly 0 (a cusp cut exactly)."""
    cp = control_points(segment)
    size = float(np.max(np.abs(np.diff(cp, axis=0)))) if len(cp) else 0.0
    if size == 0.0:
        return False
    t = np.linspace(0, 1, 4001)
    d1, d2 = derivative(cp, t), derivative(cp, t, 2)
    bend = np.abs(d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0])
    if float(np.max(bend)) <= 1e-9 * size**2:
        return False  # straight (see the examples above) or nearly so
    speed = np.hypot(d1[:, 0], d1[:, 1])
    return bool(np.min(speed) > 1e-3 * size)


@PROPERTY
@given(st.one_of(cubics(), quadratics()))
def test_random_bezier_pieces_have_monotone_curvature_of_one_sign(
    segment: Quadratic | Cubic,
) -> None:
    assume(_well_posed(segment))
    check_bezier(segment, *cut(segment))


@PROPERTY
@given(st.one_of(cubics(), quadratics()), st.integers(-200, 200))
def test_cuts_do_not_depend_on_the_scale(segment: Quadratic | Cubic, k: int) -> None:
    """Scaling by 2**k is exact in floating point: the same cuts, bit for bit."""
    f = 2.0**k
    scaled = type(segment)(*(pt(x * f, y * f) for x, y in _bezier_points(segment)))
    _, pieces = cut(segment)
    _, scaled_pieces = cut(scaled)
    assert np.array_equal(pieces, scaled_pieces)


@pytest.mark.parametrize("k", [-300, 260, 300, 480])
def test_cuts_hold_at_huge_and_tiny_coordinates(k: int) -> None:
    cubic = Cubic(pt(10, -9), pt(-5, -2), pt(1, -2), pt(-8, -10))
    f = 2.0**k
    scaled = Cubic(*(pt(x * f, y * f) for x, y in _bezier_points(cubic)))
    _, pieces = cut(cubic)
    _, scaled_pieces = cut(scaled)
    assert len(pieces) == 6  # no cut lost: the curve at size 1 has six pieces
    assert np.array_equal(pieces, scaled_pieces)


# -- arcs --------------------------------------------------------------------------------


def ellipse(
    center: Sequence[float],
    rx: float,
    ry: float,
    rotation: float,
    start: float,
    sweep: float,
) -> EllipticalArc:
    """An elliptical arc, its end points from the formula."""

    def at(phi: float) -> Point:
        x, y = rx * math.cos(phi), ry * math.sin(phi)
        c, s = math.cos(rotation), math.sin(rotation)
        return pt(center[0] + c * x - s * y, center[1] + s * x + c * y)

    return EllipticalArc(at(start), at(start + sweep), pt(*center), rx, ry, rotation, start, sweep)


def circle(center: Sequence[float], r: float, start: float, sweep: float) -> CircularArc:
    e = ellipse(center, r, r, 0.0, start, sweep)
    return CircularArc(e.start, e.end, e.center, r, start, sweep)


def ellipse_point(arc: EllipticalArc | CircularArc, phi: np.ndarray) -> np.ndarray:
    if isinstance(arc, CircularArc):
        rx = ry = arc.radius
        rot = 0.0
    else:
        rx, ry, rot = arc.rx, arc.ry, arc.rotation_rad
    x, y = rx * np.cos(phi), ry * np.sin(phi)
    c, s = math.cos(rot), math.sin(rot)
    return np.stack([arc.center[0] + c * x - s * y, arc.center[1] + s * x + c * y], axis=-1)


def check_conic(arc: EllipticalArc | CircularArc, frames: np.ndarray, pieces: np.ndarray) -> None:
    """Checks shared by elliptical and circular arcs: exact tiling, shared end points, each
    piece's turn at most π/2, its half angle, and its frame's points against the arc at
    ``φ = m + 2·atan(tan(h/2)·(2u − 1))``."""
    t0, t1 = pieces[:, P["t0"]], pieces[:, P["t1"]]
    check_tiling(pieces, int(pieces[0, P["segment"]]))
    check_shared_ends(frames, arc.start, arc.end)
    phi0, phi1 = arc.start_angle_rad + t0 * arc.sweep_rad, arc.start_angle_rad + t1 * arc.sweep_rad
    assert np.all(np.abs(phi1 - phi0) <= HALF_PI + 1e-12)
    assert np.allclose(pieces[:, P["half_angle_rad"]], np.abs(phi1 - phi0) / 2, rtol=1e-12)
    radius = arc.radius if isinstance(arc, CircularArc) else max(arc.rx, arc.ry)
    scale = max(abs(arc.center[0]), abs(arc.center[1])) + radius
    u = np.linspace(0.0, 1.0, 17)
    for k in range(len(pieces)):
        h, m = 0.5 * (phi1[k] - phi0[k]), 0.5 * (phi0[k] + phi1[k])
        phi = m + 2.0 * np.arctan(np.tan(0.5 * h) * (2.0 * u - 1.0))
        world = points(frames, np.full(len(u), k), u)
        assert np.max(np.abs(world - ellipse_point(arc, phi))) <= 256 * EPS * scale, f"piece {k}"


ELLIPSES = {
    "inside a quadrant": ellipse((0, 0), 10, 5, 0.0, 0.1, 1.2),
    "across one vertex": ellipse((1, 2), 10, 5, 0.5, -0.3, 1.0),
    "across three, clockwise": ellipse((-4, 3), 3, 8, -1.0, 2.0, -4.0),
    "almost a full turn": ellipse((0, 0), 2, 1, 0.3, 0.25, 2 * math.pi - 0.5),
    "from a vertex": ellipse((0, 0), 6, 4, math.pi / 2, HALF_PI, 2.0),
    "to a vertex": ellipse((5, 5), 6, 4, 0.0, 0.2, math.pi - 0.2),
}


@pytest.mark.parametrize("arc", ELLIPSES.values(), ids=ELLIPSES.keys())
def test_an_elliptical_arc_is_cut_at_its_vertices(arc: EllipticalArc) -> None:
    frames, pieces = cut(arc)
    check_conic(arc, frames, pieces)
    assert np.all(frames[:, F["kind"]] == PIECE_KINDS["fit"])
    a0, sweep = arc.start_angle_rad, arc.sweep_rad
    # The vertices strictly inside: multiples of π/2 between the end angles.
    lo, hi = sorted((a0, a0 + sweep))
    inside = [k * HALF_PI for k in range(math.floor(lo / HALF_PI) - 1, math.ceil(hi / HALF_PI) + 2)]
    inside = [v for v in inside if lo + 1e-9 < v < hi - 1e-9]
    cuts = a0 + pieces[:-1, P["t1"]] * sweep
    assert len(cuts) == len(inside)
    assert np.allclose(np.sort(cuts), inside, rtol=0, atol=1e-12)


@pytest.mark.parametrize(
    ("sweep", "parts"),
    [(1.0, 1), (HALF_PI, 1), (-2.0, 2), (math.pi, 2), (4.0, 3), (-(2 * math.pi - 1e-3), 4)],
)
def test_a_circular_arc_is_cut_into_equal_arc_pieces_of_at_most_a_quarter_turn(
    sweep: float, parts: int
) -> None:
    arc = circle((2.0, -1.0), 3.0, 0.7, sweep)
    frames, pieces = cut(arc)
    check_conic(arc, frames, pieces)
    assert len(pieces) == parts
    assert np.all(frames[:, F["kind"]] == PIECE_KINDS["arc"])
    assert np.allclose(np.diff(pieces[:, P["t0"]]), 1.0 / parts, rtol=0, atol=1e-15)


@PROPERTY
@given(
    st.floats(-50, 50),
    st.floats(-50, 50),
    st.floats(0.1, 50),
    st.floats(0.1, 50),
    st.floats(-math.pi, math.pi),
    st.floats(-2 * math.pi, 2 * math.pi),
    st.one_of(st.floats(0.01, 2 * math.pi - 0.01), st.floats(-2 * math.pi + 0.01, -0.01)),
)
def test_random_elliptical_arcs_are_cut_at_their_vertices(
    cx: float, cy: float, rx: float, ry: float, rot: float, start: float, sweep: float
) -> None:
    # Ends within rounding of a vertex: test_an_arc_starting_at_a_vertex_has_no_empty_piece.
    for end in (start, start + sweep):
        assume(abs(end / HALF_PI - round(end / HALF_PI)) > 1e-9)
    arc = ellipse((cx, cy), rx, ry, rot, start, sweep)
    frames, pieces = cut(arc)
    check_conic(arc, frames, pieces)
    cuts = arc.start_angle_rad + pieces[:-1, P["t1"]] * arc.sweep_rad
    assert np.allclose(cuts / HALF_PI, np.round(cuts / HALF_PI), rtol=0, atol=1e-12)
    lo, hi = sorted((start, start + sweep))
    expected = math.floor((hi - 1e-9) / HALF_PI) - math.ceil((lo + 1e-9) / HALF_PI) + 1
    assert len(cuts) == max(expected, 0)


@pytest.mark.parametrize(
    "arc",
    [
        # As parse_path_data gives "M 0 0 A 10 5 30 0 1 10 0" and "M 0 0 A 3 3 45 0 0 0 1".
        EllipticalArc(
            pt(0, 0),
            pt(10, 0),
            pt(8.68242689773237, 4.960783708246106),
            10.0,
            5.0,
            0.5235987755982988,
            3.1325827847211434,
            1.4454684956268309,
        ),
        CircularArc(
            pt(0, 0),
            pt(0, 1),
            pt(2.958039891549808, 0.5),
            3.0,
            -2.974144574370104,
            -0.33489615843937864,
        ),
    ],
    ids=["elliptical", "circular"],
)
def test_arc_pieces_end_at_t_1_exactly(arc: EllipticalArc | CircularArc) -> None:
    # Regression: the last piece's t1 was (a0 + sweep − a0)/sweep (1.0000000000000002 and
    # 0.9999999999999999 here), so arc outputs reported u_end ≠ 1.
    _, pieces = cut(arc)
    assert pieces[0, P["t0"]] == 0.0
    assert pieces[-1, P["t1"]] == 1.0


@pytest.mark.parametrize("start", [-5.551115123125783e-17, 1e-17, 6.4e-52])
def test_an_arc_starting_at_a_vertex_has_no_empty_piece(start: float) -> None:
    # Sweeping back across the vertex at φ = 0 that it (nearly) starts on.
    arc = ellipse((0.0, 0.0), 3.0, 7.0, math.pi / 4, start, -1.0 if start > 0 else 1.0)
    frames, _ = cut(arc)
    assert np.all(np.isfinite(frames))
    assert np.all(frames[:, F["chord"]] > 1e-9 * 7.0)  # no piece of a rounding error's size
