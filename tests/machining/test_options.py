"""Options are validated, naming the field."""

from __future__ import annotations

import math
from typing import Any

import pytest

from arcspline.geometry import GeometryError
from arcspline.machining import MachiningOptions, Tabs, check


def test_defaults_are_valid_and_the_lead_radius_defaults_to_the_tool_radius() -> None:
    options = check(MachiningOptions(6.0))
    assert options.tool_radius == 3.0
    assert options.resolved_lead_radius == 3.0
    assert MachiningOptions(6.0, lead_radius=0).resolved_lead_radius == 0.0


@pytest.mark.parametrize(
    ("changes", "field"),
    [
        ({"tool_diameter": 0.0}, "machining.tool_diameter"),
        ({"tool_diameter": -1.0}, "machining.tool_diameter"),
        ({"tool_diameter": math.nan}, "machining.tool_diameter"),
        ({"tool_diameter": math.inf}, "machining.tool_diameter"),
        ({"tool_diameter": True}, "machining.tool_diameter"),
        ({"cut": "around"}, "machining.cut"),
        ({"direction": "up"}, "machining.direction"),
        ({"entry": "drop"}, "machining.entry"),
        ({"compensation": "both"}, "machining.compensation"),
        ({"join": "bevel"}, "machining.join"),
        ({"lead_radius": -0.5}, "machining.lead_radius"),
        ({"lead_radius": math.nan}, "machining.lead_radius"),
        ({"tabs": Tabs(0, 5.0, 1.0)}, "machining.tabs.count"),
        ({"tabs": Tabs(2.5, 5.0, 1.0)}, "machining.tabs.count"),  # type: ignore[arg-type]
        ({"tabs": Tabs(4, 0.0, 1.0)}, "machining.tabs.width"),
        ({"tabs": Tabs(4, 5.0, -1.0)}, "machining.tabs.height"),
        ({"tool_number": 3}, "machining.tool_number"),  # needs the controller
        ({"compensation": "controller", "tool_number": 0}, "machining.tool_number"),
        ({"compensation": "controller", "tool_number": 1.5}, "machining.tool_number"),
    ],
)
def test_a_bad_field_is_named(changes: dict[str, Any], field: str) -> None:
    with pytest.raises(GeometryError) as caught:
        check(MachiningOptions(6.0)._replace(**changes))
    assert caught.value.field == field
    assert caught.value.kind == "invalid_input"
