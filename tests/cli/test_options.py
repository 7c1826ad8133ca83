"""What the options change in a request (``arcspline.cli.options``): given ones replace the
request's fields, others leave them; an option that cannot apply is a usage error. The
option lists follow the service's own request models."""

from __future__ import annotations

from typing import Any, get_args

import pytest

import arcspline
from arcspline.api.drawing_schemas import DrawingRequest, SourceUnits
from arcspline.api.schemas import GcodeRequest, OutputFormat
from arcspline.cli.errors import UsageError
from arcspline.cli.options import (
    DRAWING_FIELDS,
    GCODE_FIELDS,
    Format,
    Overrides,
    StrategyName,
)
from arcspline.cli.options import SourceUnits as CliSourceUnits

SPIRAL: dict[str, Any] = {"spiral": {"control_points": [[0, 0], [1, 0], [2, 0], [3, 1]]}}
DRAWING: dict[str, Any] = {"document": "<svg/>", "format": "svg"}


def test_the_option_lists_are_the_services_fields() -> None:
    assert set(GCODE_FIELDS) == set(GcodeRequest.model_fields) - {"units"}
    assert set(DRAWING_FIELDS) <= set(DrawingRequest.model_fields)
    assert set(get_args(StrategyName)) == set(arcspline.STRATEGY_NAMES)
    assert get_args(CliSourceUnits) == get_args(SourceUnits)
    assert get_args(Format) == get_args(OutputFormat)


def test_given_options_replace_the_requests_fields_and_others_stay() -> None:
    request = {**SPIRAL, "tolerance": 0.1, "strategy": "subdivide",
               "gcode": {"feed_rate": 100, "decimals": 3}}  # fmt: skip
    overrides = Overrides.of(0.01, "fewest-arcs", None, feed_rate=600.0, comments=True,
                             decimals=None)  # fmt: skip
    assert overrides.apply(request, "spiral") == {
        **SPIRAL,
        "tolerance": 0.01,
        "strategy": "fewest-arcs",
        "gcode": {"feed_rate": 600.0, "decimals": 3, "comments": True},
    }
    assert request["tolerance"] == 0.1, "the request itself is left alone"
    assert Overrides.of(None, None, None).apply(request, "spiral") == request


def test_a_tolerance_is_needed_from_the_options_or_the_request() -> None:
    with pytest.raises(UsageError) as refused:
        Overrides.of(None, None, None).apply(SPIRAL, "spiral")
    assert refused.value.option == "--tolerance"
    assert Overrides.of(0.5, None, None).apply(SPIRAL, "spiral")["tolerance"] == 0.5


def test_units_are_a_drawings_own_and_a_curves_program_units() -> None:
    inch = Overrides.of(0.01, None, "inch", feed_rate=10.0)
    drawing = inch.apply({**DRAWING, "gcode": {"feed_rate": 5, "units": "mm"}}, "drawing")
    assert (drawing["units"], drawing["gcode"]) == ("inch", {"feed_rate": 10.0, "units": "inch"})
    assert inch.apply(SPIRAL, "spiral")["gcode"] == {"feed_rate": 10.0, "units": "inch"}
    with pytest.raises(UsageError, match="needs --feed-rate") as refused:
        Overrides.of(0.01, None, "inch").apply(SPIRAL, "path")
    assert refused.value.option == "--units"


def test_drawing_options_apply_to_drawings_only() -> None:
    overrides = Overrides.of(0.01, None, None, layers=["A,B", "C"], source_units="in",
                             order=False, choose_start=None)  # fmt: skip
    drawing = overrides.apply(DRAWING, "drawing")
    assert drawing["layers"] == ["A", "B", "C"]
    assert (drawing["source_units"], drawing["order"]) == ("in", False)
    assert "choose_start" not in drawing
    with pytest.raises(UsageError, match="only for drawings") as refused:
        overrides.apply(SPIRAL, "spiral")
    assert refused.value.option == "--layers, --source-units, --order"


def test_a_program_is_asked_for_by_any_gcode_option() -> None:
    assert not Overrides.of(0.1, None, "mm").asks_for_program
    assert Overrides.of(0.1, None, None, feed_rate=100.0).asks_for_program
