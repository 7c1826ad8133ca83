"""Lengths, viewBox, preserveAspectRatio and the document's frame, against numbers computed
by hand (SVG 2 §8.2 "equivalent transform", CSS absolute units: 1 in = 96 px = 25.4 mm)."""

from __future__ import annotations

import pytest

from arcspline.drawings.affine import Affine
from arcspline.drawings.svg_units import (
    AspectRatio,
    Length,
    UnitSyntaxError,
    ViewBox,
    document_frame,
    parse_aspect_ratio,
    parse_length,
    parse_view_box,
    user_units,
    view_box_map,
)
from arcspline.geometry.spline import Point


@pytest.mark.parametrize(
    ("text", "px"),
    [
        ("12", 12.0),
        ("12px", 12.0),
        ("1in", 96.0),
        ("2.54cm", 96.0),
        ("25.4mm", 96.0),
        ("72pt", 96.0),
        ("6pc", 96.0),
        (" 1E1PX ", 10.0),
        ("50%", 150.0),  # of the reference 300
    ],
)
def test_lengths_in_user_units(text: str, px: float) -> None:
    assert user_units(parse_length(text), 300.0) == pytest.approx(px, rel=1e-15)


@pytest.mark.parametrize("text", ["", "mm", "1 mm x", "1e999", "1furlong", "1em", "2ex", "1rem"])
def test_bad_and_font_relative_lengths_are_refused(text: str) -> None:
    with pytest.raises(UnitSyntaxError):
        parse_length(text)


def test_a_percentage_of_an_unknown_viewport_is_refused() -> None:
    with pytest.raises(UnitSyntaxError, match="unknown viewport"):
        user_units(Length(50.0, "%"), None)


def test_view_box_syntax() -> None:
    assert parse_view_box(" -1,2.5 3e1\t4 ") == ViewBox(-1.0, 2.5, 30.0, 4.0)
    for bad in ("0 0 10", "0 0 0 10", "0 0 10 -1", "a b c d", "0 0 1e999 1"):
        with pytest.raises(UnitSyntaxError):
            parse_view_box(bad)


def test_aspect_ratio_syntax() -> None:
    assert parse_aspect_ratio(None) == AspectRatio("xMidYMid", False)
    assert parse_aspect_ratio("defer xMinYMax slice") == AspectRatio("xMinYMax", True)
    assert parse_aspect_ratio("none") == AspectRatio("none", False)
    for bad in ("xmidymid", "xMidYMid stretch", "", "xMinYMin meet slice"):
        with pytest.raises(UnitSyntaxError):
            parse_aspect_ratio(bad)


# viewBox 10 20 40 20 into a 200 x 200 viewport: sx = 5, sy = 10; meet takes 5 (slack 0 in x,
# 200 - 20·5 = 100 in y), slice takes 10 (slack 200 - 40·10 = -200 in x, 0 in y).
# Translation -vx·s, -vy·s plus share·slack.
@pytest.mark.parametrize(
    ("align", "slice_", "expected"),
    [
        ("xMinYMin", False, (5, 0, 0, 5, -50, -100)),
        ("xMidYMid", False, (5, 0, 0, 5, -50, -100 + 50)),
        ("xMaxYMax", False, (5, 0, 0, 5, -50, -100 + 100)),
        ("xMinYMax", False, (5, 0, 0, 5, -50, 0)),
        ("xMinYMin", True, (10, 0, 0, 10, -100, -200)),
        ("xMidYMin", True, (10, 0, 0, 10, -100 - 100, -200)),
        ("xMaxYMid", True, (10, 0, 0, 10, -100 - 200, -200)),
        ("none", False, (5, 0, 0, 10, -50, -200)),
        ("none", True, (5, 0, 0, 10, -50, -200)),
    ],
)
def test_view_box_map(align: str, slice_: bool, expected: tuple[float, ...]) -> None:
    m = view_box_map(ViewBox(10, 20, 40, 20), 200.0, 200.0, AspectRatio(align, slice_))
    assert m == pytest.approx(expected, abs=1e-12)


def test_mm_size_with_matching_view_box_is_exact_with_y_flipped() -> None:
    frame = document_frame("200mm", "100mm", "0 0 200 100", None)
    assert frame.units == "mm"
    assert frame.viewport == (200.0, 100.0)
    assert frame.to_mm.apply(Point(0.0, 0.0)) == (0.0, 100.0)  # top-left of the canvas
    assert frame.to_mm.apply(Point(200.0, 100.0)) == (200.0, 0.0)  # bottom-right
    assert frame.notes == ()


def test_percent_size_takes_the_view_box_in_px() -> None:
    # vpype's percent_size_viewbox case: viewBox 100 100 300 300 -> 300 px = 79.375 mm
    frame = document_frame("100%", "100%", "100 100 300 300", None)
    assert frame.units == "px"
    assert frame.to_mm.apply(Point(100.0, 100.0)) == pytest.approx((0.0, 79.375), abs=1e-12)
    assert frame.to_mm.apply(Point(400.0, 400.0)) == pytest.approx((79.375, 0.0), abs=1e-12)
    assert "viewBox's size is taken in px" in frame.notes[0]


def test_one_known_side_gives_the_other_by_the_view_box_ratio() -> None:
    frame = document_frame("40mm", None, "0 0 20 10", None)  # height 20 mm
    assert frame.to_mm.apply(Point(20.0, 0.0)) == pytest.approx((40.0, 20.0))
    assert frame.to_mm.apply(Point(0.0, 10.0)) == pytest.approx((0.0, 0.0))
    assert "height" in frame.notes[0]


def test_without_view_box_one_user_unit_is_a_px() -> None:
    frame = document_frame("1in", "2in", None, None)
    assert frame.units == "in"
    assert frame.viewport == pytest.approx((96.0, 192.0))
    assert frame.to_mm.apply(Point(96.0, 0.0)) == pytest.approx((25.4, 50.8))
    bare = document_frame(None, None, None, None)
    assert bare.units == "px"
    assert bare.viewport is None
    assert bare.to_mm.apply(Point(96.0, 96.0)) == pytest.approx((25.4, -25.4))
    assert "top edge" in bare.notes[0]


def test_the_units_override_ignores_the_declared_scale() -> None:
    # The document says 1 user unit = 0.5 mm; the override says a user unit is an inch.
    frame = document_frame("100mm", "100mm", "10 0 200 200", None, units="in")
    assert frame.units == "in"
    assert frame.to_mm == Affine(25.4, 0.0, 0.0, -25.4, -254.0, 5080.0)
    assert frame.to_mm.apply(Point(10.0, 200.0)) == (0.0, 0.0)  # the viewBox's bottom-left
    with pytest.raises(UnitSyntaxError, match="units"):
        document_frame(None, None, None, None, units="furlong")


@pytest.mark.parametrize(("width", "height"), [("0", "10"), ("10", "-1mm")])
def test_a_size_of_zero_or_less_is_refused(width: str, height: str) -> None:
    with pytest.raises(UnitSyntaxError, match="must be > 0"):
        document_frame(width, height, None, None)


def test_an_auto_size_is_a_hundred_percent() -> None:
    # SVG 2: auto on the outermost svg is 100 %, so as for "100%": the viewBox in px.
    # Before, "auto" was refused as not a length.
    auto = document_frame("auto", " auto ", "100 100 300 300", None)
    assert auto == document_frame("100%", "100%", "100 100 300 300", None)
    assert auto.units == "px"
    assert auto.to_mm.apply(Point(400.0, 400.0)) == pytest.approx((79.375, 0.0), abs=1e-12)
