"""Problem details and the mapping of every error to its status, kind and field path."""

from __future__ import annotations

import pickle

import pytest

from arcspline.api.errors import (
    clean_loc,
    core_field_loc,
    gcode_problem,
    geometry_problem,
    pool_problem,
    problem,
    problem_kind,
    validation_problem,
)
from arcspline.geometry import GeometryError
from arcspline.outputs.gcode import GcodeError
from arcspline.worker.pool import JobTimeoutError, PoolUnavailableError, QueueFullError


@pytest.mark.parametrize(
    ("field", "loc"),
    [
        ("turn_angle_deg", ["spiral", "turn_angle_deg"]),
        ("end_curvature", ["spiral", "end_curvature"]),
        ("start", ["spiral", "start"]),
        ("start_tangent", ["spiral", "start_tangent"]),
        ("control_points", ["spiral", "control_points"]),
        ("control_points[2]", ["spiral", "control_points", 2]),
        ("tolerance", ["tolerance"]),
        ("strategy", ["strategy"]),
    ],
)
def test_core_fields_map_to_request_paths(field: str, loc: list[str | int]) -> None:
    assert core_field_loc(field) == loc


def test_geometry_errors_become_422_naming_the_field() -> None:
    error = GeometryError("turn_angle_deg", "must lie strictly between 0 and 90 degrees")
    body = geometry_problem(pickle.loads(pickle.dumps(error)), ["body"])
    assert body["status"] == 422
    assert body["type"] == "urn:arcspline:problem:invalid-input"
    assert body["errors"] == [
        {
            "loc": ["body", "spiral", "turn_angle_deg"],
            "msg": "must lie strictly between 0 and 90 degrees",
            "type": "invalid_input",
        }
    ]
    assert body["detail"].startswith("body.spiral.turn_angle_deg: ")


@pytest.mark.parametrize(
    ("kind", "title"), [("segment_limit", "Too many"), ("tolerance_floor", "")]
)
def test_limit_errors_name_the_limit(kind: str, title: str) -> None:
    error = GeometryError("tolerance", "cannot be reached", kind=kind, limit=1234.0)  # type: ignore[arg-type]
    body = geometry_problem(error, ["body", "jobs", 7])
    assert body["status"] == 422
    assert body["limit"] == 1234.0
    assert "1234" in body["detail"]
    assert problem_kind(body) == kind
    assert body["errors"][0]["loc"] == ["body", "jobs", 7, "tolerance"]
    assert body["title"].startswith(title)


def test_gcode_errors_name_the_gcode_option() -> None:
    body = gcode_problem(GcodeError("decimals", "too few for this spiral"), ["body"])
    assert body["status"] == 422
    assert problem_kind(body) == "gcode"
    assert body["errors"][0]["loc"] == ["body", "gcode", "decimals"]
    assert "body.gcode.decimals" in body["detail"]


def test_pool_errors_are_503_with_retry_after_or_504() -> None:
    full = QueueFullError("64 in flight")
    full.retry_after_s = 2.0
    body, headers = pool_problem(full)
    assert (body["status"], headers) == (503, {"Retry-After": "2"})
    body, headers = pool_problem(PoolUnavailableError("gone"))
    assert body["status"] == 503
    assert "Retry-After" in headers
    body, headers = pool_problem(JobTimeoutError(30.0))
    assert (body["status"], body["limit"], headers) == (504, 30.0, {})


def test_validation_problems_list_each_field_and_drop_union_tags() -> None:
    errors = [
        {"loc": ("spiral", "spiral-parameters", "turn_angle_deg"), "msg": "too big", "type": "x"},
        {"loc": ("tolerance",), "msg": "too small", "type": "y"},
    ]
    body = validation_problem(errors, ["body"])
    assert [e["loc"] for e in body["errors"]] == [
        ["body", "spiral", "turn_angle_deg"],
        ["body", "tolerance"],
    ]
    assert "body.spiral.turn_angle_deg: too big" in body["detail"]
    assert clean_loc(["spiral", "spiral-control-points", "control_points", 1]) == [
        "spiral",
        "control_points",
        1,
    ]


def test_plain_http_problems_use_about_blank() -> None:
    body = problem("http", "Not Found", status=404)
    assert (body["type"], body["title"]) == ("about:blank", "Not Found")
    assert problem_kind(body) == "not_found"
