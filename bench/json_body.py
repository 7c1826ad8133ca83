"""What refusing duplicate JSON keys costs a request body (issue 19): figures printed, never
asserted.

A request's body is validated by pydantic-core straight from its bytes; the duplicate-key
check (``arcspline.api.duplicates``, the standard library's C scanner with an
``object_pairs_hook``) parses it once more. Timed in turn (``timing.paired_best``) on the
paper's spiral with a G-code program (a typical small request) and on a batch as large as the
default body limit allows (4 MiB).

Run with ``.venv/bin/python bench/json_body.py``.
"""

from __future__ import annotations

import sys
from functools import partial
from pathlib import Path

import orjson
from pydantic import TypeAdapter

sys.path.insert(0, str(Path(__file__).resolve().parent))

from timing import paired_best

from arcspline.api.duplicates import has_duplicate
from arcspline.api.schemas import MAX_BODY_BYTES, ApproximateRequest, BatchRequest

SPIRAL = {"start": [1.5, 3.0], "start_tangent": [1.0, 0.0], "turn_angle_deg": 51.34,
          "end_curvature": 0.41574}  # fmt: skip
SMALL = {"spiral": SPIRAL, "tolerance": 1e-3, "gcode": {"feed_rate": 100.0}}
#: A batch job with full-precision numbers, as a program would write them.
JOB = {
    "spiral": {
        "start": [0.12345678901234, 1.2345678901234],
        "start_tangent": [0.7071067811865476, 0.7071067811865476],
        "turn_angle_deg": 45.123456789,
        "end_curvature": 1.23456789012,
    },
    "tolerance": 1e-3,
}


def main() -> None:
    small = orjson.dumps(SMALL)
    jobs = MAX_BODY_BYTES // (len(orjson.dumps(JOB)) + 1) - 1
    big = orjson.dumps({"jobs": [JOB] * jobs})
    assert len(big) <= MAX_BODY_BYTES
    cases = [
        ("small request", small, TypeAdapter(ApproximateRequest), 2.0, 1e6, "µs"),
        (f"batch of {jobs} jobs", big, TypeAdapter(BatchRequest), 6.0, 1e3, "ms"),
    ]
    print(f"{'body':>24} {'bytes':>9} {'validate_json':>14} {'+ duplicate check':>18} {'ratio':>6}")
    for name, raw, adapter, budget_s, scale, unit in cases:
        assert not has_duplicate(raw)
        runs = [partial(adapter.validate_json, raw), partial(has_duplicate, raw)]
        validate_s, check_s = paired_best(runs, budget_s)
        print(
            f"{name:>24} {len(raw):>9} {validate_s * scale:>11.1f} {unit} "
            f"{check_s * scale:>15.1f} {unit} {check_s / validate_s:>5.2f}×"
        )


if __name__ == "__main__":
    main()
