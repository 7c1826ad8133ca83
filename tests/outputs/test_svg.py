"""The picture of an approximation (``outputs/svg.py``) and the writers' registry."""

from __future__ import annotations

import xml.etree.ElementTree as ET

import pytest

from arcspline.geometry import Spiral, approximate
from arcspline.outputs import WRITERS
from arcspline.outputs.svg import WRITER, nice_number

SVG = "{http://www.w3.org/2000/svg}"


@pytest.mark.parametrize(
    ("x", "nice"),
    [
        (1.0, 1.0),
        (199.0, 100.0),
        (200.0, 200.0),
        (0.07, 0.05),
        (5e6, 5e6),
        (1e-320, 1e-300),
        (0.0, 1e-300),
        (float("inf"), 1e300),
    ],
)
def test_magnifications_are_round_numbers(x: float, nice: float) -> None:
    assert nice_number(x) == pytest.approx(nice)


def test_the_writer_draws_every_segment_of_a_fewest_arcs_spline() -> None:
    spiral = Spiral.from_parameters((1.5, 3.0), (1.0, 0.0), 51.34, -0.41574)
    spline = approximate(spiral, 1e-3, "fewest-arcs")
    root = ET.fromstring(WRITER.write([(spline, spiral)]))
    arcs = [p for p in root.iter(f"{SVG}path") if " A" in p.get("d", "")]
    assert len(arcs) == len(spline) == 7
    legend = " ".join(t.text or "" for t in root.iter(f"{SVG}text"))
    assert "7 arcs, 0 lines (fewest-arcs)" in legend


def test_each_writer_is_registered_under_its_name() -> None:
    assert set(WRITERS) == {"gcode", "svg", "dxf", "svg-document", "drawing-preview"}
    for name, writer in WRITERS.items():
        assert writer.name == name
        assert "/" in writer.media_type
