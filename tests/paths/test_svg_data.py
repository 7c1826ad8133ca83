"""SVG path data (``paths/svg_data.py``): every command, the number and flag grammar, arcs
checked against their own definition (and a literal transcription of SVG's F.6.5), each
error with its offset, and round trips of random segments."""

from __future__ import annotations

import itertools
import math
import re
from unittest import mock

import pytest
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

from arcspline.geometry.curves.segments import (
    CircularArc,
    Cubic,
    EllipticalArc,
    Line,
    Path,
    Quadratic,
    Segment,
    Subpath,
)
from arcspline.geometry.errors import GeometryError
from arcspline.geometry.spline import Point
from arcspline.paths import parse_path_data, svg_data

P = Point


def segments(d: str) -> list[Segment]:
    """The segments of the path's only subpath."""
    (subpath,) = parse_path_data(d).subpaths
    return list(subpath.segments)


def lines(*points: tuple[float, float]) -> list[Segment]:
    return [Line(P(*a), P(*b)) for a, b in itertools.pairwise(points)]


def error(d: str, **kwargs: int) -> GeometryError:
    with pytest.raises(GeometryError) as info:
        parse_path_data(d, **kwargs)
    assert info.value.field == "path"
    return info.value


def assert_well_formed(path: Path) -> None:
    """The invariants every parsed path keeps: chained bit for bit, closed subpaths end where
    they start, no empty subpath, finite numbers, sweeps within (0, 2π)."""
    for subpath in path.subpaths:
        assert subpath.segments
        for a, b in itertools.pairwise(subpath.segments):
            assert a.end == b.start
            assert [math.copysign(1, u) for u in a.end] == [math.copysign(1, v) for v in b.start]
        if subpath.closed:
            assert subpath.segments[-1].end == subpath.segments[0].start
        for segment in subpath.segments:
            for value in segment:
                numbers = value if isinstance(value, tuple) else (value,)
                assert all(math.isfinite(v) for v in numbers), segment
            if isinstance(segment, CircularArc | EllipticalArc):
                assert 0 < abs(segment.sweep_rad) < 2 * math.pi


# -- commands -------------------------------------------------------------------------------


def test_lines_absolute_and_relative() -> None:
    assert segments("M1 2 L3 4") == lines((1, 2), (3, 4))
    assert segments("M1 2 l3 4") == lines((1, 2), (4, 6))
    assert segments("m1 2 l3 4 l-1 -1") == lines((1, 2), (4, 6), (3, 5))


def test_horizontal_and_vertical() -> None:
    assert segments("M1 2 H5 V7 H-1 V0") == lines((1, 2), (5, 2), (5, 7), (-1, 7), (-1, 0))
    assert segments("M1 2 h5 v7 h-1 v-10") == lines((1, 2), (6, 2), (6, 9), (5, 9), (5, -1))
    assert segments("M0 0 H1 2 3") == lines((0, 0), (1, 0), (2, 0), (3, 0))
    assert segments("M0 0 v1 2") == lines((0, 0), (0, 1), (0, 3))


def test_cubic_absolute_and_relative() -> None:
    assert segments("M0 0 C1 2 3 4 5 6") == [Cubic(P(0, 0), P(1, 2), P(3, 4), P(5, 6))]
    # All three points of a relative cubic are relative to its start.
    assert segments("M1 1 c1 2 3 4 5 6 1 0 2 0 3 0") == [
        Cubic(P(1, 1), P(2, 3), P(4, 5), P(6, 7)),
        Cubic(P(6, 7), P(7, 7), P(8, 7), P(9, 7)),
    ]


def test_quadratic_absolute_and_relative() -> None:
    assert segments("M0 0 Q1 2 3 4") == [Quadratic(P(0, 0), P(1, 2), P(3, 4))]
    assert segments("M1 1 q1 2 3 4 1 1 2 2") == [
        Quadratic(P(1, 1), P(2, 3), P(4, 5)),
        Quadratic(P(4, 5), P(5, 6), P(6, 7)),
    ]


def test_smooth_cubic_reflects_the_previous_control_point() -> None:
    assert segments("M0 0 C1 1 2 1 3 0 S5 -1 6 0") == [
        Cubic(P(0, 0), P(1, 1), P(2, 1), P(3, 0)),
        Cubic(P(3, 0), P(4, -1), P(5, -1), P(6, 0)),
    ]
    # After S too (an implicit repetition of S is an S), and relative.
    assert segments("M0 0 C1 1 2 1 3 0 s2 -1 3 0 2 1 3 0") == [
        Cubic(P(0, 0), P(1, 1), P(2, 1), P(3, 0)),
        Cubic(P(3, 0), P(4, -1), P(5, -1), P(6, 0)),
        Cubic(P(6, 0), P(7, 1), P(8, 1), P(9, 0)),
    ]


def test_smooth_cubic_after_other_commands_starts_at_the_current_point() -> None:
    for before in ("", "L3 0", "Q9 9 3 0", "T3 0"):
        d = f"M0 0 {before} S5 -1 6 0" if before else "M3 0 S5 -1 6 0"
        assert segments(d)[-1] == Cubic(P(3, 0), P(3, 0), P(5, -1), P(6, 0)), d
    # A moveto in between: no reflection either.
    path = parse_path_data("M0 0 C1 1 2 1 3 0 M3 0 S5 -1 6 0")
    assert path.subpaths[1].segments == (Cubic(P(3, 0), P(3, 0), P(5, -1), P(6, 0)),)


def test_smooth_quadratic_reflects_the_previous_control_point() -> None:
    assert segments("M0 0 Q1 1 2 0 T4 0 t2 0") == [
        Quadratic(P(0, 0), P(1, 1), P(2, 0)),
        Quadratic(P(2, 0), P(3, -1), P(4, 0)),
        Quadratic(P(4, 0), P(5, 1), P(6, 0)),
    ]


def test_smooth_quadratic_after_other_commands() -> None:
    for before in ("L2 0", "C9 9 9 9 2 0", "S9 9 2 0"):
        assert segments(f"M0 0 {before} T4 0")[-1] == Quadratic(P(2, 0), P(2, 0), P(4, 0))
    # T after a T that followed no quadratic: its control point is the previous T's (the
    # current point then), reflected.
    assert segments("M0 0 T2 0 T4 1") == [
        Quadratic(P(0, 0), P(0, 0), P(2, 0)),
        Quadratic(P(2, 0), P(4, 0), P(4, 1)),
    ]


def test_moveto_repetition_is_lineto() -> None:
    assert segments("M1 1 2 2 3 3") == lines((1, 1), (2, 2), (3, 3))
    assert segments("m1 1 2 2 3 3") == lines((1, 1), (3, 3), (6, 6))


def test_first_relative_moveto_is_absolute_later_ones_relative() -> None:
    path = parse_path_data("m-0 5 l1 0 m1 1 l1 0")
    first, second = path.subpaths
    assert math.copysign(1, first.segments[0].start.x) == -1  # taken as given, -0.0
    assert second.segments == (Line(P(2, 6), P(3, 6)),)


def test_implicit_repetition_of_every_command() -> None:
    assert segments("M0 0 L1 0 2 0") == lines((0, 0), (1, 0), (2, 0))
    assert segments("M0 0 l1 0,1 0") == lines((0, 0), (1, 0), (2, 0))
    assert len(segments("M0 0 C1 1 2 2 3 3 4 4 5 5 6 6")) == 2
    assert len(segments("M0 0 S1 1 2 2 3 3 4 4")) == 2
    assert len(segments("M0 0 T1 1 2 2")) == 2
    assert len(segments("M0 0 A1 1 0 0 1 2 0 1 1 0 0 1 0 0")) == 2


def test_close_appends_a_line_to_the_start_and_marks_closed() -> None:
    (subpath,) = parse_path_data("M0 0 L1 0 L1 1 Z").subpaths
    assert subpath.closed
    assert subpath.segments == tuple(lines((0, 0), (1, 0), (1, 1), (0, 0)))
    assert subpath.segments[-1].end is subpath.segments[0].start
    # Already at the start: no closing line.
    (subpath,) = parse_path_data("M0 0 L1 0 L0 0 z").subpaths
    assert subpath == Subpath(tuple(lines((0, 0), (1, 0), (0, 0))), closed=True)


def test_a_command_after_close_starts_a_new_subpath_at_the_start() -> None:
    path = parse_path_data("M1 1 L2 1 L2 2 Z l0 5 L7 7")
    assert path.subpaths == (
        Subpath(tuple(lines((1, 1), (2, 1), (2, 2), (1, 1))), closed=True),
        Subpath(tuple(lines((1, 1), (1, 6), (7, 7)))),
    )
    # m after Z is relative to the closed subpath's start, not to the last point drawn.
    path = parse_path_data("M1 1 L5 5 Z m1 0 h1")
    assert path.subpaths[1].segments == (Line(P(2, 1), P(3, 1)),)


def test_several_subpaths() -> None:
    path = parse_path_data("M0 0 L1 0 M5 5 L6 5 L6 6 z M9 9 h1")
    assert path.subpaths == (
        Subpath(tuple(lines((0, 0), (1, 0)))),
        Subpath(tuple(lines((5, 5), (6, 5), (6, 6), (5, 5))), closed=True),
        Subpath(tuple(lines((9, 9), (10, 9)))),
    )


def test_subpaths_without_segments_are_left_out() -> None:
    assert parse_path_data("M1 2") == Path(())
    assert parse_path_data("M1 2 M3 4 m1 1") == Path(())
    assert parse_path_data("M1 2 Z") == Path(())
    assert parse_path_data("M1 2 A1 1 0 0 1 1 2") == Path(())  # an omitted arc
    path = parse_path_data("M0 0 h1 Z Z M5 5")
    assert len(path.subpaths) == 1


def test_zero_length_segments_are_kept() -> None:
    assert segments("M1 1 L1 1") == [Line(P(1, 1), P(1, 1))]
    assert segments("M1 1 l0 0 h0 v0") == lines((1, 1), (1, 1), (1, 1), (1, 1))
    assert segments("M1 1 Q1 1 1 1") == [Quadratic(P(1, 1), P(1, 1), P(1, 1))]


def test_segments_chain_bit_for_bit() -> None:
    path = parse_path_data(
        "m.1 .2 l.3 .7 h.1 v.2 c.1 .1 .2 .2 .3 .3 s.1 .1 .3 .1 q.1 .2 .3 .3 t.1 .1 "
        "a.5 .7 10 0 1 .2 .3 z l.1 .1"
    )
    assert_well_formed(path)
    for a, b in itertools.pairwise(path.subpaths[0].segments):
        assert a.end is b.start


def test_coordinates_are_taken_as_given() -> None:
    assert segments("M0 0 L3 -4") == lines((0, 0), (3, -4))  # no y-flip


# -- numbers and separators -----------------------------------------------------------------


@pytest.mark.parametrize(
    ("numbers", "values"),
    [
        ("1 2", (1, 2)),
        ("1,2", (1, 2)),
        ("1 , 2", (1, 2)),
        ("\t1\n,\r\f2", (1, 2)),
        (".5.5", (0.5, 0.5)),
        ("-1-2", (-1, -2)),
        ("+1+2", (1, 2)),
        ("1e-3 2E+2", (1e-3, 200)),
        ("1e2.5", (100, 0.5)),
        ("1.-.5", (1, -0.5)),
        ("1..5", (1, 0.5)),
        ("0010 -0", (10, 0)),
        ("1.5e1-2.5E-1", (15, -0.25)),
        ("1e-400 5", (0, 5)),  # underflows to zero: finite, allowed
        ("00.5 12345678901234567890", (0.5, 12345678901234567890.0)),
    ],
)
def test_number_forms(numbers: str, values: tuple[float, float]) -> None:
    assert segments(f"M0 0L{numbers}") == [Line(P(0, 0), P(*values))]


def test_whitespace_around_commands_is_optional() -> None:
    assert segments("M0,0L1,1") == segments("  M 0 0 L 1 1  ")
    assert segments("M0 0L1 1Z") == segments("\nM0 0\nL1 1\nZ\n")


def test_arc_flags_without_separators() -> None:
    spaced = segments("M0 0 a1 1 0 0 0 10 10")
    assert segments("M0 0 a1 1 0 0010 10") == spaced
    assert segments("M0 0 a1,1,0,0,0,10,10") == spaced
    assert segments("M0 0 a1 1 0 00 10 10") == spaced
    assert segments("M0 0 a1 1 0 0 0 1 1") == segments("M0 0 a1 1 0 001 1")
    swept = segments("M0 0 a1 1 0 1 1 1 1")
    assert segments("M0 0 a1 1 0 111 1") == swept
    assert segments("M0 0 a1 1 0 1,1,1,1") == swept


# -- errors ---------------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("d", "message"),
    [
        ("M0 L1 1", "at character 3: expected a number for command 'M', found 'L'"),
        ("M0 0 L X", "at character 7: expected a number for command 'L', found 'X'"),
        ("M0 0 L1", "at character 7: expected a number for command 'L', found end of data"),
        ("M0 0 L", "at character 6: expected a number for command 'L', found end of data"),
        ("M0 0 L,1 1", "at character 6: expected a number for command 'L', found ','"),
        ("M0 0 L1,,1", "at character 8: expected a number for command 'L', found ','"),
        ("M0 0 L1 1,", "at character 10: expected a number for command 'L' after ',', "
         "found end of data"),
        ("M0 0 L1 1, L2 2", "at character 11: expected a number for command 'L' after ',', "
         "found 'L'"),
        ("M0 0 L1 1 X", "at character 10: unknown command 'X'"),
        ("M 0 0 X 1", "at character 6: unknown command 'X'"),
        ("M0 0 e1", "at character 5: unknown command 'e'"),
        ("M0 0 L1 1 #", "at character 10: expected a command letter, found '#'"),
        ("M0 0 L1 1 \u00e9", "at character 10: expected a command letter, found '\u00e9'"),
        ("M0 0 L1 \u0661", "at character 8: expected a number for command 'L', found '\u0661'"),
        ("L0 0", "at character 0: path data must begin with a moveto command ('M' or 'm'), "
         "found 'L'"),
        ("  z", "at character 2: path data must begin with a moveto command ('M' or 'm'), "
         "found 'z'"),
        ("none", "at character 0: path data must begin with a moveto command ('M' or 'm'), "
         "found 'n'"),
        ("M1e999 0", "at character 1: number '1e999' for command 'M' is out of range "
         "(not finite)"),
        ("M0 0 L1 -1e400", "at character 8: number '-1e400' for command 'L' is out of range "
         "(not finite)"),
        ("M0 0 L1e 2", "at character 7: malformed exponent in a number for command 'L': "
         "expected digits after 'e', found ' '"),
        ("M0 0 L1E+", "at character 7: malformed exponent in a number for command 'L': "
         "expected digits after 'E', found '+'"),
        ("M0 0 L. 1", "at character 6: expected a number for command 'L', found '.'"),
        ("M0 0 L+-1 1", "at character 6: expected a number for command 'L', found '+'"),
        ("M0 0 Z 1", "at character 7: command 'Z' takes no parameters, found '1'"),
        ("M0 0 z,", "at character 6: command 'z' takes no parameters, found ','"),
        ("M0 0 A1 1 0 2 0 1 1", "at character 12: expected a flag ('0' or '1') for command "
         "'A', found '2'"),
        ("M0 0 a1 1 0 1 -1 1 1", "at character 14: expected a flag ('0' or '1') for command "
         "'a', found '-'"),
        ("M0 0 A1 1 0 1.0 1 1 1", "at character 13: expected a flag ('0' or '1') for command "
         "'A', found '.'"),
        ("M1e308 0 l1e308 0", "at character 10: a relative coordinate overflows the float "
         "range"),
        ("M1e308 0 h1e308", "at character 10: a relative coordinate overflows the float range"),
        ("M0 0 Q-1e308 0 1e308 0 T0 0", "at character 24: the reflected control point "
         "overflows the float range"),
    ],
)  # fmt: skip
def test_error_messages_name_the_offset(d: str, message: str) -> None:
    err = error(d)
    assert err.message == message
    assert err.kind == "invalid_input"
    offset = int(re.match(r"at character (\d+)", message).group(1))  # type: ignore[union-attr]
    assert 0 <= offset <= len(d)


@pytest.mark.parametrize("d", ["", "   ", "\n\t\r\f"])
def test_empty_path_data(d: str) -> None:
    assert error(d).message == "the path data is empty"


def test_segment_limit() -> None:
    d = "M0 0 L1 0 L1 1 Z"
    assert len(parse_path_data(d, max_segments=3).subpaths[0].segments) == 3
    err = error(d, max_segments=2)
    assert err.kind == "segment_limit"
    assert err.limit == 2
    assert err.message == "at character 15: more than 2 segments"  # the closing line
    err = error("M0 0 h1 2 3 4", max_segments=2)
    assert err.message == "at character 10: more than 2 segments"
    assert error("M0 0 h0", max_segments=0).kind == "segment_limit"
    # Omitted arcs and a lone moveto make no segment.
    assert parse_path_data("M0 0 A1 1 0 0 0 0 0 M1 1", max_segments=0) == Path(())


def test_segment_limit_stops_early_on_huge_input() -> None:
    d = "M0 0" + " l1 1" * 200_000
    err = error(d, max_segments=10)
    assert err.message == "at character 56: more than 10 segments"


def test_long_input_parses_without_recursion() -> None:
    n = 20_000
    path = parse_path_data("M0 0 " + "h1 v1 " * n + "z" + " m1 1 h1 z" * n)
    assert len(path.subpaths) == n + 1
    assert len(path.subpaths[0].segments) == 2 * n + 1


def test_negative_segment_limit_is_refused() -> None:
    with pytest.raises(GeometryError) as info:
        parse_path_data("M0 0", max_segments=-1)
    assert info.value.field == "max_segments"


# -- arcs -----------------------------------------------------------------------------------


def reference_center_form(
    x1: float,
    y1: float,
    rx: float,
    ry: float,
    phi_deg: float,
    fa: int,
    fs: int,
    x2: float,
    y2: float,
) -> tuple[float, float, float, float, float, float]:
    """SVG 1.1 F.6.5 and F.6.6, transcribed literally: (cx, cy, rx, ry, θ1, Δθ)."""
    phi = math.radians(phi_deg)
    c, s = math.cos(phi), math.sin(phi)
    x1p = c * (x1 - x2) / 2 + s * (y1 - y2) / 2
    y1p = -s * (x1 - x2) / 2 + c * (y1 - y2) / 2
    rx, ry = abs(rx), abs(ry)
    lam = x1p**2 / rx**2 + y1p**2 / ry**2
    if lam > 1:
        rx, ry = math.sqrt(lam) * rx, math.sqrt(lam) * ry
    num = rx**2 * ry**2 - rx**2 * y1p**2 - ry**2 * x1p**2
    den = rx**2 * y1p**2 + ry**2 * x1p**2
    k = math.sqrt(max(num / den, 0.0)) * (1 if fa != fs else -1)
    cxp, cyp = k * rx * y1p / ry, -k * ry * x1p / rx
    cx = c * cxp - s * cyp + (x1 + x2) / 2
    cy = s * cxp + c * cyp + (y1 + y2) / 2

    def angle(ux: float, uy: float, vx: float, vy: float) -> float:
        a = math.acos(max(-1.0, min(1.0, (ux * vx + uy * vy) / math.hypot(ux, uy)
                                    / math.hypot(vx, vy))))  # fmt: skip
        return -a if ux * vy - uy * vx < 0 else a

    theta1 = angle(1, 0, (x1p - cxp) / rx, (y1p - cyp) / ry)
    dtheta = angle((x1p - cxp) / rx, (y1p - cyp) / ry, (-x1p - cxp) / rx, (-y1p - cyp) / ry)
    dtheta %= 2 * math.pi
    if not fs and dtheta > 0:
        dtheta -= 2 * math.pi
    return cx, cy, rx, ry, theta1, dtheta


def ellipse_point(arc: CircularArc | EllipticalArc, angle: float) -> tuple[float, float]:
    if isinstance(arc, CircularArc):
        return (
            arc.center.x + arc.radius * math.cos(angle),
            arc.center.y + arc.radius * math.sin(angle),
        )
    c, s = math.cos(arc.rotation_rad), math.sin(arc.rotation_rad)
    u, v = arc.rx * math.cos(angle), arc.ry * math.sin(angle)
    return arc.center.x + c * u - s * v, arc.center.y + s * u + c * v


def ellipse_residual(arc: CircularArc | EllipticalArc, p: Point) -> float:
    """``(x/rx)² + (y/ry)² - 1`` of ``p`` in the ellipse's own axes."""
    if isinstance(arc, CircularArc):
        return math.hypot(p.x - arc.center.x, p.y - arc.center.y) / arc.radius - 1
    c, s = math.cos(arc.rotation_rad), math.sin(arc.rotation_rad)
    dx, dy = p.x - arc.center.x, p.y - arc.center.y
    return ((c * dx + s * dy) / arc.rx) ** 2 + ((-s * dx + c * dy) / arc.ry) ** 2 - 1


def check_arc(arc: Segment, large: bool, sweep: bool, scale: float) -> None:
    """An arc against its own definition: both end points on its ellipse, at the start angle
    and the start angle plus the sweep; the flags choose the sweep's size and sign."""
    assert isinstance(arc, CircularArc | EllipticalArc)
    assert abs(ellipse_residual(arc, arc.start)) < 1e-12
    assert abs(ellipse_residual(arc, arc.end)) < 1e-12
    for p, angle in ((arc.start, arc.start_angle_rad), (arc.end, arc.start_angle_rad +
                                                        arc.sweep_rad)):  # fmt: skip
        x, y = ellipse_point(arc, angle)
        assert math.hypot(x - p.x, y - p.y) < 1e-12 * scale
    assert (arc.sweep_rad > 0) == sweep
    if large:
        assert math.pi <= abs(arc.sweep_rad) < 2 * math.pi
    else:
        assert 0 < abs(arc.sweep_rad) <= math.pi


@pytest.mark.parametrize("large", [0, 1])
@pytest.mark.parametrize("sweep", [0, 1])
@pytest.mark.parametrize(
    ("rx", "ry", "rotation"), [(5, 5, 0), (5, 5, 33), (5, 3, 0), (5, 3, 30), (3, 7, -100)]
)
def test_arc_against_its_definition_and_the_reference(
    rx: float, ry: float, rotation: float, large: int, sweep: int
) -> None:
    d = f"M1 2 A{rx} {ry} {rotation} {large} {sweep} 4 6"
    (arc,) = segments(d)
    assert arc.start == P(1, 2)
    assert arc.end == P(4, 6)
    if rx == ry:
        assert isinstance(arc, CircularArc)
        assert arc.radius == rx
    else:
        assert isinstance(arc, EllipticalArc)
        assert (arc.rx, arc.ry) == (rx, ry)
        assert arc.rotation_rad == pytest.approx(math.radians(rotation), abs=1e-15)
    check_arc(arc, bool(large), bool(sweep), 10)
    assert abs(arc.sweep_rad) != pytest.approx(math.pi, abs=1e-3)  # no scaling happened
    cx, cy, _, _, theta1, dtheta = reference_center_form(1, 2, rx, ry, rotation, large, sweep,
                                                         4, 6)  # fmt: skip
    assert arc.center == pytest.approx((cx, cy), abs=1e-12)
    assert arc.sweep_rad == pytest.approx(dtheta, abs=1e-12)
    # The reference's θ1 is in the rotated axes; a circle's start angle is the polar angle.
    polar = theta1 + (math.radians(rotation) if rx == ry else 0.0)
    assert math.remainder(arc.start_angle_rad - polar, 2 * math.pi) == pytest.approx(0, abs=1e-12)


def test_sweep_flag_one_turns_anticlockwise_in_a_y_up_frame() -> None:
    (arc,) = segments("M1 0 A1 1 0 0 1 0 1")
    assert isinstance(arc, CircularArc)
    assert arc.center == pytest.approx((0, 0), abs=1e-15)
    assert arc.start_angle_rad == pytest.approx(0, abs=1e-15)
    assert arc.sweep_rad == pytest.approx(math.pi / 2)
    (arc,) = segments("M1 0 A1 1 0 0 0 0 1")
    assert arc.center == pytest.approx((1, 1))
    assert arc.sweep_rad == pytest.approx(-math.pi / 2)
    (arc,) = segments("M1 0 A1 1 0 1 1 0 1")
    assert arc.center == pytest.approx((1, 1))
    assert arc.sweep_rad == pytest.approx(3 * math.pi / 2)


def test_relative_arc() -> None:
    assert segments("M1 2 a3 3 0 0 1 3 4") == segments("M1 2 A3 3 0 0 1 4 6")


def test_radii_too_small_are_scaled_up_about_the_chord_midpoint() -> None:
    (arc,) = segments("M0 0 A1 1 0 0 1 10 0")
    assert arc == CircularArc(P(0, 0), P(10, 0), P(5, 0), 5.0, math.pi, math.pi)
    (arc,) = segments("M1 1 A1 2 0 1 0 4 5")
    assert isinstance(arc, EllipticalArc)
    assert arc.center == P(2.5, 3.0)  # the midpoint exactly
    assert arc.rx / arc.ry == pytest.approx(0.5, rel=1e-15)
    assert arc.sweep_rad == -math.pi
    check_arc(arc, False, False, 10)
    check_arc(arc, True, False, 10)  # half an ellipse is both
    *_, rx, ry, _, _ = reference_center_form(1, 1, 1, 2, 0, 1, 0, 4, 5)
    assert (arc.rx, arc.ry) == pytest.approx((rx, ry), rel=1e-15)
    # Rotated, tiny radii.
    (arc,) = segments("M3 -2 A1e-3 3e-3 40 1 1 -7 5")
    assert arc.center == P(-2, 1.5)
    check_arc(arc, True, True, 10)


def test_negative_radii_are_absolute() -> None:
    assert segments("M1 2 A-5 -3 30 1 0 3 4") == segments("M1 2 A5 3 30 1 0 3 4")


def test_zero_radius_is_a_line_and_equal_end_points_omit_the_arc() -> None:
    assert segments("M1 2 A0 3 0 1 1 3 4") == lines((1, 2), (3, 4))
    assert segments("M1 2 a3 0 0 1 1 2 2") == lines((1, 2), (3, 4))
    # Equal end points come first (F.6.2): the arc is omitted even with a zero radius.
    assert segments("M1 2 A0 0 0 1 1 1 2 L5 5") == lines((1, 2), (5, 5))
    assert segments("M1 2 a3 3 0 1 1 0 0 L5 5") == lines((1, 2), (5, 5))


def test_circle_ignores_the_rotation_and_ellipse_rotation_is_reduced() -> None:
    assert segments("M1 2 A5 5 77 1 0 3 4") == segments("M1 2 A5 5 0 1 0 3 4")
    (a,) = segments("M1 2 A5 3 390 1 0 3 4")
    (b,) = segments("M1 2 A5 3 30 1 0 3 4")
    assert a.rotation_rad == b.rotation_rad  # type: ignore[union-attr]
    (c,) = segments("M1 2 A5 3 90 1 0 3 4")
    (e,) = segments("M1 2 A3 5 0 1 0 3 4")
    assert c.center == e.center  # exact quarter turns: cos 90° is 0, not 6e-17


def test_arc_sweeping_to_nothing_is_its_chord_and_nearly_full_stays_below_two_pi() -> None:
    (line,) = segments("M0 0 A1e300 1e300 0 0 1 1e-300 0")
    assert line == Line(P(0, 0), P(1e-300, 0))
    (arc,) = segments("M0 0 A1e300 1e300 0 1 1 1e-300 0")
    assert isinstance(arc, CircularArc)
    assert arc.sweep_rad == math.nextafter(2 * math.pi, 0)


def test_uncomputable_arc_is_an_error() -> None:
    err = error("M-1e308 0 A1e-300 1e300 0 0 1 1e308 1e308")
    assert err.message == (
        "at character 11: the arc cannot be computed in floating point "
        "(radii or coordinates too extreme)"
    )


# -- properties -----------------------------------------------------------------------------

PROPERTY = settings(
    max_examples=300,
    deadline=None,
    derandomize=True,
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.filter_too_much],
)

coordinate = st.floats(-1e3, 1e3, allow_nan=False, allow_infinity=False)
radius = st.floats(1.0, 1e3)
ratio = st.one_of(st.just(1.0), st.floats(0.25, 0.8), st.floats(1.25, 4.0))
#: Sweeps away from 0, π and 2π, where the end points do not determine the arc well.
sweep_size = st.one_of(st.floats(0.2, math.pi - 0.2), st.floats(math.pi + 0.2, 2 * math.pi - 0.2))


@st.composite
def drawn_paths(draw: st.DrawFn) -> tuple[str, list[Subpath]]:
    """Random segments and path data that describes them (absolute or relative commands)."""
    parts: list[str] = []
    subpaths: list[Subpath] = []
    for _ in range(draw(st.integers(1, 3))):
        start = cur = P(draw(coordinate), draw(coordinate))
        parts.append(f"M{start.x!r} {start.y!r}")
        segs: list[Segment] = []
        for _ in range(draw(st.integers(1, 6))):
            rel = draw(st.booleans())

            def fmt(p: Point, cur: Point = cur, rel: bool = rel) -> str:
                return f"{p.x - cur.x!r},{p.y - cur.y!r}" if rel else f"{p.x!r},{p.y!r}"

            kind = draw(st.sampled_from(["L", "Q", "C", "A"]))
            if kind == "L":
                end = P(draw(coordinate), draw(coordinate))
                segs.append(Line(cur, end))
                parts.append(f"{'l' if rel else 'L'}{fmt(end)}")
            elif kind == "Q":
                c, end = (P(draw(coordinate), draw(coordinate)) for _ in range(2))
                segs.append(Quadratic(cur, c, end))
                parts.append(f"{'q' if rel else 'Q'}{fmt(c)} {fmt(end)}")
            elif kind == "C":
                c1, c2, end = (P(draw(coordinate), draw(coordinate)) for _ in range(3))
                segs.append(Cubic(cur, c1, c2, end))
                parts.append(f"{'c' if rel else 'C'}{fmt(c1)} {fmt(c2)} {fmt(end)}")
            else:
                rx = draw(radius)
                ry = rx * draw(ratio)
                rotation_deg = draw(st.floats(-359.0, 359.0))
                rot = 0.0 if rx == ry else math.radians(rotation_deg)
                theta1 = draw(st.floats(-math.pi + 0.01, math.pi - 0.01))
                sweep = draw(sweep_size) * draw(st.sampled_from([-1, 1]))
                c, s = math.cos(rot), math.sin(rot)
                u, v = rx * math.cos(theta1), ry * math.sin(theta1)
                center = P(cur.x - (c * u - s * v), cur.y - (s * u + c * v))
                u, v = rx * math.cos(theta1 + sweep), ry * math.sin(theta1 + sweep)
                end = P(center.x + (c * u - s * v), center.y + (s * u + c * v))
                assume(end != cur)
                if rx == ry:
                    segs.append(CircularArc(cur, end, center, rx, theta1, sweep))
                else:
                    segs.append(EllipticalArc(cur, end, center, rx, ry, rot, theta1, sweep))
                flags = f"{int(abs(sweep) > math.pi)}{int(sweep > 0)}"
                parts.append(
                    f"{'a' if rel else 'A'}{rx!r} {ry!r} {rotation_deg!r} {flags}{fmt(end)}"
                )
            cur = end
        closed = draw(st.booleans())
        if closed:
            assume(math.dist(cur, start) > 1e-6)
            segs.append(Line(cur, start))
            parts.append(draw(st.sampled_from("Zz")))
        subpaths.append(Subpath(tuple(segs), closed))
    separator = draw(st.sampled_from([" ", "", "\n"]))
    return separator.join(parts), subpaths


def assert_close(got: Segment, want: Segment, scale: float) -> None:
    """Points and radii within ``1e-12 * scale``; angles within what moves a point of the arc
    by as much (``1e-12 * scale`` over the smallest radius)."""
    assert type(got) is type(want)
    radii = [getattr(want, name) for name in ("radius", "rx", "ry") if hasattr(want, name)]
    angle_tolerance = 1e-12 * scale / min(radii, default=1.0)
    for name, a, b in zip(type(want)._fields, got, want, strict=True):
        if name in ("rotation_rad", "start_angle_rad"):
            assert abs(math.remainder(a - b, 2 * math.pi)) <= angle_tolerance, (name, a, b)
        elif name == "sweep_rad":
            assert abs(a - b) <= angle_tolerance, (name, a, b)
        else:
            a, b = (a, b) if isinstance(a, tuple) else ((a,), (b,))
            assert math.dist(a, b) <= 1e-12 * scale, (name, a, b)


@PROPERTY
@given(case=drawn_paths())
def test_formatted_segments_parse_back(case: tuple[str, list[Subpath]]) -> None:
    d, expected = case
    path = parse_path_data(d)
    assert_well_formed(path)
    assert len(path.subpaths) == len(expected)
    scale = max(
        abs(v)
        for subpath in expected
        for segment in subpath.segments
        for value in segment
        for v in (value if isinstance(value, tuple) else (value,))
    )
    for got, want in zip(path.subpaths, expected, strict=True):
        assert got.closed == want.closed
        assert len(got.segments) == len(want.segments)
        for g, w in zip(got.segments, want.segments, strict=True):
            assert_close(g, w, scale)


path_characters = st.text(alphabet="MmLlHhVvCcSsQqTtAaZz0123456789.,+-eE \n", max_size=60)


@PROPERTY
@given(d=st.one_of(st.text(max_size=40), path_characters, path_characters.map("M0 0".__add__)))
def test_arbitrary_text_parses_or_raises_a_geometry_error(d: str) -> None:
    try:
        path = parse_path_data(d, max_segments=20)
    except GeometryError as err:
        caught = err
    else:
        assert_well_formed(path)
        return
    assert caught.field == "path"
    assert caught.kind in ("invalid_input", "segment_limit")
    assert caught.message.startswith("at character ") or not d.strip(" \t\n\r\f")


#: Pieces of path data, well formed and not, for text that gets past the first few characters.
path_tokens = st.lists(
    st.sampled_from(
        ["1", "-2.5", ".5", "3.", "1e3", "1E-2", "1e", "0", "01", "10", ",", " ", "\n", "+", "-",
         ".", "1e999", "L", "l", "h", "V", "C", "s", "Q", "t", "A", "a", "Z", "m", "e", "X"]
    ),
    max_size=40,
).map(lambda tokens: "M0 0" + "".join(tokens))  # fmt: skip
NEVER = re.compile(r"(?!)")


def outcome(d: str) -> str:
    try:
        return repr(parse_path_data(d))  # repr: -0.0 and 0.0 differ
    except GeometryError as err:
        return f"{err.kind}: {err.message}"


@PROPERTY
@given(
    d=st.one_of(
        path_tokens, path_characters.map("M0 0".__add__), drawn_paths().map(lambda case: case[0])
    )
)
def test_whole_argument_sets_read_as_token_by_token(d: str) -> None:
    """The parser reads a well-formed argument set in one match and falls back to reading
    token by token, which finds errors; both readings agree."""
    fast = outcome(d)
    never = dict.fromkeys(svg_data._ARGUMENT_SETS, NEVER)
    with mock.patch.dict(svg_data._ARGUMENT_SETS, never):
        assert outcome(d) == fast
