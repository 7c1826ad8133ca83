"""The SVG drawing (``outputs/svg_document.py``): well-formed XML in real units whose paths,
read back by the strict path-data parser and un-flipped (the document's y is the drawing's
−y), are the spline's own segments: end points and radii exactly, centres within 1e-9 of
the coordinate scale, each arc turning the spline's way."""

from __future__ import annotations

import math
import xml.etree.ElementTree as ET

import numpy as np
import pytest

from arcspline.geometry import CircularArc, GeometryError, Line
from arcspline.geometry.spline import COLUMN
from arcspline.outputs.svg_document import (
    HALF_CIRCLE_MARGIN,
    WRITER,
    SvgDocumentOptions,
)
from arcspline.paths import parse_path_data

from .test_dxf import NAMES, RTOL, parts_of, scale_of, spline_midpoint

SVG = "{http://www.w3.org/2000/svg}"


def unflip(segment: Line | CircularArc) -> Line | CircularArc:
    """The segment in drawing coordinates (y up): y negated, arcs turning the other way."""

    def point(p: tuple[float, float]) -> tuple[float, float]:
        return (p[0], -p[1])

    if isinstance(segment, Line):
        return Line(point(segment.start), point(segment.end))  # type: ignore[arg-type]
    return CircularArc(
        point(segment.start),  # type: ignore[arg-type]
        point(segment.end),  # type: ignore[arg-type]
        point(segment.center),  # type: ignore[arg-type]
        segment.radius,
        -segment.start_angle_rad,
        -segment.sweep_rad,
    )


def number(text: str, unit: str) -> float:
    assert text.endswith(unit), text
    return float(text.removesuffix(unit))


@pytest.mark.parametrize("name", NAMES)
def test_paths_read_back_as_the_splines_segments(name: str) -> None:
    parts = parts_of(name)
    near = RTOL * scale_of(parts)
    root = ET.fromstring(WRITER.write(parts, SvgDocumentOptions()))
    paths = list(root.iter(f"{SVG}path"))
    group = root.find(f"{SVG}g")
    assert group is not None
    assert group.get("fill") == "none"
    assert group.get("stroke") == "black"
    assert [p.get("id") for p in paths] == [f"toolpath-{k}" for k in range(1, len(parts) + 1)]
    c = COLUMN
    for element, (spline, _) in zip(paths, parts, strict=True):
        (subpath,) = parse_path_data(element.get("d", "")).subpaths
        read = [unflip(s) for s in subpath.segments]  # type: ignore[arg-type]
        rows = spline.table
        closed = tuple(rows[-1, c["end_x"] : c["end_y"] + 1]) == tuple(
            rows[0, c["start_x"] : c["start_y"] + 1]
        )
        assert subpath.closed == closed
        k = 0
        for row in rows:
            start = tuple(row[c["start_x"] : c["start_y"] + 1])
            end = tuple(row[c["end_x"] : c["end_y"] + 1])
            if row[c["is_arc"]] == 0:
                segment = read[k]
                k += 1
                assert isinstance(segment, Line)
                assert (segment.start, segment.end) == (start, end)
                continue
            sweep = row[c["sweep_rad"]]
            # A half circle comes back as its two halves (the module's documented rule).
            halves = 2 if abs(math.cos(sweep / 2)) < HALF_CIRCLE_MARGIN else 1
            pieces = read[k : k + halves]
            k += halves
            assert all(isinstance(p, CircularArc) for p in pieces)
            assert (pieces[0].start, pieces[-1].end) == (start, end)
            centre = row[c["center_x"] : c["center_y"] + 1]
            for piece in pieces:
                assert isinstance(piece, CircularArc)
                assert piece.radius == pytest.approx(row[c["radius"]], rel=1e-15)
                assert np.abs(np.array(piece.center) - centre).max() <= near
            read_sweep = sum(p.sweep_rad for p in pieces if isinstance(p, CircularArc))
            assert read_sweep == pytest.approx(sweep, rel=RTOL)
            # The middle of the arc as read, from its own centre and start angle.
            first = pieces[0]
            assert isinstance(first, CircularArc)
            middle = first.start_angle_rad + read_sweep / 2
            at = np.array(first.center) + first.radius * np.array(
                [math.cos(middle), math.sin(middle)]
            )
            assert np.abs(at - spline_midpoint(row)).max() <= near
        assert k == len(read)


def test_the_mixed_case_has_a_half_circle_to_split() -> None:
    parts = parts_of("mixed")
    rows = parts[0][0].table
    assert np.any(np.abs(np.cos(rows[:, COLUMN["sweep_rad"]] / 2)) < HALF_CIRCLE_MARGIN)


@pytest.mark.parametrize(
    ("units", "unit", "mm_per_unit"), [("mm", "mm", 1.0), ("inch", "in", 25.4)]
)
@pytest.mark.parametrize("name", NAMES)
def test_the_document_is_in_real_units_and_holds_the_drawing(
    name: str, units: str, unit: str, mm_per_unit: float
) -> None:
    parts = parts_of(name)
    text = WRITER.write(parts, SvgDocumentOptions(units=units))  # type: ignore[arg-type]
    root = ET.fromstring(text)
    assert root.tag == f"{SVG}svg"
    width, height = number(root.get("width", ""), unit), number(root.get("height", ""), unit)
    x0, y0, w, h = (float(v) for v in root.get("viewBox", "").split())
    assert (w, h) == (width, height)  # one user unit is one drawing unit
    # Every end point, flipped, lies inside the viewBox with room to spare.
    rows = np.concatenate([s.table for s, _ in parts])
    c = COLUMN
    for x_col, y_col in (("start_x", "start_y"), ("end_x", "end_y")):
        x, y = rows[:, c[x_col]], -rows[:, c[y_col]]
        assert np.all((x > x0) & (x < x0 + w) & (y > y0) & (y < y0 + h))


def test_no_transform_is_used() -> None:
    text = WRITER.write(parts_of("mixed"), None)
    assert "transform" not in text


def test_coordinates_that_are_not_finite_are_refused() -> None:
    from .test_dxf import arc_row, synthetic

    spline = synthetic([{**arc_row(0.0, 1.0), "end_y": math.inf}])
    with pytest.raises(GeometryError) as caught:
        WRITER.write([(spline, None)], None)  # type: ignore[list-item]
    assert (caught.value.field, caught.value.kind) == ("parts", "precision")


def test_bad_units_are_refused_by_name() -> None:
    with pytest.raises(GeometryError) as caught:
        SvgDocumentOptions(units="px")  # type: ignore[arg-type]
    assert caught.value.field == "units"


def test_no_parts_give_an_empty_document() -> None:
    root = ET.fromstring(WRITER.write([], None))
    assert list(root.iter(f"{SVG}path")) == []
    assert root.get("width", "").endswith("mm")


def test_the_writer_is_named_and_typed() -> None:
    assert WRITER.name == "svg-document"
    assert WRITER.media_type == "image/svg+xml"
