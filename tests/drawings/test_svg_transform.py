"""SVG transform lists, against matrices written out by hand (SVG 1.1 §7.4-7.6)."""

from __future__ import annotations

import math

import pytest

from arcspline.drawings.affine import Affine
from arcspline.drawings.svg_transform import TransformSyntaxError, parse_transform
from arcspline.geometry.spline import Point


def _close(m: Affine, expected: tuple[float, ...]) -> None:
    assert m == pytest.approx(expected, abs=1e-12)


@pytest.mark.parametrize(
    ("text", "expected"),
    [
        ("", (1, 0, 0, 1, 0, 0)),
        ("  ", (1, 0, 0, 1, 0, 0)),
        ("matrix(1 2 3 4 5 6)", (1, 2, 3, 4, 5, 6)),
        ("matrix(1,2,3,4,5,6)", (1, 2, 3, 4, 5, 6)),
        ("translate(7)", (1, 0, 0, 1, 7, 0)),  # ty defaults to 0
        ("translate(7 -8)", (1, 0, 0, 1, 7, -8)),
        ("scale(3)", (3, 0, 0, 3, 0, 0)),  # sy defaults to sx
        ("scale(3,-1)", (3, 0, 0, -1, 0, 0)),
        ("rotate(90)", (0, 1, -1, 0, 0, 0)),  # (1,0) -> (0,1)
        # about (10, 0): T(10,0) R(90) T(-10,0): x' = -y + 10, y' = x - 10
        ("rotate(90 10 0)", (0, 1, -1, 0, 10, -10)),
        ("skewX(45)", (1, 0, 1, 1, 0, 0)),  # tan 45° = 1
        ("skewY(45)", (1, 1, 0, 1, 0, 0)),
        ("translate(1e1,-.5E1)", (1, 0, 0, 1, 10, -5)),  # exponents, implicit separators
        ("translate(10-5)", (1, 0, 0, 1, 10, -5)),
    ],
)
def test_each_kind(text: str, expected: tuple[float, ...]) -> None:
    _close(parse_transform(text), expected)


@pytest.mark.parametrize(
    "text",
    [
        "translate(10,20) scale(2)",
        "translate(10,20),scale(2)",
        " translate( 10 , 20 ) ,\n scale( 2 ) ",
        "translate(10,20)scale(2)",
    ],
)
def test_a_list_applies_its_last_transform_first(text: str) -> None:
    # (1, 1) scaled by 2 is (2, 2), then moved by (10, 20): (12, 22)
    assert parse_transform(text).apply(Point(1.0, 1.0)) == (12.0, 22.0)


def test_rotate_about_a_point_keeps_the_point() -> None:
    m = parse_transform("rotate(33 4 -7)")
    assert m.apply(Point(4.0, -7.0)) == pytest.approx((4.0, -7.0), abs=1e-12)
    # a point 1 to the right of the centre goes 33° round it
    x, y = m.apply(Point(5.0, -7.0))
    assert (x, y) == pytest.approx(
        (4 + math.cos(math.radians(33)), -7 + math.sin(math.radians(33))), abs=1e-12
    )


@pytest.mark.parametrize(
    ("text", "offset", "words"),
    [
        ("translate(1,)", 12, "a number"),
        ("foo(1)", 0, "one of matrix"),
        ("scale()", 6, "1 or 2 numbers"),
        ("rotate(1 2)", 10, "1 or 3 numbers"),
        ("matrix(1 2 3 4 5)", 16, "6 numbers"),
        ("scale(1) ,", 10, "a transform after ','"),
        ("scale(1),,scale(2)", 9, "one of"),
        ("scale(1e999)", 6, "finite"),
        ("scale(1", 7, "')'"),
        ("scale 1", 6, "'('"),
        ("Scale(1)", 0, "one of"),
    ],
)
def test_malformed_lists_are_refused_at_their_offset(text: str, offset: int, words: str) -> None:
    with pytest.raises(TransformSyntaxError) as caught:
        parse_transform(text)
    assert f"at character {offset}:" in str(caught.value)
    assert words in str(caught.value)
