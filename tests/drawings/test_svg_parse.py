"""The XML layer of the SVG reader: hostile documents refused by name (entities, size,
element count, depth), a plain DOCTYPE allowed, and the tree it builds (tags, namespaces,
lines)."""

from __future__ import annotations

import pytest

from arcspline.drawings.model import DocumentError, DocumentLimits
from arcspline.drawings.svg import read_svg
from arcspline.drawings.svg_parse import parse_svg
from tests.drawings.svg_support import DATA, read

# ---- hostile documents --------------------------------------------------------------------------


@pytest.mark.parametrize("name", ["billion_laughs.svg", "external_entity.svg"])
def test_entities_are_refused(name: str) -> None:
    with pytest.raises(DocumentError) as caught:
        read(name)
    assert caught.value.where == "document"
    assert "entities are not allowed" in caught.value.reason


def test_a_plain_doctype_is_allowed() -> None:
    drawing = read_svg(
        '<?xml version="1.0"?>\n<!DOCTYPE svg PUBLIC "-//W3C//DTD SVG 1.1//EN" '
        '"http://www.w3.org/Graphics/SVG/1.1/DTD/svg11.dtd">\n'
        '<svg xmlns="http://www.w3.org/2000/svg"><line x2="1"/></svg>'
    )
    assert len(drawing.elements) == 1


def test_deep_nesting_is_refused() -> None:
    with pytest.raises(DocumentError, match="nested deeper than 64"):
        read("deep_nesting.svg")


def test_size_and_element_limits() -> None:
    text = '<svg xmlns="http://www.w3.org/2000/svg">' + "<g/>" * 50 + "</svg>"
    with pytest.raises(DocumentError, match="larger than 100 bytes"):
        read_svg(text, limits=DocumentLimits(max_bytes=100))
    with pytest.raises(DocumentError, match="more than 20 elements"):
        read_svg(text, limits=DocumentLimits(max_elements=20))


def test_a_text_document_with_a_lone_surrogate_is_refused_by_name() -> None:
    # Before: the parser's UnicodeEncodeError escaped, an error of another kind. The svg tag
    # is 40 characters, then "\n<g>": the surrogate is character 44 (0-based), on line 2.
    with pytest.raises(DocumentError) as caught:
        read_svg('<svg xmlns="http://www.w3.org/2000/svg">\n<g>\ud800</g></svg>')
    assert caught.value.where == "document"
    assert "lone surrogate at line 2 (character 44)" in caught.value.reason


# ---- the tree ------------------------------------------------------------------------------


def test_the_tree_keeps_tags_namespaces_attributes_and_lines() -> None:
    text = (
        '<svg xmlns="http://www.w3.org/2000/svg" xmlns:s="urn:x"\n'
        ' xmlns:xlink="http://www.w3.org/1999/xlink">\n'
        '<g id="a">\n<use xlink:href="#a"/></g>text\n<s:named/></svg>'
    )
    for document in (text, text.encode()):
        root = parse_svg(document, DocumentLimits())
        g, named = root.children
        (use,) = g.children
        assert (root.tag, root.svg, root.line) == ("svg", True, 1)
        assert (g.source, use.source, use.line) == ("g#a", "use (line 4)", 4)
        assert use.attrib == {"{http://www.w3.org/1999/xlink}href": "#a"}
        assert (named.tag, named.svg, named.name, named.line) == (
            "named",
            False,
            "a foreign named",
            5,
        )


def test_the_limits_are_exact() -> None:
    # 1 svg + 3 g nested: 4 elements, depth 4 (the svg at 1); each limit at its value passes.
    text = "<svg><g><g><g/></g></g></svg>"
    parse_svg(text, DocumentLimits(max_bytes=len(text), max_elements=4, max_depth=4))
    for limits, words in (
        (DocumentLimits(max_bytes=len(text) - 1), "larger than"),
        (DocumentLimits(max_elements=3), "more than 3 elements"),
        (DocumentLimits(max_depth=3), "nested deeper than 3"),
    ):
        with pytest.raises(DocumentError, match=words):
            parse_svg(text, limits)
    # A text document is measured in UTF-8: "é" is two bytes.
    wide = "<svg id='é'/>"
    with pytest.raises(DocumentError, match="larger than"):
        parse_svg(wide, DocumentLimits(max_bytes=len(wide)))


def test_a_document_larger_than_a_chunk_parses_whole() -> None:
    # 2 x 65 536 bytes of attribute: the element spans three chunks of the feed.
    text = f'<svg><g id="{"x" * (1 << 17)}"/><path d="M0 0"/></svg>'
    root = parse_svg(text.encode(), DocumentLimits())
    assert [c.tag for c in root.children] == ["g", "path"]
    assert len(root.children[0].attrib["id"]) == 1 << 17


def test_data_files_parse_to_their_root() -> None:
    root = parse_svg((DATA / "nested_svg.svg").read_bytes(), DocumentLimits())
    assert root.tag == "svg"
    assert read("nested_svg.svg").elements_in == 1
