"""Text outlines from the shared corpus (read in place), offset inside and outside."""

from __future__ import annotations

import pytest

from arcspline.drawings import DrawingOptions, approximate_drawing, read_svg
from arcspline.geometry import Limits
from arcspline.geometry.curves.segments import Subpath
from arcspline.geometry.offset import OffsetOptions, elements_of, offset_path
from tests.geometry.offset.checks import measure
from tests.support.corpus import corpus_files

TEXT = "domoszlai__juicy-gcode__testtext.svg"


@pytest.fixture(scope="module")
def text_spline():  # type: ignore[no-untyped-def]
    (path,) = [p for p in corpus_files("svg") if p.name == TEXT]
    drawing = read_svg(path.read_text())
    return approximate_drawing(drawing, DrawingOptions(0.01), Limits(max_segments=10**6)).spline


@pytest.mark.parametrize("side", ["inside", "outside"])
@pytest.mark.parametrize("d", [0.05, 0.3, 1.0])
def test_text_outlines_never_come_nearer_than_the_tool(text_spline, side: str, d: float) -> None:  # type: ignore[no-untyped-def]
    out = offset_path(text_spline, OffsetOptions(d, side), Limits(max_segments=10**6))  # type: ignore[arg-type]
    assert out.spline is not None
    assert set(out.origin) == set(range(len(text_spline.subpaths)))  # no glyph run vanishes
    assert out.source_max_deviation >= text_spline.stats.max_deviation
    for k, source in enumerate(text_spline.subpaths):
        contour = elements_of(source.spline)
        pairs = zip(out.spline.subpaths, out.origin, strict=True)
        mine = [Subpath(elements_of(s.spline), s.closed) for s, o in pairs if o == k]
        report = measure([contour], mine, d, side)  # type: ignore[arg-type]
        # the tool path keeps the tool off the fitted outline, up to the loops cut out of it
        assert report.closest_mm >= d - out.source_max_deviation - 1e-9, report.describe()
