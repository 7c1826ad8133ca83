"""POST /v1/approximate holds the answer to the input exactly as given (docs/method.md §1):
control points just off the paper's form are fitted as given, and a turn angle near 90°
keeps its precision. Measured by the independent oracle, never by the core."""

from __future__ import annotations

import math
from typing import Any

import httpx
import numpy as np
import pytest

from tests.support import oracle

from .spline_json import spline_from_json

pytestmark = pytest.mark.anyio

URL = "/v1/approximate"


async def test_points_just_off_the_form_are_answered_for_the_points_given(
    client: httpx.AsyncClient,
) -> None:
    # The paper's spiral with its last leg 0.9e-6 longer than the form allows for exactly:
    # inside the form's bound, far outside the tolerance.
    given = oracle.paper_control_points((1.5, 3.0), (1.0, 0.0), 51.34, 0.41574)
    given[3] = given[3] + 0.9e-6 * (given[3] - given[2])
    tolerance = 1e-8
    body = {"spiral": {"control_points": given.tolist()}, "tolerance": tolerance}
    response = await client.post(URL, json=body)
    assert response.status_code == 200, response.text
    answer: dict[str, Any] = response.json()
    assert answer["segments"][-1]["end"] == given[3].tolist()
    verdict = oracle.check(given, spline_from_json(answer), tolerance, samples=20_000)
    assert not verdict.violations, verdict.describe()


async def test_a_turn_a_tenth_of_a_microdegree_short_of_90_ends_where_the_spiral_ends(
    client: httpx.AsyncClient,
) -> None:
    spiral = {
        "start": [2.0, -1.0],
        "start_tangent": [1.0, 0.0],
        "turn_angle_deg": 89.9999999,
        "end_curvature": 1.0,
    }
    exact = oracle.paper_control_points(
        spiral["start"], spiral["start_tangent"], spiral["turn_angle_deg"], 1.0
    )
    tolerance = 1e-7 * oracle.chord(exact)
    response = await client.post(URL, json={"spiral": spiral, "tolerance": tolerance})
    assert response.status_code == 200, response.text
    segments = spline_from_json(response.json()).segments
    assert math.dist(segments[-1].end, exact[3]) <= oracle.rounding_slack(exact)
    continuity = oracle.continuity(exact, segments)
    assert not continuity.violations(), continuity.violations()
    deviation = oracle.measure(exact, segments, samples=20_000)
    assert deviation.max <= tolerance * (1 + 1e-9) + oracle.rounding_slack(exact)
    assert np.isfinite(deviation.max)
