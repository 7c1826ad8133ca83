"""The SVG reader on hostile input: whatever the bytes, it gives a drawing with exact
accounting and finite numbers, or a DocumentError, never an error of another kind
(docs/drawings.md §1). Undecodable encodings, numbers that overflow once placed, and
reference bombs are each pinned by a hand-made document; random bytes and random documents
from a grammar of tags, attributes and extreme numbers check the rule at large."""

from __future__ import annotations

import math
import time

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from arcspline.drawings.model import DocumentError, DocumentLimits, Drawing
from arcspline.drawings.svg import read_svg

SVG_NS = "http://www.w3.org/2000/svg"
OPEN = f'<svg xmlns="{SVG_NS}" width="10mm" height="10mm" viewBox="0 0 10 10">'
NON_FINITE = "has a non-finite number"


def assert_sound(drawing: Drawing) -> None:
    """Exact accounting, and every number of every segment finite (checked here, apart from
    the reader's own check)."""
    assert drawing.elements_in == len(drawing.elements) + drawing.skipped
    for element in drawing.elements:
        for segment in element.subpath.segments:
            for value in segment:
                numbers = value if isinstance(value, tuple) else (value,)
                assert all(math.isfinite(v) for v in numbers), (element.source, segment)


# ---- encodings ----------------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("encoding", "why"),
    [
        ("x-bogus", "unknown encoding"),
        ("utf-7", "multi-byte"),
        ("shift_jis", "multi-byte"),
        ("utf-32", "multi-byte"),
        ("rot13", "not a text encoding"),
        ("idna", "idna"),
        ("punycode", "can't decode"),
    ],
)
def test_an_encoding_the_parser_cannot_decode_is_refused_by_name(encoding: str, why: str) -> None:
    # Before: LookupError, ValueError or UnicodeError escaped (a 500 at the API).
    document = f'<?xml version="1.0" encoding="{encoding}"?>{OPEN}<circle r="1"/></svg>'
    for prefix in (b"", b"\xef\xbb\xbf"):
        with pytest.raises(DocumentError) as caught:
            read_svg(prefix + document.encode("ascii"))
        assert caught.value.where == "document"
        assert f"the encoding {encoding!r} cannot be read" in caught.value.reason
        assert why in caught.value.reason


@pytest.mark.parametrize("encoding", ["utf-8", "utf-16", "iso-8859-1", "cp1252", "us-ascii"])
def test_encodings_the_parser_decodes_still_read(encoding: str) -> None:
    document = f'<?xml version="1.0" encoding="{encoding}"?>{OPEN}<line x2="5"/></svg>'
    drawing = read_svg(document.encode(encoding))
    assert [e.subpath.segments[0].end for e in drawing.elements] == [(5.0, 10.0)]


# ---- numbers that overflow once placed ----------------------------------------------------------


@pytest.mark.parametrize(
    "shape",
    [
        # scale(1e308) times the viewBox's 1 mm per unit is finite; the point 10 overflows.
        '<line transform="scale(1e308)" x2="10"/>',
        # Each of the two scales is finite; their product is not.
        '<g transform="scale(1e200)"><circle transform="scale(1e200)" r="1"/></g>',
        # The rectangle's far side, x + width = 2e308, overflows before any map.
        '<rect x="1e308" width="1e308" height="1"/>',
        # A finite ellipse whose right end cx + rx overflows.
        '<ellipse cx="1.5e308" rx="1e308" ry="1"/>',
        # A half turn about (1e308, 0): the centre's image is moved by 2e308, which overflows.
        '<path transform="rotate(180 1e308 0)" d="M 0 0 L 1 1"/>',
        # inf · 0 = NaN in the composed map of a matrix with an overflowing entry.
        '<g transform="matrix(1e308 0 0 1 0 0)"><line transform="scale(10) rotate(90)" '
        'x2="1"/></g>',
    ],
)
def test_an_element_whose_numbers_overflow_is_warned_and_counted(shape: str) -> None:
    drawing = read_svg(f'{OPEN}{shape}<line id="kept" x1="1" x2="2"/></svg>')
    assert_sound(drawing)
    assert [e.source for e in drawing.elements] == ["line#kept"]
    (warning,) = drawing.warnings
    assert NON_FINITE in warning.reason
    assert warning.occurrences == 1
    assert drawing.elements_in == 2


def test_large_but_finite_coordinates_are_drawn_exactly() -> None:
    # 1e200 units at 1 mm per unit, y flipped about the 10 mm top: no overflow, drawn.
    drawing = read_svg(f'{OPEN}<line x1="1e200" x2="-1e200" y2="1e200"/></svg>')
    assert_sound(drawing)
    (element,) = drawing.elements
    assert element.subpath.segments[0] == ((1e200, 10.0), (-1e200, 10.0 - 1e200))


def test_a_document_frame_that_overflows_is_refused() -> None:
    with pytest.raises(DocumentError, match="scale that is not finite"):
        read_svg(
            f'<svg xmlns="{SVG_NS}" width="1e308mm" height="1" viewBox="0 0 1e-10 1" '
            'preserveAspectRatio="none"/>'
        )


@pytest.mark.parametrize(
    "shape",
    [
        '<circle r="1e400"/>',
        '<path d="M 0 0 L 1e999 1"/>',
        '<line transform="scale(1e400)" x2="1"/>',
        '<polygon points="0 0 1 1 1e309 0"/>',
    ],
)
def test_a_number_written_beyond_the_float_range_is_an_error_naming_the_element(
    shape: str,
) -> None:
    # Not a number SVG can mean (as a syntax error): refused, naming the element.
    with pytest.raises(DocumentError) as caught:
        read_svg(f"{OPEN}{shape}</svg>")
    assert caught.value.where.split(" ")[0] in ("circle", "path", "line", "polygon")
    assert "finite" in caught.value.reason


# ---- reference bombs -----------------------------------------------------------------------------


def bomb(segments: int, uses: int) -> str:
    """One path of ``segments`` lines in defs, drawn by ``uses`` uses."""
    d = "M0 0" + " l1 1 1 -1" * (segments // 2)
    instances = '<use href="#p"/>' * uses
    return f'{OPEN}<defs><path id="p" d="{d}"/></defs>{instances}</svg>'


def test_a_reference_bomb_is_refused_before_it_is_drawn() -> None:
    # Before: 20 000 segments × 400 uses = 8 M segments drawn (108 s, 2.5 GB). Now the 11th
    # use crosses 200 000 and is refused at once.
    started = time.perf_counter()
    with pytest.raises(DocumentError) as caught:
        read_svg(bomb(20_000, 400), limits=DocumentLimits(max_segments=200_000))
    assert time.perf_counter() - started < 10.0
    assert caught.value.where == "document"
    assert "more than 200000 segments" in caught.value.reason
    assert "path#p" in caught.value.reason
    # The default (the reproducer's bomb, 8 M segments, crosses it at its 51st use).
    assert DocumentLimits().max_segments == 1_000_000


def test_a_drawing_at_the_segment_limit_reads() -> None:
    # 2 000 segments × 10 uses = 20 000 exactly: read, each instance its own element.
    drawing = read_svg(bomb(2_000, 10), limits=DocumentLimits(max_segments=20_000))
    assert_sound(drawing)
    assert len(drawing.elements) == 10
    assert sum(len(e.subpath.segments) for e in drawing.elements) == 20_000
    with pytest.raises(DocumentError, match="more than 19999 segments"):
        read_svg(bomb(2_000, 10), limits=DocumentLimits(max_segments=19_999))


def test_segments_outside_uses_count_too() -> None:
    # A polygon of 3 sides and a rect of 4: 7 segments, over a limit of 6.
    document = f'{OPEN}<polygon points="0 0 1 0 0 1"/><rect width="1" height="1"/></svg>'
    assert len(read_svg(document, limits=DocumentLimits(max_segments=7)).elements) == 2
    with pytest.raises(DocumentError, match="more than 6 segments"):
        read_svg(document, limits=DocumentLimits(max_segments=6))


def test_a_used_shape_is_drawn_the_same_in_each_instance() -> None:
    # The path is read once for both uses; each instance is moved by its own x.
    document = (
        f'{OPEN}<defs><path id="p" d="M 0 0 L 1 0"/></defs>'
        '<use href="#p" x="2"/><use href="#p" x="5"/></svg>'
    )
    drawing = read_svg(document)
    assert [e.subpath.segments[0][:2] for e in drawing.elements] == [
        ((2.0, 10.0), (3.0, 10.0)),
        ((5.0, 10.0), (6.0, 10.0)),
    ]


# ---- anything at all -----------------------------------------------------------------------------

ORDINARY = st.sampled_from(["0", "1", "-1", "0.5", "7", "3.25", "90", "45", "-30"])
EXTREME = st.sampled_from(
    ["1e-320", "5e-324", "1e-300", "1e154", "1e200", "-1e200", "1e308", "-1e308",
     "1.7976931348623157e308", "1e400", "-1e999"]
)  # fmt: skip
#: Mostly ordinary numbers, so that documents get past their frame to the extreme ones.
NUMBERS = st.one_of(ORDINARY, ORDINARY, ORDINARY, EXTREME)
LENGTHS = st.tuples(NUMBERS, st.sampled_from(["", "", "mm", "in", "%", "px"])).map("".join)
TRANSFORMS = st.lists(
    st.one_of(
        st.builds("scale({})".format, NUMBERS),
        st.builds("translate({} {})".format, NUMBERS, NUMBERS),
        st.builds("rotate({} {} {})".format, NUMBERS, NUMBERS, NUMBERS),
        st.builds("skewX({})".format, NUMBERS),
        st.builds("matrix({} {} {} {} {} {})".format, *[NUMBERS] * 6),
    ),
    max_size=3,
).map(" ".join)
PATHS = st.lists(
    st.one_of(
        st.builds("M {} {}".format, NUMBERS, NUMBERS),
        st.builds("l {} {}".format, NUMBERS, NUMBERS),
        st.builds("C {} {} {} {} {} {}".format, *[NUMBERS] * 6),
        st.builds("q {} {} {} {}".format, *[NUMBERS] * 4),
        st.builds(
            "A {} {} {} {} {} {} {}".format,
            NUMBERS,
            NUMBERS,
            NUMBERS,
            st.sampled_from("01"),
            st.sampled_from("01"),
            NUMBERS,
            NUMBERS,
        ),
        st.just("Z"),
    ),
    min_size=1,
    max_size=5,
).map(lambda commands: "M 0 0 " + " ".join(commands))
ATTRIBUTES = st.dictionaries(
    st.sampled_from(["x", "y", "width", "height", "r", "rx", "ry", "cx", "cy", "x1", "y1", "x2",
                     "y2"]),
    LENGTHS,
    max_size=5,
)  # fmt: skip
EXTRAS = st.fixed_dictionaries(
    {},
    optional={
        "transform": TRANSFORMS,
        "d": PATHS,
        "points": st.lists(NUMBERS, max_size=8).map(" ".join),
        "viewBox": st.lists(NUMBERS, min_size=4, max_size=4).map(" ".join),
        "href": st.sampled_from(["#a", "#b", "#missing"]),
        "id": st.sampled_from(["a", "b"]),
        "style": st.sampled_from(["display:none", "visibility:hidden", "clip-path:url(#a)"]),
    },
)
GEOMETRY = {
    "rect": ("x", "y", "width", "height"),
    "circle": ("cx", "cy", "r"),
    "ellipse": ("cx", "cy", "rx", "ry"),
    "line": ("x1", "y1", "x2", "y2"),
    "use": ("x", "y"),
}
TAGS = st.sampled_from(
    ["g", "path", "rect", "circle", "ellipse", "line", "polyline", "polygon", "use", "svg",
     "symbol", "defs", "switch", "text"]
)  # fmt: skip


@st.composite
def elements(draw: st.DrawFn, depth: int = 0) -> str:
    tag = draw(TAGS)
    # A shape mostly gets the attributes that make it drawn; any element may get any other.
    geometry = {name: draw(LENGTHS) for name in GEOMETRY.get(tag, ()) if draw(st.integers(0, 4))}
    if tag == "path" and draw(st.integers(0, 4)):
        geometry["d"] = draw(PATHS)
    if tag in ("polyline", "polygon") and draw(st.integers(0, 4)):
        geometry["points"] = " ".join(draw(st.lists(NUMBERS, min_size=4, max_size=8)))
    attributes = {**geometry, **draw(ATTRIBUTES), **draw(EXTRAS)}
    text = " ".join(f'{name}="{value}"' for name, value in attributes.items())
    children = draw(st.lists(elements(depth + 1), max_size=3)) if depth < 3 else []
    return f"<{tag} {text}>{''.join(children)}</{tag}>"


@st.composite
def documents(draw: st.DrawFn) -> str:
    sizes = st.one_of(st.sampled_from(["10mm", "2in", "100"]), LENGTHS)
    root = draw(st.dictionaries(st.sampled_from(["width", "height"]), sizes, max_size=2))
    if draw(st.booleans()):
        box = st.one_of(
            st.just("0 0 10 10"), st.lists(NUMBERS, min_size=4, max_size=4).map(" ".join)
        )
        root["viewBox"] = draw(box)
    text = " ".join(f'{name}="{value}"' for name, value in root.items())
    body = "".join(draw(st.lists(elements(), max_size=4)))
    return f'<svg xmlns="{SVG_NS}" {text}>{body}</svg>'


def read_or_refuse(document: bytes | str) -> None:
    """The reader's whole contract for any input: a sound drawing or a DocumentError."""
    try:
        drawing = read_svg(document, limits=DocumentLimits(max_segments=10_000))
    except DocumentError as error:
        refused = error
    else:
        assert_sound(drawing)
        return
    assert refused.where
    assert refused.reason


FUZZ = settings(max_examples=200, deadline=None, suppress_health_check=[HealthCheck.too_slow])


@FUZZ
@given(documents())
def test_any_document_of_the_grammar_reads_soundly_or_is_refused(document: str) -> None:
    read_or_refuse(document)


@FUZZ
@given(
    st.one_of(
        st.binary(max_size=200),
        st.tuples(
            st.sampled_from([b"", b"\xef\xbb\xbf", b"\xff\xfe", b"\xfe\xff", b"\x00\x00\xfe\xff"]),
            st.sampled_from([b"", b'<?xml version="1.0"?>', b'<?xml version="1.0" encoding="'])
            | st.builds(
                lambda e: b'<?xml version="1.0" encoding="' + e + b'"?>',
                st.sampled_from(
                    [
                        b"utf-8",
                        b"utf-16",
                        b"latin-1",
                        b"utf-7",
                        b"gb2312",
                        b"hex",
                        b"x",
                        b"mac-roman",
                        b"koi8-r",
                        b"undefined",
                        b"cp037",
                    ]
                ),
            ),
            documents().map(lambda text: text.encode("utf-8")),
            st.binary(max_size=8),
        ).map(b"".join),
    )
)
def test_any_bytes_read_soundly_or_are_refused(document: bytes) -> None:
    read_or_refuse(document)
