"""The picture of a whole drawing (``outputs/drawing_preview.py``): well-formed SVG with one
numbered, zoomable group per toolpath in cutting order, one dashed rapid per toolpath
(the first from the start point), corners dotted where the direction of travel turns, a
scale bar of a round length that is as long as it says, and a bounded number of samples.

The picture's map from drawing to pixels is recovered from the picture itself (the start
points of two toolpaths), so the checks do not use the module's frame. Tool-centre paths
add the part's contours and the swept band, the tool's diameter wide at the picture's scale
(recovered from a contour's radius in pixels).
"""

from __future__ import annotations

import math
import re
import xml.etree.ElementTree as ET

import numpy as np
import pytest

import arcspline
from arcspline.outputs import WRITERS
from arcspline.outputs.drawing_preview import (
    DEVIATION_SAMPLES,
    PreviewOptions,
    ToolView,
    corners,
    render_drawing,
)
from arcspline.outputs.part import Part

from .test_dxf import parts_of

SVG = "{http://www.w3.org/2000/svg}"
SQUARE = "M 0 0 L 10 0 L 10 10 L 0 10 Z"
CIRCLE = "M 10 0 A 10 10 0 0 1 -10 0 A 10 10 0 0 1 10 0 Z"


def parts(data: str, tolerance: float = 0.01) -> list[Part]:
    result = arcspline.approximate_path(arcspline.parse_path_data(data), tolerance)
    return [(s.spline, s.curve) for s in result.subpaths]


def first_point(d: str) -> tuple[float, float]:
    x, y = re.match(r"M([-\d.]+),([-\d.]+)", d).groups()  # type: ignore[union-attr]
    return float(x), float(y)


def command_points(d: str) -> list[tuple[float, float]]:
    """The point each command of ``d`` ends at (its last coordinate pair)."""
    pairs = (re.findall(r"([-\d.]+),([-\d.]+)", command) for command in re.split(r"[MLA]", d))
    return [(float(found[-1][0]), float(found[-1][1])) for found in pairs if found]


def last_point(d: str) -> tuple[float, float]:
    return command_points(d)[-1]


def is_round(value: float) -> bool:
    """Whether ``value`` is 1, 2 or 5 × 10^k."""
    mantissa = value / 10 ** math.floor(math.log10(value) + 1e-9)
    return bool(min(abs(mantissa - m) for m in (1, 2, 5)) < 1e-9)


def picture(drawing: list[Part], **options: object) -> ET.Element:
    return ET.fromstring(render_drawing(drawing, **options))  # type: ignore[arg-type]


def cuts(root: ET.Element) -> list[str]:
    return [p.get("d", "") for p in root.iter(f"{SVG}path") if p.get("class") == "cut"]


def test_toolpaths_are_numbered_in_cutting_order_with_a_rapid_to_each() -> None:
    drawing = parts_of("mixed") + parts("M 200 50 L 210 60 L 220 50")
    start = (-20.0, -10.0)
    root = picture(drawing, start=start)
    groups = [g for g in root.iter(f"{SVG}g") if g.get("class") == "toolpath"]
    assert [g.get("id") for g in groups] == ["toolpath-1", "toolpath-2", "toolpath-3"]
    numbers = [t for t in root.iter(f"{SVG}text") if t.get("class") == "number"]
    assert [t.text for t in numbers] == ["1", "2", "3"]
    views = [v.get("id") for v in root.iter(f"{SVG}view")]
    assert views == ["view-toolpath-1", "view-toolpath-2", "view-toolpath-3"]
    for group in groups:
        title = group.find(f"{SVG}title")
        assert title is not None
        assert title.text is not None
        assert title.text.startswith(f"toolpath {group.get('id', '')[-1]}:")
        found = re.search(r"deviation ×(\S+)$", title.text)
        assert found is not None
        assert is_round(float(found.group(1)))
    rapids = [line for line in root.iter(f"{SVG}line") if line.get("class") == "rapid"]
    assert len(rapids) == len(drawing)
    rapid_group = next(g for g in root.iter(f"{SVG}g") if g.get("class") == "rapids")
    assert rapid_group.get("stroke-dasharray")
    paths = cuts(root)
    assert len(paths) == len(drawing)
    # Each rapid ends where its toolpath starts and begins where the one before ends.
    for k, rapid in enumerate(rapids):
        end = float(rapid.get("x2", "")), float(rapid.get("y2", ""))
        assert end == first_point(paths[k])
        if k:
            begin = float(rapid.get("x1", "")), float(rapid.get("y1", ""))
            assert begin == pytest.approx(last_point(paths[k - 1]), abs=2e-3)
    # The first rapid begins at `start`: recover the map from two toolpaths' start points.
    (w0, p0), (w1, p1) = (
        (drawing[k][0].columns.start[0], np.array(first_point(paths[k]))) for k in (0, 2)
    )
    scale = (p1[0] - p0[0]) / (w1[0] - w0[0])
    assert (p1[1] - p0[1]) / (w1[1] - w0[1]) == pytest.approx(-scale, rel=1e-4)  # y flipped
    first = np.array([float(rapids[0].get("x1", "")), float(rapids[0].get("y1", ""))])
    expected = p0 + scale * np.array([start[0] - w0[0], -(start[1] - w0[1])])
    assert first == pytest.approx(expected, abs=2e-3)
    # The number of each toolpath sits at its start point.
    for k, text in enumerate(numbers):
        x, y = float(text.get("x", "")), float(text.get("y", ""))
        assert (x - 4, y + 4) == pytest.approx(first_point(paths[k]), abs=2e-3)


def test_everything_drawn_lies_inside_the_canvas() -> None:
    root = picture(parts_of("huge") + parts_of("mixed"))
    width, height = float(root.get("width", "")), float(root.get("height", ""))
    for d in cuts(root):
        xy = np.array(re.findall(r"([-\d.]+),([-\d.]+)", d), dtype=float)
        assert np.all((xy >= 0) & (xy <= [width, height]))


@pytest.mark.parametrize("data", ["mixed", "tiny", "huge"])
def test_the_scale_bar_is_a_round_length_and_as_long_as_it_says(data: str) -> None:
    drawing = parts_of(data) + parts_of(data)
    root = picture(drawing, units="mm")
    bar = next(g for g in root.iter(f"{SVG}g") if g.get("class") == "scale-bar")
    label = bar.find(f"{SVG}text")
    assert label is not None
    assert label.text is not None
    value_text, unit = label.text.split()
    assert unit == "mm"
    value = float(value_text)
    assert is_round(value)
    # Its length in pixels against the picture's own map (two toolpath starts).
    path = bar.find(f"{SVG}path")
    assert path is not None
    numbers = [float(v) for v in re.findall(r"-?[\d.]+", path.get("d", ""))]
    bar_px = numbers[3] - numbers[0]  # "M bx,by-5 V by H x_end V by-5"
    paths = cuts(root)
    spline = drawing[0][0]
    # Two known points of one toolpath, far apart: its start and the farthest joint.
    points = command_points(paths[0])
    far = int(np.argmax(np.hypot(*(spline.columns.end - spline.columns.start[0]).T)))
    w0, w1 = spline.columns.start[0], spline.columns.end[far]
    p0, p1 = np.array(points[0]), np.array(points[far + 1])
    scale = float(np.hypot(*(p1 - p0)) / np.hypot(*(w1 - w0)))
    assert bar_px == pytest.approx(value * scale, rel=1e-3)


def test_corners_are_marked_where_the_direction_turns() -> None:
    (square,) = parts(SQUARE)
    assert {tuple(p) for p in corners(square[0]).tolist()} == {
        (10.0, 0.0),
        (10.0, 10.0),
        (0.0, 10.0),
        (0.0, 0.0),
    }
    (circle,) = parts(CIRCLE, 0.001)
    assert len(corners(circle[0])) == 0  # tangent everywhere, closing joint included
    (open_turn,) = parts("M 0 0 L 10 0 L 10 0.1 L 20 0.1")
    assert len(corners(open_turn[0])) == 2  # two 90° turns, no closing joint
    (slight,) = parts("M 0 0 L 10 0 L 20 0.1")  # 0.57°: below the 1° threshold
    assert len(corners(slight[0])) == 0
    root = picture([square, circle])
    counts = [
        len(list(g.iter(f"{SVG}circle")))
        for g in root.iter(f"{SVG}g")
        if g.get("class") == "corners"
    ]
    assert counts == [4, 0]


def test_the_deviation_view_is_drawn_per_toolpath_within_a_sample_budget() -> None:
    many = " ".join(f"M {3 * i} 0 C {3 * i + 1} 2 {3 * i + 2} -2 {3 * i + 3} 1" for i in range(120))
    drawing = parts(many, 1e-4)
    segments = sum(len(s) for s, _ in drawing)
    assert segments > 2000
    root = picture(drawing)
    samples = 0
    for group in (g for g in root.iter(f"{SVG}g") if g.get("class") == "toolpath"):
        deviation = group.find(f"{SVG}g[@class='deviation']")
        assert deviation is not None
        polylines = deviation.findall(f"{SVG}polyline")
        assert polylines
        samples += sum(len(p.get("points", "").split()) for p in polylines)
    assert samples <= max(DEVIATION_SAMPLES, 3 * segments)


def test_an_empty_drawing_still_draws() -> None:
    root = picture([])
    assert root.tag == f"{SVG}svg"
    assert not [t for t in root.iter(f"{SVG}text") if t.get("class") == "number"]


# -- tool-centre paths: the contours and the swept band ---------------------------------------

TOOL_CIRCLE = "M 12 0 A 12 12 0 0 1 -12 0 A 12 12 0 0 1 12 0 Z"
INNER_CIRCLE = "M 8 0 A 8 8 0 0 1 -8 0 A 8 8 0 0 1 8 0 Z"


def groups(root: ET.Element) -> dict[str, ET.Element]:
    return {g.get("class", ""): g for g in root.iter(f"{SVG}g") if g.get("class")}


def arc_radii(d: str) -> list[float]:
    return [float(r) for r in re.findall(r"A([\d.e+-]+),", d)]


def test_a_tool_view_draws_the_contour_and_a_band_of_the_tools_diameter() -> None:
    contour = parts(CIRCLE)[0][0]
    view = ToolView((contour,), 4.0, "offset 2 outside")
    root = ET.fromstring(render_drawing(parts(TOOL_CIRCLE), tool=view))
    found = groups(root)
    (drawn,) = [p.get("d", "") for p in found["contours"]]
    (band,) = [p.get("d", "") for p in found["swept"]]
    # The picture's scale from the contour (radius 10) drawn as arcs; the band is the tool
    # path itself (radius 12), stroked as wide as the tool.
    scale = arc_radii(drawn)[0] / 10.0
    assert arc_radii(drawn) == pytest.approx([10.0 * scale] * 2, rel=1e-5)
    assert arc_radii(band) == pytest.approx([12.0 * scale] * 2, rel=1e-5)
    assert band == cuts(root)[0]
    assert float(found["swept"].get("stroke-width", "")) == pytest.approx(4.0 * scale, rel=1e-5)
    assert found["swept"].get("stroke-linecap") == found["swept"].get("stroke-linejoin") == "round"
    assert 0 < float(found["swept"].get("stroke-opacity", "")) < 1
    assert found["contours"].get("stroke") != found["swept"].get("stroke")
    legend = " ".join(t.text or "" for t in root.iter(f"{SVG}text"))
    assert "offset 2 outside" in legend
    assert "swept width 4 mm" in legend


def test_the_frame_holds_contours_larger_than_the_tool_paths() -> None:
    contour = parts(CIRCLE)[0][0]
    view = ToolView((contour,), 4.0, "offset 2 inside")
    root = ET.fromstring(render_drawing(parts(INNER_CIRCLE), tool=view))
    width, height = float(root.get("width", "")), float(root.get("height", ""))
    (drawn,) = [p.get("d", "") for p in groups(root)["contours"]]
    # The contour's leftmost and rightmost points (its arcs' ends) and its radius in pixels.
    xy = np.array(re.findall(r"([-\d.]+),([-\d.]+)", drawn), dtype=float)
    radius_px = arc_radii(drawn)[0]
    left, right = xy[:, 0].min(), xy[:, 0].max()
    assert right - left == pytest.approx(2 * radius_px, rel=1e-4)
    top = xy[:, 1].mean() - radius_px
    bottom = xy[:, 1].mean() + radius_px
    assert 0 <= left < right <= width
    assert 0 <= top < bottom <= height


def test_the_writer_takes_preview_options() -> None:
    contour = parts(CIRCLE)[0][0]
    options = PreviewOptions("inch", ToolView((contour,), 0.25, "tool ⌀0.25"))
    text = WRITERS["drawing-preview"].write(parts(TOOL_CIRCLE), options)
    assert "swept width 0.25 inch" in text
    assert "tool ⌀0.25" in text
    plain = WRITERS["drawing-preview"].write(parts(TOOL_CIRCLE), "inch")
    assert 'class="swept"' not in plain
    assert 'class="contours"' not in plain
