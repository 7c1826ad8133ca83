"""Property-based contract test: schemathesis generates requests from the committed OpenAPI
document (valid ones, and invalid ones for operations with a body) and checks that the app
answers none with a 5xx and none with a response the document does not describe.

The app runs with its lifespan (schemathesis starts it on first use and stops it after each
test), so requests reach the real process pool. Each operation is its own pytest item with
its own id (``@schema.parametrize()`` gives every item the same node id, which pytest-xdist
collapses into one).
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest
import schemathesis
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from schemathesis import GenerationMode
from schemathesis.checks import (
    content_type_conformance,
    negative_data_rejection,
    not_a_server_error,
    response_headers_conformance,
    response_schema_conformance,
    status_code_conformance,
)

from arcspline.api.app import create_app
from arcspline.settings import Settings

OPENAPI = Path(__file__).resolve().parents[2] / "openapi" / "openapi.json"

# Bounded work per request: random spirals at random tolerances can ask for the most
# segments (large bodies) or for slow fewest-arcs runs; a 504 is a documented answer.
app = create_app(
    Settings(
        pool_size=2,
        queue_capacity=16,
        max_segments=2000,
        job_time_limit_s=2,
        batch_time_limit_s=4,
    )
)
schema = schemathesis.openapi.from_path(str(OPENAPI))
schema.app = app  # the binding from_asgi makes, without a request at import time

OPERATIONS = {result.ok().label: result.ok() for result in schema.get_all_operations()}
CASES = [
    (label, mode)
    for label, operation in OPERATIONS.items()
    for mode in (GenerationMode.POSITIVE, GenerationMode.NEGATIVE)
    if mode is GenerationMode.POSITIVE or operation.body
]
CHECKS = [
    not_a_server_error,
    status_code_conformance,
    content_type_conformance,
    response_headers_conformance,
    response_schema_conformance,
]


def rejects_negative_data(ctx: Any, response: Any, case: Any) -> bool | None:
    """``negative_data_rejection``, with the body limit's 413 counted as a rejection: an
    invalid body past the limit (10 001 subpaths of a path) is refused before it is read."""
    if response.status_code == 413:
        return None
    return negative_data_rejection(ctx, response, case)


@pytest.mark.parametrize(("label", "mode"), CASES, ids=[f"{op}-{m.value}" for op, m in CASES])
@settings(
    max_examples=40,
    deadline=None,
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.filter_too_much],
)
@given(data=st.data())
def test_the_app_keeps_its_contract(label: str, mode: GenerationMode, data: st.DataObject) -> None:
    operation = OPERATIONS[label]
    case = data.draw(operation.as_strategy(generation_mode=mode))
    checks = list(CHECKS)
    if operation.path not in ("/v1/approximate/batch", "/v1/paths/batch"):
        # A batch answers 200 to invalid jobs on purpose: each becomes an error entry.
        checks.append(rejects_negative_data)
    case.call_and_validate(checks=checks)
