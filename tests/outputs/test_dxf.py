"""The DXF drawing (``outputs/dxf.py``), read back with ezdxf itself: every LINE, ARC and
LWPOLYLINE vertex lands on the spline's own segment table within 1e-9 of the coordinate
scale, each arc turning the spline's way (its midpoint, computed from the entity alone, is
the spline's), with the units, layers and extents the options ask for.

The parts come from real approximations: a path of a cubic, lines, a half circle, a
rotated elliptical arc and a large clockwise arc; a clockwise circle; the same shapes at
1e-3 mm and at 1e5 mm.
"""

from __future__ import annotations

import io
import math
from functools import cache

import numpy as np
import pytest
from ezdxf.document import Drawing
from ezdxf.entities.dxfgfx import DXFGraphic
from ezdxf.entities.lwpolyline import LWPolyline
from ezdxf.filemanagement import read as read_document

import arcspline
from arcspline.geometry import GeometryError
from arcspline.geometry.spline import COLUMN, ArcSpline, SplineStats
from arcspline.outputs.dxf import WRITER, DxfOptions
from arcspline.outputs.part import Part

#: (name, path data, tolerance).
CASES = [
    (
        "mixed",
        "M 0 0 C 10 0 20 10 30 30 L 40 30 A 5 5 0 0 1 50 30 Z "
        "M 60 0 A 8 4 30 0 1 80 10 L 90 0 A 6 6 0 1 0 100 0 Q 105 10 110 0",
        0.01,
    ),
    ("clockwise-circle", "M 10 0 A 10 10 0 0 0 -10 0 A 10 10 0 0 0 10 0 Z", 0.001),
    (
        "tiny",
        "M 0 0 C 0.001 0 0.002 0.001 0.003 0.003 A 0.002 0.002 0 0 0 0.005 0.001 L 0.004 0",
        1e-6,
    ),
    (
        "huge",
        "M 100000 100000 C 110000 100000 120000 110000 130000 130000 "
        "A 5000 5000 0 1 0 140000 120000 L 135000 100000 Z",
        1.0,
    ),
]
NAMES = [name for name, _, _ in CASES]
RTOL = 1e-9


@cache
def parts_of(name: str) -> list[Part]:
    _, data, tolerance = next(case for case in CASES if case[0] == name)
    result = arcspline.approximate_path(arcspline.parse_path_data(data), tolerance)
    return [(s.spline, s.curve) for s in result.subpaths]


def scale_of(parts: list[Part]) -> float:
    """The coordinate scale: the largest coordinate magnitude of any end point or centre."""
    rows = np.concatenate([spline.table for spline, _ in parts])
    c = COLUMN
    arcs = rows[:, c["is_arc"]] != 0
    points = [rows[:, c["start_x"] : c["end_y"] + 1], rows[arcs, c["center_x"] : c["center_y"] + 1]]
    return float(max(np.abs(p).max() for p in points if p.size))


def read(text: str) -> Drawing:
    return read_document(io.StringIO(text))


def spline_midpoint(row: np.ndarray) -> np.ndarray:
    """The arc's middle point, from its table row's centre, radius and angles."""
    c = COLUMN
    middle = row[c["start_angle_rad"]] + row[c["sweep_rad"]] / 2
    point: np.ndarray = np.array([row[c["center_x"]], row[c["center_y"]]]) + row[
        c["radius"]
    ] * np.array([math.cos(middle), math.sin(middle)])
    return point


def at_deg(centre: np.ndarray, radius: float, angle_deg: float) -> np.ndarray:
    a = math.radians(angle_deg)
    point: np.ndarray = centre + radius * np.array([math.cos(a), math.sin(a)])
    return point


@pytest.mark.parametrize("name", NAMES)
def test_lines_and_arcs_read_back_as_the_splines_segments(name: str) -> None:
    parts = parts_of(name)
    near = RTOL * scale_of(parts)
    doc = read(WRITER.write(parts, DxfOptions()))
    entities = list(doc.modelspace())
    rows = np.concatenate([spline.table for spline, _ in parts])
    assert len(entities) == len(rows)
    c = COLUMN
    clockwise = 0
    for entity, row in zip(entities, rows, strict=True):
        start = row[c["start_x"] : c["start_y"] + 1]
        end = row[c["end_x"] : c["end_y"] + 1]
        assert entity.dxf.layer == "ARCSPLINE"
        if row[c["is_arc"]] == 0:
            assert entity.dxftype() == "LINE"
            assert tuple(entity.dxf.start)[:2] == tuple(start)
            assert tuple(entity.dxf.end)[:2] == tuple(end)
            continue
        assert entity.dxftype() == "ARC"
        centre = np.array(entity.dxf.center)[:2]
        radius = entity.dxf.radius
        assert tuple(centre) == tuple(row[c["center_x"] : c["center_y"] + 1])
        assert radius == row[c["radius"]]
        first = at_deg(centre, radius, entity.dxf.start_angle)
        last = at_deg(centre, radius, entity.dxf.end_angle)
        sweep = row[c["sweep_rad"]]
        if sweep < 0:  # written anticlockwise, from the spline's end to its start
            first, last = last, first
            clockwise += 1
        assert np.abs(first - start).max() <= near
        assert np.abs(last - end).max() <= near
        ccw_deg = (entity.dxf.end_angle - entity.dxf.start_angle) % 360.0
        assert ccw_deg == pytest.approx(math.degrees(abs(sweep)), abs=1e-9)
        middle = at_deg(centre, radius, entity.dxf.start_angle + ccw_deg / 2)
        assert np.abs(middle - spline_midpoint(row)).max() <= near
    if name in ("mixed", "clockwise-circle", "huge"):
        assert clockwise > 0


def bulge_arc(p0: np.ndarray, p1: np.ndarray, bulge: float) -> tuple[np.ndarray, float, float]:
    """Centre, radius and signed sweep of a bulged polyline segment (bulge = tan(sweep/4))."""
    sweep = 4.0 * math.atan(bulge)
    chord = p1 - p0
    length = math.hypot(*chord)
    left = np.array([-chord[1], chord[0]]) / length
    centre = (p0 + p1) / 2 + left * (length / 2) / math.tan(sweep / 2)
    return centre, length / (2 * abs(math.sin(sweep / 2))), sweep


@pytest.mark.parametrize("name", NAMES)
def test_polylines_carry_the_arcs_as_bulges(name: str) -> None:
    parts = parts_of(name)
    near = RTOL * scale_of(parts)
    doc = read(WRITER.write(parts, DxfOptions(polyline=True)))
    polylines = list(doc.modelspace())
    assert [e.dxftype() for e in polylines] == ["LWPOLYLINE"] * len(parts)
    c = COLUMN
    for polyline, (spline, _) in zip(polylines, parts, strict=True):
        assert isinstance(polyline, LWPolyline)
        rows = spline.table
        vertices = [np.array(v[:2]) for v in polyline.get_points("xyb")]
        bulges = [v[2] for v in polyline.get_points("xyb")]
        closed = bool(rows[-1, c["end_x"]] == rows[0, c["start_x"]]) and bool(
            rows[-1, c["end_y"]] == rows[0, c["start_y"]]
        )
        assert polyline.closed == closed
        assert len(vertices) == len(rows) + (0 if closed else 1)
        for i, row in enumerate(rows):
            p0, p1 = vertices[i], vertices[(i + 1) % len(vertices)]
            assert tuple(p0) == tuple(row[c["start_x"] : c["start_y"] + 1])
            assert tuple(p1) == tuple(row[c["end_x"] : c["end_y"] + 1])
            if row[c["is_arc"]] == 0:
                assert bulges[i] == 0.0
                continue
            centre, radius, sweep = bulge_arc(p0, p1, bulges[i])
            assert np.abs(centre - row[c["center_x"] : c["center_y"] + 1]).max() <= near
            assert radius == pytest.approx(row[c["radius"]], rel=RTOL)
            assert sweep == pytest.approx(row[c["sweep_rad"]], rel=RTOL)
            rotate = sweep / 2
            cos, sin = math.cos(rotate), math.sin(rotate)
            d = p0 - centre
            middle = centre + np.array([cos * d[0] - sin * d[1], sin * d[0] + cos * d[1]])
            assert np.abs(middle - spline_midpoint(row)).max() <= near


@pytest.mark.parametrize(("units", "insunits", "measurement"), [("mm", 4, 1), ("inch", 1, 0)])
def test_units_are_declared_in_the_header(units: str, insunits: int, measurement: int) -> None:
    doc = read(WRITER.write(parts_of("mixed"), DxfOptions(units=units)))  # type: ignore[arg-type]
    assert doc.dxfversion == "AC1015"  # R2000
    assert doc.header["$INSUNITS"] == insunits
    assert doc.header["$MEASUREMENT"] == measurement


def test_layer_per_part_puts_each_toolpath_on_its_own_layer() -> None:
    parts = parts_of("mixed")
    doc = read(WRITER.write(parts, DxfOptions(layer_per_part=True)))
    layers = [e.dxf.layer for e in doc.modelspace()]
    expected = [f"TOOLPATH_{k}" for k, (s, _) in enumerate(parts, 1) for _ in range(len(s))]
    assert layers == expected
    assert {"TOOLPATH_1", "TOOLPATH_2"} <= {layer.dxf.name for layer in doc.layers}
    doc = read(WRITER.write(parts, DxfOptions(polyline=True, layer_per_part=True)))
    assert [e.dxf.layer for e in doc.modelspace()] == ["TOOLPATH_1", "TOOLPATH_2"]


@pytest.mark.parametrize("name", NAMES)
def test_extents_bound_the_drawing_tightly(name: str) -> None:
    parts = parts_of(name)
    doc = read(WRITER.write(parts, DxfOptions()))
    # Dense samples of every segment, from its row: the box must hold them and be no larger.
    samples = []
    c = COLUMN
    for row in np.concatenate([s.table for s, _ in parts]):
        t = np.linspace(0, 1, 2001)[:, None]
        if row[c["is_arc"]]:
            a = row[c["start_angle_rad"]] + row[c["sweep_rad"]] * t[:, 0]
            centre = row[c["center_x"] : c["center_y"] + 1]
            samples.append(centre + row[c["radius"]] * np.stack([np.cos(a), np.sin(a)], -1))
        else:
            start, end = row[c["start_x"] : c["start_y"] + 1], row[c["end_x"] : c["end_y"] + 1]
            samples.append(start + (end - start) * t)
    every = np.concatenate(samples)
    low, high = every.min(axis=0), every.max(axis=0)
    size = float((high - low).max())
    extmin, extmax = np.array(doc.header["$EXTMIN"])[:2], np.array(doc.header["$EXTMAX"])[:2]
    assert np.all(extmin <= low + 1e-12 * scale_of(parts))
    assert np.all(extmax >= high - 1e-12 * scale_of(parts))
    assert np.all(low - extmin <= 1e-5 * size)  # sampling misses the extreme by ~(π/2000)²/2
    assert np.all(extmax - high <= 1e-5 * size)


def synthetic(rows: list[dict[str, float]]) -> ArcSpline:
    """A spline of the given rows (fields by name, the rest 0), for edge cases."""
    table = np.zeros((len(rows), len(COLUMN)))
    for i, row in enumerate(rows):
        for field, value in row.items():
            table[i, COLUMN[field]] = value
    stats = SplineStats(len(rows), 0, 0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0)
    return ArcSpline(table, stats, 0.01, "subdivide")


def arc_row(start_rad: float, sweep_rad: float, radius: float = 2.0) -> dict[str, float]:
    end_rad = start_rad + sweep_rad
    return {
        "is_arc": 1.0,
        "start_x": radius * math.cos(start_rad),
        "start_y": radius * math.sin(start_rad),
        "end_x": radius * math.cos(end_rad),
        "end_y": radius * math.sin(end_rad),
        "radius": radius,
        "start_angle_rad": start_rad,
        "sweep_rad": sweep_rad,
    }


def ccw_extent_deg(entities: list[DXFGraphic]) -> float:
    """The anticlockwise extent of ARC entities, in degrees, as a reader sees it."""
    return float(sum((e.dxf.end_angle - e.dxf.start_angle) % 360.0 for e in entities))


@pytest.mark.parametrize("sweep_rad", [1e-17, 1e-16, 4e-16, 1e-15, 1e-13])
@pytest.mark.parametrize("start_rad", [0.0, 1.0, -2.5])
@pytest.mark.parametrize("sign", [1.0, -1.0])
def test_tiny_sweeps_never_read_as_circles(sweep_rad: float, start_rad: float, sign: float) -> None:
    # Rounding of the end points can make the angles equal (a reader's full circle) or
    # swapped (the complement): the segment must still read as a sliver or its chord.
    spline = synthetic([arc_row(start_rad, sign * sweep_rad)])
    entities = list(read(WRITER.write([(spline, None)], DxfOptions())).modelspace())  # type: ignore[list-item]
    arcs = [e for e in entities if e.dxftype() == "ARC"]
    assert len(entities) == 1
    assert ccw_extent_deg(arcs) <= 1e-9


@pytest.mark.parametrize("gap_rad", [0.0, 1e-16, 1e-15, 4e-15, 1e-13])
@pytest.mark.parametrize("start_rad", [0.0, 0.5, -2.5])
@pytest.mark.parametrize("sign", [1.0, -1.0])
def test_near_circles_never_read_as_slivers(gap_rad: float, start_rad: float, sign: float) -> None:
    sweep_rad = sign * math.nextafter(2 * math.pi - gap_rad, 0.0)
    spline = synthetic([arc_row(start_rad, sweep_rad)])
    entities = list(read(WRITER.write([(spline, None)], DxfOptions())).modelspace())  # type: ignore[list-item]
    assert {e.dxftype() for e in entities} == {"ARC"}
    assert ccw_extent_deg(entities) == pytest.approx(360.0, abs=1e-9)


def test_coordinates_that_are_not_finite_are_refused() -> None:
    spline = synthetic([{**arc_row(0.0, 1.0), "center_x": math.nan}])
    with pytest.raises(GeometryError) as caught:
        WRITER.write([(spline, None)], DxfOptions())  # type: ignore[list-item]
    assert caught.value.field == "parts"
    assert caught.value.kind == "precision"


def test_no_parts_give_an_empty_drawing() -> None:
    doc = read(WRITER.write([], None))
    assert len(doc.modelspace()) == 0
    assert doc.header["$INSUNITS"] == 4


@pytest.mark.parametrize(
    ("options", "field"),
    [
        ({"units": "cm"}, "units"),
        ({"polyline": 1}, "polyline"),
        ({"layer_per_part": "yes"}, "layer_per_part"),
    ],
)
def test_bad_options_are_refused_by_name(options: dict[str, object], field: str) -> None:
    with pytest.raises(GeometryError) as caught:
        DxfOptions(**options)  # type: ignore[arg-type]
    assert caught.value.field == field


def test_the_writer_is_named_and_typed() -> None:
    assert WRITER.name == "dxf"
    assert WRITER.media_type == "image/vnd.dxf"


def test_the_same_spline_gives_the_same_bytes() -> None:
    """No time stamp or fresh GUID: a DXF is a function of its request."""
    parts = parts_of(NAMES[0])
    first = WRITER.write(parts, DxfOptions())
    second = WRITER.write(parts, DxfOptions())
    assert first == second


def test_ezdxf_keeps_its_own_metadata_setting_for_other_writers() -> None:
    import ezdxf

    WRITER.write(parts_of(NAMES[0]), DxfOptions())
    assert ezdxf.options.write_fixed_meta_data_for_testing is False  # type: ignore[attr-defined]
