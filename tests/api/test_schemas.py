"""Request models refuse bad input cheaply; response models describe what the worker emits."""

from __future__ import annotations

import json
from typing import Any

import pytest
from pydantic import TypeAdapter, ValidationError

from arcspline.api.schemas import (
    ApproximateRequest,
    ApproximateResponse,
    SpiralControlPoints,
    SpiralParameters,
)
from arcspline.geometry import STRATEGIES, Spiral, approximate
from arcspline.worker.jobs import Encoded, encode

ADAPTER: TypeAdapter[ApproximateRequest] = TypeAdapter(ApproximateRequest)


def _errors(body: Any) -> list[tuple[tuple[str | int, ...], str]]:
    with pytest.raises(ValidationError) as info:
        ADAPTER.validate_json(json.dumps(body))
    return [(tuple(e["loc"]), e["type"]) for e in info.value.errors()]


def test_the_spiral_form_is_chosen_by_its_fields(paper_request: dict[str, Any]) -> None:
    assert isinstance(ADAPTER.validate_python(paper_request).spiral, SpiralParameters)
    points = {"spiral": {"control_points": [[0, 0], [1, 0], [2, 0], [3, 1]]}, "tolerance": 1}
    assert isinstance(ADAPTER.validate_python(points).spiral, SpiralControlPoints)


def test_integers_are_numbers_but_strings_and_booleans_are_not() -> None:
    body = {
        "spiral": {
            "start": [1, 3],
            "start_tangent": [1, 0],
            "turn_angle_deg": 51,
            "end_curvature": 1,
        },
        "tolerance": 1,
    }
    assert ADAPTER.validate_python(body).tolerance == 1.0
    assert (("tolerance",), "float_type") in _errors({**body, "tolerance": "1"})
    assert (("tolerance",), "float_type") in _errors({**body, "tolerance": True})


def test_strategies_are_those_of_the_core(paper_request: dict[str, Any]) -> None:
    for strategy in STRATEGIES:
        assert ADAPTER.validate_python({**paper_request, "strategy": strategy}).strategy == strategy
    assert (("strategy",), "literal_error") in _errors({**paper_request, "strategy": "Subdivide"})


def test_many_errors_are_reported_together(paper_request: dict[str, Any]) -> None:
    body = {
        "spiral": {"start": [0], "start_tangent": [0, 0], "turn_angle_deg": 90, "end_curvature": 0},
        "tolerance": 0,
        "extra": 1,
    }
    found = {loc for loc, _ in _errors(body)}
    tag = "spiral-parameters"
    assert found == {
        ("spiral", tag, "start"),
        ("spiral", tag, "start_tangent"),
        ("spiral", tag, "turn_angle_deg"),
        ("spiral", tag, "end_curvature"),
        ("tolerance",),
        ("extra",),
    }


@pytest.mark.parametrize("tolerance", [0.1, 1e-5])
@pytest.mark.parametrize("strategy", STRATEGIES)
def test_the_response_model_accepts_what_the_worker_encodes(
    tolerance: float, strategy: str
) -> None:
    spiral = Spiral.from_parameters((1.5, 3.0), (1.0, 0.0), 51.34, 0.41574)
    spline = approximate(spiral, tolerance, strategy)  # type: ignore[arg-type]
    encoded = encode(spline, {"gcode": "G0 X0 Y0\nM2\n"})
    assert isinstance(encoded, Encoded)
    body = json.loads(encoded.body)
    model = ApproximateResponse.model_validate(body)
    assert model.stats.arc_count == spline.stats.arc_count
    assert len(model.segments) == len(spline)


def test_a_drawings_source_units_are_those_the_readers_know() -> None:
    from typing import get_args

    from arcspline.api.drawing_schemas import SourceUnits
    from arcspline.drawings.model import MM_PER_UNIT

    assert set(get_args(SourceUnits)) == set(MM_PER_UNIT)
