"""The SVG reader on whole documents: one small file per trap (tests/data/svg/, coordinates
computed by hand in the comments), curves checked by sampling against an independent formula,
errors named by element, and every file of the shared corpus read with exact accounting.
Parsing, shapes, styles and attributes have their own test modules."""

from __future__ import annotations

import math

import numpy as np
import pytest

from arcspline.drawings.model import DocumentError
from arcspline.drawings.svg import read_svg
from arcspline.geometry.curves.segments import CircularArc, EllipticalArc
from tests.drawings.svg_support import SVG_OPEN, assert_checked, ends, read, sample
from tests.support.corpus import corpus_files

# ---- units and viewports ------------------------------------------------------------------------


def test_percent_size_with_view_box_takes_the_view_box_in_px() -> None:
    # viewBox 10 20 96 48 in px: 25.4 x 12.7 mm; (10,20) is the top-left -> (0, 12.7) y up
    drawing = read("percent_size_viewbox.svg")
    assert drawing.units == "px"
    assert ends(drawing) == [((0.0, 12.7), (25.4, 0.0))]
    (note,) = drawing.warnings
    assert note.occurrences == 0
    assert "viewBox's size is taken in px" in note.reason


def test_mm_size_meet_centres_the_view_box() -> None:
    # 100 x 50 mm, viewBox 10 x 10, meet: s = min(10, 5) = 5, x slack 100 - 50 = 50 -> +25.
    # (0,0) -> (25, 0) y down -> (25, 50) y up; (10,10) -> (75, 50) -> (75, 0).
    drawing = read("size_mm_meet.svg")
    assert drawing.units == "mm"
    assert ends(drawing) == [((25.0, 50.0), (75.0, 0.0))]


def test_inch_size_slice_aligns_the_max_edges() -> None:
    # 2 x 1 in = 50.8 x 25.4 mm, viewBox 1 x 1, slice: s = 50.8; y slack 25.4 - 50.8 = -25.4
    # (YMax: all of it). (0,0) -> (0, -25.4) -> y up 25.4 + 25.4 = 50.8; (1,1) -> (50.8, 0).
    drawing = read("size_in_slice.svg")
    assert drawing.units == "in"
    assert ends(drawing) == [((0.0, 50.8), (50.8, 0.0))]


def test_point_size_with_none_scales_each_axis() -> None:
    # 72 pt x 36 pt = 25.4 x 12.7 mm; viewBox 10 x 10, none: sx = 2.54, sy = 1.27 mm per unit.
    # (5,5) -> (12.7, 6.35) y down -> (12.7, 12.7 - 6.35 = 6.35) y up.
    drawing = read("size_pt_none.svg")
    assert drawing.units == "pt"
    assert ends(drawing) == [((0.0, 12.7), (25.4, 0.0)), ((12.7, 6.35), (25.4, 6.35))]


def test_the_units_override_makes_a_user_unit_that_unit() -> None:
    # viewBox 0 0 10 10, override cm: (0,0) -> (0, 100) mm, (10,10) -> (100, 0) mm.
    drawing = read("size_mm_meet.svg", units="cm")
    assert drawing.units == "cm"
    assert ends(drawing) == [((0.0, 100.0), (100.0, 0.0))]
    with pytest.raises(DocumentError) as caught:
        read("size_mm_meet.svg", units="cubit")
    assert caught.value.where == "units"


def test_nested_svg_has_its_own_viewport() -> None:
    # inner viewBox 4 x 2 into 40 x 20 at (10, 20): scale 10. (0,0) -> (10,20) -> mm (10, 80);
    # (4,2) -> (50, 40) -> mm (50, 60).
    assert ends(read("nested_svg.svg")) == [((10.0, 80.0), (50.0, 60.0))]


def test_use_of_a_symbol_and_of_a_path_and_a_dangling_use() -> None:
    # symbol viewBox 10 x 10 into 20 x 20 at (20, 30): (0,0) -> (20,30) -> mm (20, 70),
    # (10,0) -> (40, 30) -> (40, 70), (10,10) -> (40, 50), (0,10) -> (20, 50).
    # path M0 0 L5 0 used at (1, 2): (1, 98) to (6, 98). Defs are not drawn by themselves.
    drawing = read("use_symbol.svg")
    assert [e.source for e in drawing.elements] == ["rect#unit", "path#stroke"]
    assert ends(drawing) == [
        ((20.0, 70.0), (40.0, 70.0), (40.0, 70.0), (40.0, 50.0),
         (40.0, 50.0), (20.0, 50.0), (20.0, 50.0), (20.0, 70.0)),
        ((1.0, 98.0), (6.0, 98.0)),
    ]  # fmt: skip
    assert drawing.elements_in == 3
    (warning,) = drawing.warnings
    assert warning.element == "use#dangling"
    assert "not found" in warning.reason


def test_a_used_symbol_hidden_by_display_none_is_counted() -> None:
    # Before: the symbol's category hid its children from the count: nothing drawn, nothing
    # said. Its two shapes are drawable and not drawn: 2 in, 2 in one warning.
    drawing = read_svg(
        SVG_OPEN + '<symbol id="s" style="display:none"><rect width="1" height="1"/>'
        '<line x2="1"/></symbol><use href="#s"/></svg>'
    )
    assert drawing.elements == ()
    assert drawing.elements_in == 2
    assert [(w.element, w.occurrences) for w in drawing.warnings] == [("symbol#s", 2)]


def test_a_used_symbol_of_zero_size_is_counted() -> None:
    drawing = read_svg(
        SVG_OPEN + '<symbol id="s"><rect width="1" height="1"/></symbol>'
        '<use href="#s" width="0"/></svg>'
    )
    assert drawing.elements_in == 1
    (warning,) = drawing.warnings
    assert (warning.element, warning.occurrences) == ("symbol#s", 1)
    assert "zero size" in warning.reason


def test_a_used_symbol_passes_on_its_visibility() -> None:
    # Before: the symbol's own visibility was not read and its rect was drawn. A child that
    # says visible is drawn beneath it (visibility is inherited, and may be overridden).
    drawing = read_svg(
        SVG_OPEN + '<symbol id="s" visibility="hidden" clip-path="url(#c)">'
        '<rect id="hid" width="1" height="1"/><line id="seen" x2="1" visibility="visible"/>'
        '</symbol><use href="#s"/></svg>'
    )
    assert [e.source for e in drawing.elements] == ["line#seen"]
    assert drawing.elements_in == 2
    assert {(w.element, w.occurrences) for w in drawing.warnings} == {
        ("symbol#s", 0),  # the clip path's note
        ("rect#hid", 1),
    }


def test_a_hidden_switch_counts_only_the_alternative_it_would_draw() -> None:
    # Illustrator's pattern: a foreignObject for itself, then the drawing. Visible, the
    # switch draws the g (1 rect); hidden, it is that rect that is not drawn, not the
    # foreignObject as well (before: 2).
    body = (
        '<foreignObject requiredExtensions="http://ns.adobe.com/AdobeIllustrator/10.0/"/>'
        '<g><rect width="1" height="1"/></g></switch></svg>'
    )
    shown = read_svg(SVG_OPEN + "<switch>" + body)
    hidden = read_svg(SVG_OPEN + '<switch id="w" style="display:none">' + body)
    assert (len(shown.elements), shown.elements_in) == (1, 1)
    assert hidden.elements_in == 1
    assert [(w.element, w.occurrences) for w in hidden.warnings] == [("switch#w", 1)]


def test_an_auto_size_is_the_whole_viewport() -> None:
    # Before: width="auto" (SVG 2: 100 % on the outermost svg) was refused as not a length.
    # As with 100 %: the viewBox 0 0 96 48 is taken in px, 25.4 x 12.7 mm.
    drawing = read_svg(
        '<svg xmlns="http://www.w3.org/2000/svg" width="auto" height="auto" '
        'viewBox="0 0 96 48"><line x2="96" y2="48"/></svg>'
    )
    assert ends(drawing) == [((0.0, 12.7), (25.4, 0.0))]


# ---- transforms and exact curves ----------------------------------------------------------------


def test_rotate_about_a_point() -> None:
    # rotate(90 10 10): (20,10) -> (10,20), (30,10) -> (10,30); y up in 100: (10,80), (10,70)
    assert ends(read("rotate_about_point.svg")) == [((10.0, 80.0), (10.0, 70.0))]


def test_skewed_ellipse_is_exact() -> None:
    drawing = read("skewed_ellipse.svg")
    (element,) = drawing.elements
    segments = list(element.subpath.segments)
    assert element.subpath.closed
    assert [type(s) for s in segments] == [EllipticalArc, EllipticalArc]
    # (20, 0) -> skewX(30): x + tan30·0 = 20 -> +50: (70, 50) -> y up (70, 50)
    assert segments[0].start == pytest.approx((70.0, 50.0), abs=1e-12)
    assert segments[1].end == segments[0].start
    # The map user -> mm is p -> (50 + x + tan30·y, 100 - (50 + y)); undo it by hand and every
    # sampled point must lie on (x/20)² + (y/10)² = 1.
    for segment in segments:
        pts = sample(segment)  # type: ignore[arg-type]
        y = 50.0 - pts[:, 1]
        x = pts[:, 0] - 50.0 - math.tan(math.radians(30.0)) * y
        assert np.abs((x / 20.0) ** 2 + (y / 10.0) ** 2 - 1.0).max() < 1e-12
    assert_checked(segments)


def test_a_mirrored_arc_turns_the_other_way() -> None:
    # M10 0 A10 10 0 0 1 0 10 turns +90° in SVG's numbers (y down). Mirrored by scale(-1 1)
    # and moved by (50, 50): (-10,0)->(0,10) about (0,0) -> (40,50)->(50,60) y down ->
    # (40,50)->(50,40) y up, about (50,50): from 180° to 270°, anticlockwise: +90°.
    # The same arc unmirrored: (60,50)->(50,40), from 0° to -90°: clockwise, -90°.
    mirrored, plain = (e.subpath.segments[0] for e in read("mirrored_arc.svg").elements)
    assert isinstance(mirrored, CircularArc)
    assert isinstance(plain, CircularArc)
    assert (mirrored.start, mirrored.end, mirrored.center) == ((40, 50), (50, 40), (50, 50))
    assert mirrored.sweep_rad == pytest.approx(math.pi / 2)
    assert (plain.start, plain.end) == ((60, 50), (50, 40))
    assert plain.sweep_rad == pytest.approx(-math.pi / 2)
    # the mirrored arc's middle: SVG (7.07, 7.07) -> (-7.07, 7.07) -> (42.93, 57.07) -> y up
    middle = sample(mirrored, 3)[1]
    assert middle == pytest.approx((50 - 50**0.5, 50 - 50**0.5), abs=1e-12)


# ---- visibility and warnings --------------------------------------------------------------------


def test_display_none_and_hidden_are_counted_not_drawn() -> None:
    # drawn: line#shown (visible inside a hidden group); warned: the 2 shapes of g#layer,
    # rect#off, line#ghost: 1 + 2 + 1 + 1 = 5 in.
    drawing = read("display_none.svg")
    assert [e.source for e in drawing.elements] == ["line#shown"]
    assert drawing.elements_in == 5
    assert {(w.element, w.occurrences) for w in drawing.warnings} == {
        ("g#layer", 2), ("rect#off", 1), ("line#ghost", 1)
    }  # fmt: skip


def test_text_and_images_are_warned_with_their_count() -> None:
    drawing = read("text_warning.svg")
    assert drawing.elements_in == 4
    assert {(w.element, w.occurrences) for w in drawing.warnings} == {
        ("text (line 2)", 2), ("image (line 4)", 1)
    }  # fmt: skip


def test_a_singular_transform_is_warned() -> None:
    drawing = read_svg(
        '<svg xmlns="http://www.w3.org/2000/svg"><g transform="scale(0 1)">'
        '<line id="flat" x2="1" y2="1"/></g><line x2="1"/></svg>'
    )
    assert len(drawing.elements) == 1
    assert drawing.elements_in == 2
    (warning,) = drawing.warnings[1:]  # the first is the note on the missing size
    assert warning.element == "line#flat"
    assert "collapses the plane" in warning.reason


# ---- hostile and broken documents ---------------------------------------------------------------


def test_expanding_uses_counts_against_the_element_limit() -> None:
    # each level uses the one below ten times: 10^6 lines from a few hundred bytes
    levels = ['<g id="l0"><line x2="1"/></g>']
    for i in range(1, 7):
        levels.append(f'<g id="l{i}">' + f'<use href="#l{i - 1}"/>' * 10 + "</g>")
    text = '<svg xmlns="http://www.w3.org/2000/svg"><defs>' + "".join(levels) + "</defs>"
    text += '<use href="#l6"/></svg>'
    with pytest.raises(DocumentError, match="once uses are expanded"):
        read_svg(text)


def test_a_use_cycle_is_refused() -> None:
    text = (
        '<svg xmlns="http://www.w3.org/2000/svg"><g id="a"><line x2="1"/>'
        '<use id="loop" href="#a"/></g></svg>'
    )
    with pytest.raises(DocumentError) as caught:
        read_svg(text)
    assert caught.value.where == "use#loop"
    assert "cycle" in caught.value.reason


@pytest.mark.parametrize(
    ("text", "where", "words"),
    [
        ("<svg><g>", "document", "line 1, column 9"),
        ("<svg/>\n<svg/>", "document", "line 2"),
        ("<svg><path id='p' d='M 0 0 L 1 X'/></svg>", "path#p", "at character 10"),
        ("<svg>\n\n<path d='M 0 0 Q 1'/></svg>", "path (line 3)", "at character"),
        ("<svg><rect transform='scale(1,)' width='1' height='1'/></svg>", "rect (line 1)",
         "at character 8"),
        ("<svg><circle id='c' r='-1'/></svg>", "circle#c", "r must be >= 0"),
        ("<svg><polygon id='p' points='0 0 1'/></svg>", "polygon#p", "odd count"),
        ("<svg><rect id='r' width='1em' height='1'/></svg>", "rect#r", "font-relative"),
        ("<svg viewBox='0 0 0 1'/>", "svg (line 1)", "must be > 0"),
        ("<html/>", "document", "not an svg"),
    ],
)  # fmt: skip
def test_bad_documents_name_the_element(text: str, where: str, words: str) -> None:
    with pytest.raises(DocumentError) as caught:
        read_svg(text)
    assert caught.value.where == where
    assert words in caught.value.reason


# ---- the shared corpus --------------------------------------------------------------------------


def test_every_corpus_file_reads_with_exact_accounting() -> None:
    files = corpus_files("svg")
    assert len(files) >= 15
    drawn, refused = 0, []
    for path in files:
        try:
            drawing = read_svg(path.read_bytes())
        except DocumentError as error:  # a refusal by name is allowed (none happens today)
            refused.append((path.name, error.where))
            continue
        drawn += len(drawing.elements)
        assert drawing.elements_in == len(drawing.elements) + drawing.skipped, path.name
        for element in drawing.elements:
            segments = list(element.subpath.segments)
            assert segments, (path.name, element.source)
            assert_checked(segments)
            if element.subpath.closed:
                assert segments[-1].end == segments[0].start, (path.name, element.source)
    assert all(where for _, where in refused), refused
    assert drawn >= 4000  # 4 095 subpaths today
