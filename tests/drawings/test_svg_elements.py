"""What the reader does with each kind of element: the counts of drawable elements under a
node (for display:none and zero-size viewports) and the child a switch draws."""

from __future__ import annotations

from arcspline.drawings.model import DocumentLimits
from arcspline.drawings.svg_elements import (
    descendants,
    drawable_count,
    switch_choice,
    unsupported_reason,
)
from arcspline.drawings.svg_parse import Node, parse_svg


def _tree(body: str) -> Node:
    return parse_svg(f'<svg xmlns="http://www.w3.org/2000/svg">{body}</svg>', DocumentLimits())


def test_drawable_count() -> None:
    # rect, text, use, line in a, unknown "blob": 5. Not counted: defs' circle, title, the
    # foreign element and what is in it, the switch's alternative after its first choice.
    root = _tree(
        '<rect/><text>t</text><use href="#x"/><a><line/></a><blob/>'
        '<defs><circle/></defs><title/><f:x xmlns:f="urn:f"><rect/></f:x>'
        '<switch><path systemLanguage="fr"/><g><path/></g><path/></switch>'
    )
    assert drawable_count(root) == 5 + 1
    defs = root.children[5]
    assert drawable_count(defs) == 0
    assert drawable_count(defs, instanced=True) == 1  # a used symbol's contents count


def test_a_switch_draws_its_first_unconditional_svg_child() -> None:
    switch = _tree(
        '<switch><x:a xmlns:x="urn:x"/><foreignObject requiredExtensions="e"/>'
        '<g requiredFeatures=""/><g id="this"/><g/></switch>'
    ).children[0]
    assert [n.attrib.get("id") for n in switch_choice(switch)] == ["this"]
    assert switch_choice(_tree('<switch><g systemLanguage="en"/></switch>').children[0]) == []


def test_unsupported_reason_and_descendants_in_document_order() -> None:
    root = _tree('<g id="1"><text id="2"/></g><video id="3"/><mesh2 id="4"/>')
    assert [n.attrib.get("id") for n in descendants(root)] == [None, "1", "2", "3", "4"]
    g, video, unknown = root.children
    assert unsupported_reason(g) is None
    assert unsupported_reason(video) == "videos are not drawn"
    assert unsupported_reason(unknown) == "unknown element mesh2: not drawn"
