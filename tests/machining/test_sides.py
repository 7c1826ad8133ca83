"""Cut sides by nesting depth; travel sense by milling direction."""

from __future__ import annotations

import pytest

from arcspline.geometry import GeometryError
from arcspline.machining.sides import cut_side, runs_clockwise, tool_on_left


@pytest.mark.parametrize(
    ("depth", "side"), [(0, "outside"), (1, "inside"), (2, "outside"), (3, "inside")]
)
def test_auto_alternates_with_depth(depth: int, side: str) -> None:
    assert cut_side("auto", True, depth, 0) == side


def test_open_contours_are_cut_on_their_line_or_refused_a_side() -> None:
    assert cut_side("auto", False, 1, 3) == "on"
    assert cut_side("on", False, 0, 3) == "on"
    with pytest.raises(GeometryError) as caught:
        cut_side("outside", False, 0, 3)
    assert caught.value.field == "path.subpaths[3]"


def test_climb_with_m3_keeps_the_tool_left() -> None:
    assert tool_on_left("climb")
    assert not tool_on_left("conventional")
    assert runs_clockwise("outside", "climb")
    assert not runs_clockwise("inside", "climb")
    assert not runs_clockwise("outside", "conventional")
    assert runs_clockwise("inside", "conventional")
