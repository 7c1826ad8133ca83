"""POST /v1/approximate in process: results, and every refusal as problem details."""

from __future__ import annotations

import copy
import math
from typing import Any

import httpx
import numpy as np
import pytest
from support import oracle

from arcspline.api.schemas import ApproximateResponse

from .conftest import locs, problem_of, running_app, until_ready
from .spline_json import control_points, spline_from_json

pytestmark = pytest.mark.anyio

URL = "/v1/approximate"


async def test_the_papers_example_gives_table_1s_twelve_arcs_within_tolerance(
    client: httpx.AsyncClient, paper_request: dict[str, Any]
) -> None:
    response = await client.post(URL, json=paper_request)
    assert response.status_code == 200, response.text
    assert response.headers["content-type"] == "application/json"
    body = response.json()
    ApproximateResponse.model_validate(body)
    stats = body["stats"]
    assert (stats["arc_count"], stats["line_count"], stats["segment_count"]) == (12, 0, 12)
    assert stats["tolerance"] == 0.001
    assert stats["strategy"] == "subdivide"
    assert stats["max_deviation"] == pytest.approx(0.0009584, rel=5e-3)
    assert body["gcode"] is None
    # The JSON, read back, is a valid approximation by an independent measurement.
    verdict = oracle.check(
        control_points(paper_request["spiral"]), spline_from_json(body), 0.001, samples=20_000
    )
    assert not verdict.violations, verdict.describe()


async def test_arc_fields_are_consistent_with_each_other(
    client: httpx.AsyncClient, paper_request: dict[str, Any]
) -> None:
    body = (await client.post(URL, json=paper_request)).json()
    for arc in body["segments"]:
        cx, cy = arc["center"]
        for x, y in (arc["start"], arc["end"]):
            assert math.hypot(x - cx, y - cy) == pytest.approx(arc["radius"], rel=1e-9)
        assert arc["direction"] == ("ccw" if arc["sweep_rad"] > 0 else "cw")
        assert arc["length"] == pytest.approx(arc["radius"] * abs(arc["sweep_rad"]), rel=1e-9)
        angle = math.atan2(arc["start"][1] - cy, arc["start"][0] - cx)
        assert math.remainder(angle - arc["start_angle_rad"], math.tau) == pytest.approx(
            0.0, abs=1e-9
        )


async def test_control_points_and_a_clockwise_spiral(client: httpx.AsyncClient) -> None:
    spiral = {
        "start": [10.0, -2.0],
        "start_tangent": [0.0, 3.0],
        "turn_angle_deg": 70.0,
        "end_curvature": -0.8,
    }
    by_parameters = (await client.post(URL, json={"spiral": spiral, "tolerance": 1e-3})).json()
    points = control_points(spiral).tolist()
    response = await client.post(
        URL, json={"spiral": {"control_points": points}, "tolerance": 1e-3}
    )
    assert response.status_code == 200, response.text
    by_points = response.json()
    assert {s["direction"] for s in by_points["segments"]} == {"cw"}
    assert by_points["stats"]["arc_count"] == by_parameters["stats"]["arc_count"]
    verdict = oracle.check(np.asarray(points), spline_from_json(by_points), 1e-3, samples=20_000)
    assert not verdict.violations, verdict.describe()


async def test_fewest_arcs_strategy_is_accepted(
    client: httpx.AsyncClient, paper_request: dict[str, Any]
) -> None:
    subdivide = (await client.post(URL, json=paper_request)).json()
    response = await client.post(URL, json={**paper_request, "strategy": "fewest-arcs"})
    assert response.status_code == 200, response.text
    body = response.json()
    assert body["stats"]["strategy"] == "fewest-arcs"
    assert body["stats"]["segment_count"] <= subdivide["stats"]["segment_count"]
    assert body["stats"]["max_deviation"] <= 0.001


def _spiral(**changes: Any) -> dict[str, Any]:
    spiral: dict[str, Any] = {
        "start": [1.5, 3.0],
        "start_tangent": [1.0, 0.0],
        "turn_angle_deg": 51.34,
        "end_curvature": 0.41574,
    }
    spiral.update(changes)
    return spiral


INVALID: list[tuple[str, dict[str, Any], list[str | int]]] = [
    ("θ = 0", {"spiral": _spiral(turn_angle_deg=0), "tolerance": 1e-3}, ["turn_angle_deg"]),
    ("θ = 90", {"spiral": _spiral(turn_angle_deg=90), "tolerance": 1e-3}, ["turn_angle_deg"]),
    ("θ < 0", {"spiral": _spiral(turn_angle_deg=-5), "tolerance": 1e-3}, ["turn_angle_deg"]),
    ("c = 0", {"spiral": _spiral(end_curvature=0), "tolerance": 1e-3}, ["end_curvature"]),
    (
        "zero tangent",
        {"spiral": _spiral(start_tangent=[0, 0]), "tolerance": 1e-3},
        ["start_tangent"],
    ),
    ("short vector", {"spiral": _spiral(start=[1.0]), "tolerance": 1e-3}, ["start"]),
    ("long vector", {"spiral": _spiral(start=[1.0, 2.0, 3.0]), "tolerance": 1e-3}, ["start"]),
    (
        "string number",
        {"spiral": _spiral(end_curvature="0.4"), "tolerance": 1e-3},
        ["end_curvature"],
    ),
    (
        "boolean number",
        {"spiral": _spiral(turn_angle_deg=True), "tolerance": 1e-3},
        ["turn_angle_deg"],
    ),
    ("missing field", {"spiral": {"start": [0, 0]}, "tolerance": 1e-3}, ["start_tangent"]),
    (
        "three control points",
        {"spiral": {"control_points": [[0, 0], [1, 0], [2, 0]]}, "tolerance": 1e-3},
        ["control_points"],
    ),
    (
        "mixed spiral forms",
        {
            "spiral": {"control_points": [[0, 0], [1, 0], [2, 0], [3, 1]], "start": [0, 0]},
            "tolerance": 1e-3,
        },
        ["start"],
    ),
]
TOP_LEVEL_INVALID: list[tuple[str, dict[str, Any], list[str | int]]] = [
    ("tolerance 0", {"spiral": _spiral(), "tolerance": 0}, ["tolerance"]),
    ("negative tolerance", {"spiral": _spiral(), "tolerance": -1e-3}, ["tolerance"]),
    (
        "unknown strategy",
        {"spiral": _spiral(), "tolerance": 1e-3, "strategy": "greedy"},
        ["strategy"],
    ),
    ("typo", {"spiral": _spiral(), "tolerence": 1e-3}, ["tolerence"]),
    ("missing tolerance", {"spiral": _spiral()}, ["tolerance"]),
    (
        "gcode without feed",
        {"spiral": _spiral(), "tolerance": 1e-3, "gcode": {}},
        ["gcode", "feed_rate"],
    ),
    (
        "gcode unknown option",
        {"spiral": _spiral(), "tolerance": 1e-3, "gcode": {"feed_rate": 100, "feedrate": 1}},
        ["gcode", "feedrate"],
    ),
]


@pytest.mark.parametrize(
    ("body", "field"), [(b, f) for _, b, f in INVALID], ids=[name for name, _, _ in INVALID]
)
async def test_invalid_spirals_are_refused_naming_the_field(
    client: httpx.AsyncClient, body: dict[str, Any], field: list[str | int]
) -> None:
    problem = problem_of(await client.post(URL, json=body), 422)
    assert problem["type"].endswith(":validation")
    assert ["body", "spiral", *field] in [loc[: len(field) + 2] for loc in locs(problem)]


@pytest.mark.parametrize(
    ("body", "field"),
    [(b, f) for _, b, f in TOP_LEVEL_INVALID],
    ids=[name for name, _, _ in TOP_LEVEL_INVALID],
)
async def test_invalid_requests_are_refused_naming_the_field(
    client: httpx.AsyncClient, body: dict[str, Any], field: list[str | int]
) -> None:
    problem = problem_of(await client.post(URL, json=body), 422)
    assert ["body", *field] in locs(problem)


@pytest.mark.parametrize("token", ["NaN", "Infinity", "-Infinity", "1e999"])
async def test_non_finite_numbers_are_refused(client: httpx.AsyncClient, token: str) -> None:
    raw = (
        '{"spiral": {"start": [1.5, 3.0], "start_tangent": [1.0, 0.0], '
        f'"turn_angle_deg": 51.34, "end_curvature": {token}}}, "tolerance": 0.001}}'
    )
    response = await client.post(URL, content=raw, headers={"content-type": "application/json"})
    problem = problem_of(response, 422)
    assert ["body", "spiral", "end_curvature"] in locs(problem)


@pytest.mark.parametrize("raw", ['{"spiral": ', "[1, 2", "not json", '{"a": 1,}'])
async def test_malformed_json_is_a_400(client: httpx.AsyncClient, raw: str) -> None:
    response = await client.post(URL, content=raw, headers={"content-type": "application/json"})
    problem = problem_of(response, 400)
    assert problem["type"].endswith(":malformed-json")


@pytest.mark.parametrize(
    ("raw", "reason"),
    [
        (b'{"tolerance": ' + b"[" * 100_000 + b"]" * 100_000 + b"}", "nested too deeply"),
        (b'{"tolerance": 1' + b"0" * 5000 + b"}", "digits"),
        (b'{"tolerance": "\xff"}', "not UTF-8"),
    ],
    ids=["deep", "long-integer", "not-utf8"],
)
async def test_json_the_parser_cannot_take_is_malformed_json(
    client: httpx.AsyncClient, raw: bytes, reason: str
) -> None:
    response = await client.post(URL, content=raw, headers={"content-type": "application/json"})
    problem = problem_of(response, 400)
    assert problem["type"].endswith(":malformed-json")
    assert reason in problem["detail"]


async def test_a_body_that_is_not_an_object_is_refused(client: httpx.AsyncClient) -> None:
    problem_of(await client.post(URL, json=[1, 2, 3]), 422)
    problem_of(await client.post(URL, content=b""), 422)


async def test_an_unreachable_tolerance_names_the_tolerance_and_the_floor(
    client: httpx.AsyncClient, paper_request: dict[str, Any]
) -> None:
    response = await client.post(URL, json={**paper_request, "tolerance": 1e-13})
    problem = problem_of(response, 422)
    assert problem["type"].endswith(":tolerance-floor")
    assert locs(problem) == [["body", "tolerance"]]
    assert 1e-13 < problem["limit"] < 1e-6
    assert f"{problem['limit']:g}" in problem["detail"]


async def test_the_segment_limit_is_named() -> None:
    async with running_app(max_segments=20) as (_, client):
        body = {"spiral": _spiral(), "tolerance": 1e-5}
        problem = problem_of(await client.post(URL, json=body), 422)
    assert problem["type"].endswith(":segment-limit")
    assert problem["limit"] == 20
    assert "20" in problem["detail"]
    assert locs(problem) == [["body", "tolerance"]]


async def test_a_spiral_the_core_refuses_names_the_spiral_field(client: httpx.AsyncClient) -> None:
    # Schema-valid, but not of the paper's form (B2 − B1 ≠ B1 − B0): only the core can tell.
    body = {"spiral": {"control_points": [[0, 0], [1, 0], [3, 0], [4, 1]]}, "tolerance": 1e-3}
    problem = problem_of(await client.post(URL, json=body), 422)
    assert problem["type"].endswith(":invalid-input")
    assert locs(problem) == [["body", "spiral", "control_points"]]


async def test_an_oversize_body_is_a_413_before_it_is_read() -> None:
    async with running_app(max_body_bytes=1024) as (_, client):
        body = {"spiral": _spiral(), "tolerance": 1e-3, "padding": "x" * 2000}
        problem = problem_of(await client.post(URL, json=body), 413)
        assert problem["limit"] == 1024

        async def chunks() -> Any:
            for _ in range(10):
                yield b" " * 200

        # Without a Content-Length (chunked), the limit applies as the body arrives.
        problem = problem_of(await client.post(URL, content=chunks()), 413)
        assert problem["type"].endswith(":body-too-large")


async def test_unknown_paths_and_methods_are_problems(client: httpx.AsyncClient) -> None:
    problem_of(await client.get("/v2/approximate"), 404)
    response = await client.get(URL)
    problem_of(response, 405)
    assert response.headers["allow"] == "POST"


async def test_every_response_carries_a_request_id(
    client: httpx.AsyncClient, paper_request: dict[str, Any]
) -> None:
    response = await client.post(URL, json=paper_request, headers={"X-Request-ID": "a" * 32})
    assert response.headers["x-request-id"] == "a" * 32
    bad = await client.post(URL, json={})
    request_id = bad.headers["x-request-id"]
    assert problem_of(bad, 422)["request_id"] == request_id


async def test_queue_full_is_a_503_with_retry_after(
    app: Any, client: httpx.AsyncClient, paper_request: dict[str, Any]
) -> None:
    pool = app.state.runtime.pool
    with pool.admit(pool.capacity):  # every place taken, as by a burst of slow requests
        response = await client.post(URL, json=paper_request)
    problem = problem_of(response, 503)
    assert problem["type"].endswith(":queue-full")
    assert int(response.headers["retry-after"]) >= 1
    assert (await client.post(URL, json=paper_request)).status_code == 200


async def test_time_limit_is_a_504_and_the_pool_recovers(paper_request: dict[str, Any]) -> None:
    async with running_app(job_time_limit_s=0.001) as (app, client):
        big = {**paper_request, "tolerance": 1e-9}
        problem = problem_of(await client.post(URL, json=big), 504)
        assert problem["type"].endswith(":time-limit")
        assert problem["limit"] == 0.001
        await until_ready(client)
        assert app.state.runtime.pool.restarts >= 1


async def test_gcode_is_returned_when_asked(
    client: httpx.AsyncClient, paper_request: dict[str, Any]
) -> None:
    body = {**paper_request, "gcode": {"feed_rate": 300}}
    response = await client.post(URL, json=body)
    assert response.status_code == 200, response.text
    program = response.json()["gcode"]
    assert isinstance(program, str)
    assert "G17" in program
    assert program.rstrip().endswith("M2")


async def test_gcode_option_errors_name_the_gcode_field(
    client: httpx.AsyncClient, paper_request: dict[str, Any]
) -> None:
    # Schema-valid, but only half of a 2.5-D cut: the G-code writer refuses it.
    body = copy.deepcopy(paper_request)
    body["gcode"] = {"feed_rate": 300, "cut_z": -1.0}
    problem = problem_of(await client.post(URL, json=body), 422)
    assert problem["type"].endswith(":gcode")
    assert all(loc[:2] == ["body", "gcode"] and len(loc) == 3 for loc in locs(problem))
