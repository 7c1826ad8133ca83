"""The job functions the workers run: results, errors as values, JSON bodies."""

from __future__ import annotations

import json

import numpy as np
import pytest

from arcspline.geometry import (
    COLUMN,
    DEFAULT_LIMITS,
    ArcSpline,
    GeometryError,
    Limits,
    Spiral,
    SpiralFromControlPoints,
    SpiralFromParameters,
    approximate,
)
from arcspline.outputs.gcode import GcodeOptions
from arcspline.worker.jobs import (
    Encoded,
    Job,
    approximate_chunk,
    approximate_one,
    encode,
)

PAPER = SpiralFromParameters(
    start=(1.5, 3.0), start_tangent=(1.0, 0.0), turn_angle_deg=51.34, end_curvature=0.41574
)


def _paper_spiral() -> Spiral:
    return Spiral.from_parameters((1.5, 3.0), (1.0, 0.0), 51.34, 0.41574)


def test_encode_writes_every_field_of_every_segment() -> None:
    spline = approximate(_paper_spiral(), 1e-3)
    encoded = encode(spline, {})
    assert isinstance(encoded, Encoded)
    body = json.loads(encoded.body)
    c = spline.columns
    assert (encoded.arc_count, encoded.line_count) == (12, 0)
    for i, segment in enumerate(body["segments"]):
        assert segment["type"] == "arc"
        assert segment["start"] == c.start[i].tolist()
        assert segment["end"] == c.end[i].tolist()
        assert segment["center"] == c.center[i].tolist()
        assert segment["radius"] == c.radius[i]
        assert segment["sweep_rad"] == c.sweep_rad[i]
        assert segment["direction"] == ("ccw" if c.sweep_rad[i] > 0 else "cw")
        for name in (
            "start_angle_rad",
            "length",
            "u_start",
            "u_end",
            "max_deviation",
            "u_at_max_deviation",
        ):
            assert segment[name] == getattr(c, name)[i]
    stats = body["stats"]
    assert stats["segment_count"] == 12
    assert stats["tolerance"] == 1e-3
    assert stats["strategy"] == "subdivide"
    assert stats["min_radius"] == spline.stats.min_radius
    assert body["gcode"] is None


def test_lines_carry_no_centre_or_radius() -> None:
    # A turn of 1e-9° is numerically straight: the core answers with lines.
    spiral = Spiral.from_parameters((0.0, 0.0), (1.0, 0.0), 1e-9, 1.0)
    spline = approximate(spiral, spiral.chord * 1e-3)
    encoded = encode(spline, {})
    assert isinstance(encoded, Encoded)
    body = json.loads(encoded.body)
    assert body["stats"]["line_count"] == len(body["segments"]) > 0
    assert body["stats"]["min_radius"] is None
    assert body["stats"]["max_radius"] is None
    for segment in body["segments"]:
        assert set(segment) == {
            "type",
            "start",
            "end",
            "length",
            "u_start",
            "u_end",
            "max_deviation",
            "u_at_max_deviation",
        }
        assert segment["type"] == "line"


def test_approximate_one_returns_the_body_or_the_error() -> None:
    ok = approximate_one(Job(PAPER, 0.1), DEFAULT_LIMITS)
    assert isinstance(ok, Encoded)
    assert ok.arc_count == 4
    floor = approximate_one(Job(PAPER, 1e-14), DEFAULT_LIMITS)
    assert isinstance(floor, GeometryError)
    assert floor.kind == "tolerance_floor"
    capped = approximate_one(Job(PAPER, 1e-5), Limits(max_segments=10))
    assert isinstance(capped, GeometryError)
    assert capped.kind == "segment_limit"
    assert capped.limit == 10
    bad = approximate_one(
        Job(SpiralFromControlPoints(((0, 0), (1, 0), (3, 0), (4, 1))), 0.1), DEFAULT_LIMITS
    )
    assert isinstance(bad, GeometryError)
    assert bad.field == "control_points"


def test_approximate_one_adds_the_program_when_asked() -> None:
    result = approximate_one(
        Job(PAPER, 0.1, outputs=(("gcode", GcodeOptions(feed_rate=200.0)),)), DEFAULT_LIMITS
    )
    assert isinstance(result, Encoded)
    program = json.loads(result.body)["gcode"]
    assert isinstance(program, str)
    assert "M2" in program


def test_a_chunk_answers_each_job_in_order_like_single_jobs() -> None:
    jobs = [
        Job(PAPER, 0.1),
        Job(PAPER, 1e-14),
        Job(PAPER, 0.01, "fewest-arcs"),
        Job(SpiralFromControlPoints(((0, 0), (1, 0), (3, 0), (4, 1))), 0.1),
        Job(PAPER, 1e-4),
        Job(PAPER, 1e-3, "fewest-arcs"),
    ]
    results = approximate_chunk(jobs, DEFAULT_LIMITS)
    assert len(results) == len(jobs)
    for job, result in zip(jobs, results, strict=True):
        single = approximate_one(job, DEFAULT_LIMITS)
        assert type(result) is type(single)
        if isinstance(result, Encoded):
            assert isinstance(single, Encoded)
            assert (result.arc_count, result.line_count) == (single.arc_count, single.line_count)
            assert json.loads(result.body)["stats"]["strategy"] == job.strategy
        else:
            assert isinstance(single, GeometryError)
            assert (result.field, result.kind) == (single.field, single.kind)


@pytest.mark.parametrize("column", ["end_x", "max_deviation", "center_y", "start_angle_rad"])
def test_a_result_with_a_non_finite_number_is_refused_not_sent(column: str) -> None:
    spline = approximate(_paper_spiral(), 1e-2)
    broken = spline.table.copy()
    broken[1, COLUMN[column]] = np.nan
    error = encode(ArcSpline(broken, spline.stats, spline.tolerance, spline.strategy), {})
    assert isinstance(error, GeometryError)
    assert (error.kind, error.field) == ("precision", "spiral")


# The core warns (overflow) on this input; in a worker that is only a log line.
@pytest.mark.filterwarnings("ignore::RuntimeWarning")
def test_a_degenerate_spiral_never_yields_nan() -> None:
    # Found by schemathesis: a turn of 6e-307° at coordinates of 1e16 collapses the control
    # points; at a huge tolerance the core once answered with NaN coordinates.
    spec = SpiralFromParameters(
        start=(-1.1959078817986156e16, -6.3419143617633e16),
        start_tangent=(3.5640755264004884e16, 10000.0),
        turn_angle_deg=5.831373173582048e-307,
        end_curvature=-0.5,
    )
    result = approximate_one(Job(spec, 9.031625772995782e307), DEFAULT_LIMITS)
    if isinstance(result, Encoded):
        assert b"null" not in result.body.split(b'"gcode":')[0]
    else:
        assert isinstance(result, GeometryError)
