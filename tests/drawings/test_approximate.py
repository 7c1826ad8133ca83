"""A drawing approximated: joined, tidied and ordered toolpaths within the tolerance of the
drawing *as given* (union Hausdorff distance by the independent path oracle, against the
elements before joining and tidying moved them), the budget adding up, units, and refusals."""

from __future__ import annotations

import math
from typing import Any

import pytest

from arcspline.drawings.approximate import DrawingOptions, approximate_drawing
from arcspline.drawings.model import DocumentError, Drawing, Element
from arcspline.geometry import DEFAULT_LIMITS, GeometryError
from arcspline.geometry.curves.segments import CircularArc, Cubic, Line, Subpath
from tests.support import path_oracle

#: An open S of two cubics drawn as separate elements with a 2e-4 gap between them, a near
#: cusp (a control point 3e-5 from its end point), a circle, and a stray point.
S1 = Cubic((0.0, 0.0), (10.0, 0.0), (10.0, 10.0), (20.0, 10.0))
S2 = Cubic((20.0002, 10.0), (30.0, 10.0), (30.0, 20.00003), (30.0, 20.0))
CIRCLE = (
    CircularArc((45.0, 10.0), (35.0, 10.0), (40.0, 10.0), 5.0, 0.0, math.pi),
    CircularArc((35.0, 10.0), (45.0, 10.0), (40.0, 10.0), 5.0, math.pi, math.pi),
)
DRAWING = Drawing(
    elements=(
        Element(Subpath((S2,)), "path#s2"),
        Element(Subpath(CIRCLE, closed=True), "circle#c"),
        Element(Subpath((S1,)), "path#s1"),
        Element(Subpath((Line((7.0, 7.0), (7.0, 7.0)),)), "line#dot"),
    ),
    warnings=(),
    units="mm",
    elements_in=4,
)
AS_GIVEN = Subpath((S1, S2, *CIRCLE))


def _segments(result: Any) -> list[dict[str, Any]]:
    out = []
    for sub in result.spline.subpaths:
        for seg in sub.spline.segments:
            kind = "arc" if hasattr(seg, "radius") else "line"
            item = {"type": kind, "start": list(seg.start), "end": list(seg.end)}
            if kind == "arc":
                item |= {
                    "center": list(seg.center), "radius": seg.radius, "sweep_rad": seg.sweep_rad,
                    "direction": "ccw" if seg.sweep_rad > 0 else "cw",
                }  # fmt: skip
            out.append(item)
    return out


@pytest.mark.parametrize("strategy", ["subdivide", "fewest-arcs"])
def test_the_toolpaths_follow_the_drawing_as_given(strategy: Any) -> None:
    tolerance = 0.01
    result = approximate_drawing(DRAWING, DrawingOptions(tolerance, strategy), DEFAULT_LIMITS)
    assert len(result.toolpaths) == 2  # the S joined, the circle
    assert result.joins == 1
    budget = result.budget
    assert budget.join_gap == pytest.approx(2e-4)
    assert budget.snap_move == pytest.approx(4 / 9 * 3e-5)
    assert budget.fit == pytest.approx(tolerance - budget.join_gap - budget.snap_move)
    assert result.spline.tolerance == budget.fit
    distance = path_oracle.union_hausdorff(AS_GIVEN, _segments(result))
    assert distance.hausdorff <= tolerance + path_oracle.rounding_slack(50.0), distance
    # the stray point is left out, and said
    assert result.elements_read == 3
    assert [w.element for w in result.warnings] == ["line#dot"]


def test_toolpaths_are_ordered_from_the_origin() -> None:
    result = approximate_drawing(DRAWING, DrawingOptions(0.01), DEFAULT_LIMITS)
    assert result.toolpaths[0].subpath.segments[0].start == (0.0, 0.0)
    assert result.rapid_after <= result.rapid_before
    unordered = approximate_drawing(DRAWING, DrawingOptions(0.01, order=False), DEFAULT_LIMITS)
    assert unordered.rapid_after == unordered.rapid_before


def test_inches_scale_everything() -> None:
    result = approximate_drawing(DRAWING, DrawingOptions(0.01 / 25.4, units="inch"), DEFAULT_LIMITS)
    ends = [p for sub in result.spline.subpaths for p in sub.spline.columns.end.tolist()]
    assert max(x for x, _ in ends) == pytest.approx(45 / 25.4, rel=1e-12)


@pytest.mark.parametrize(
    ("options", "field"),
    [
        (DrawingOptions(0.0), "tolerance"),
        (DrawingOptions(math.nan), "tolerance"),
        (DrawingOptions(0.01, join_tolerance=0.005), "join_tolerance"),
        (DrawingOptions(0.01, join_tolerance=-1.0), "join_tolerance"),
    ],
)
def test_bad_options_are_refused_by_name(options: DrawingOptions, field: str) -> None:
    with pytest.raises(GeometryError) as caught:
        approximate_drawing(DRAWING, options, DEFAULT_LIMITS)
    assert caught.value.field == field


def test_a_drawing_with_nothing_to_cut_says_what_it_held() -> None:
    empty = DRAWING._replace(elements=DRAWING.elements[3:], elements_in=1)
    with pytest.raises(DocumentError, match=r"nothing to cut.*line#dot"):
        approximate_drawing(empty, DrawingOptions(0.01), DEFAULT_LIMITS)


def test_a_refusal_names_the_toolpath_and_its_elements() -> None:
    # A tolerance far below what double precision resolves at this size.
    with pytest.raises(GeometryError) as caught:
        approximate_drawing(DRAWING, DrawingOptions(1e-13), DEFAULT_LIMITS)
    assert caught.value.field == "tolerance"
    assert "at toolpaths[0].segments[0]" in caught.value.message
    assert caught.value.message.endswith("(drawn by path#s1)")  # too far to join at 1e-14


@pytest.mark.parametrize("x", [math.nan, math.inf, 1e160])
def test_an_element_beyond_the_core_is_refused_by_name_before_joining(x: float) -> None:
    wild = Element(Subpath((Line((0.0, 0.0), (x, 1.0)),)), "line#wild")
    drawing = DRAWING._replace(elements=(*DRAWING.elements, wild), elements_in=5)
    with pytest.raises(DocumentError) as caught:
        approximate_drawing(drawing, DrawingOptions(0.01), DEFAULT_LIMITS)
    assert caught.value.where == "line#wild"
    assert "not finite or beyond" in caught.value.reason
