"""The path jobs the workers run: ``approximate_path_one`` and ``encode_path`` (strict JSON,
every number finite, the fields of the core's result), ``approximate_path_chunk`` (order, a
bad job isolated), ``render`` (an SVG), errors as values, and jobs that cross the process
boundary."""

from __future__ import annotations

import json
import math
import pickle
import xml.etree.ElementTree as ET
from typing import Any

import pytest

from arcspline.geometry import DEFAULT_LIMITS, GeometryError, Limits
from arcspline.geometry.paths import approximate_path
from arcspline.outputs.gcode import GcodeError, GcodeOptions
from arcspline.paths import PathFromData, PathFromSegments, parse_path_data
from arcspline.paths.specs import ArcAbout, CubicTo, EllipticalArcTo, LineTo, SubpathForm
from arcspline.worker.jobs import (
    Document,
    Encoded,
    PathJob,
    approximate_path_chunk,
    approximate_path_one,
    encode_path,
    path_segments,
    render,
)
from tests.support import gcode_reader

MIXED = "M 0 0 C 10 0 20 10 30 30 L 40 30 A 5 5 0 0 1 50 30 Z M 60 0 A 8 4 30 0 1 80 10 L 90 0"
JSON_FORM = PathFromSegments(
    (
        SubpathForm(
            (0.0, 0.0),
            (CubicTo((10.0, 0.0), (20.0, 10.0), (30.0, 30.0)), LineTo((40.0, 30.0))),
            True,
        ),
        SubpathForm(
            (60.0, 0.0),
            (
                ArcAbout((65.0, 0.0), -90.0),
                EllipticalArcTo((8.0, 4.0), 30.0, False, True, (80.0, 10.0)),
            ),
        ),
    )
)
SVG = "{http://www.w3.org/2000/svg}"


def _refuse_constant(token: str) -> Any:
    raise AssertionError(f"the body holds {token}, which is not JSON")


def strict_body(encoded: Encoded) -> dict[str, Any]:
    """The encoded body as strict JSON, after checking that every number in it is finite."""
    body: dict[str, Any] = json.loads(encoded.body, parse_constant=_refuse_constant)

    def walk(value: Any, where: str) -> None:
        if isinstance(value, dict):
            for key, item in value.items():
                walk(item, f"{where}.{key}")
        elif isinstance(value, list):
            for i, item in enumerate(value):
                walk(item, f"{where}[{i}]")
        elif isinstance(value, float):
            assert math.isfinite(value), where

    walk(body, "")
    return body


@pytest.mark.parametrize("strategy", ["subdivide", "fewest-arcs"])
@pytest.mark.parametrize("spec", [PathFromData(MIXED), JSON_FORM], ids=["svg-data", "json-form"])
def test_approximate_path_one_encodes_the_cores_result(
    spec: PathFromData | PathFromSegments, strategy: str
) -> None:
    encoded = approximate_path_one(PathJob(spec, 0.05, strategy), DEFAULT_LIMITS)
    assert isinstance(encoded, Encoded)
    body = strict_body(encoded)
    assert set(body) == {"subpaths", "stats", "gcode"}
    assert body["gcode"] is None
    # The same as the core's result, encoded here directly.
    result = approximate_path(spec.build(), 0.05, strategy, DEFAULT_LIMITS)
    direct = encode_path(result, {})
    assert isinstance(direct, Encoded)
    assert strict_body(direct) == body
    assert (encoded.arc_count, encoded.line_count) == (
        result.stats.arc_count,
        result.stats.line_count,
    )
    assert encoded.arc_count + encoded.line_count == result.segment_count
    assert len(body["subpaths"]) == len(result.subpaths) == 2
    for sub, core in zip(body["subpaths"], result.subpaths, strict=True):
        assert sub["closed"] == core.closed
        assert sub["segments"] == path_segments(core)
        assert len(sub["segments"]) == len(core.spline)
        c = core.spline.columns
        for i, seg in enumerate(sub["segments"]):
            assert seg["start"] == c.start[i].tolist()
            assert seg["end"] == c.end[i].tolist()
            assert seg["max_deviation"] == c.max_deviation[i]
            assert seg["type"] == ("arc" if c.is_arc[i] else "line")
            if seg["type"] == "arc":
                assert seg["radius"] == c.radius[i]
                assert seg["direction"] == ("ccw" if c.sweep_rad[i] > 0 else "cw")
        src = core.sources()
        assert [s["source_segment"] for s in sub["segments"]] == src.segment.tolist()
        assert [s["u_start"] for s in sub["segments"]] == src.t_start.tolist()
        stats = sub["stats"]
        assert stats["segment_count"] == core.spline.stats.segment_count
        assert stats["max_deviation"] == core.spline.stats.max_deviation <= 0.05
        assert stats["strategy"] == strategy
    assert body["stats"]["subpath_count"] == 2
    assert body["stats"]["segment_count"] == result.segment_count


def test_radii_are_null_only_where_a_subpath_has_no_arcs() -> None:
    # A subpath of lines only, then one with an arc: the null radii of the first must not
    # be mistaken for a number that is not finite.
    spec = PathFromData("M 0 0 L 10 0 L 10 10 M 20 0 A 5 5 0 0 1 30 0")
    encoded = approximate_path_one(PathJob(spec, 0.1), DEFAULT_LIMITS)
    assert isinstance(encoded, Encoded)
    body = strict_body(encoded)
    lines, arcs = body["subpaths"]
    assert (lines["stats"]["min_radius"], lines["stats"]["max_radius"]) == (None, None)
    assert {s["type"] for s in lines["segments"]} == {"line"}
    assert set(lines["segments"][0]) == {
        "type", "start", "end", "length", "u_start", "u_end", "max_deviation",
        "u_at_max_deviation", "source_segment",
    }  # fmt: skip
    assert arcs["stats"]["min_radius"] == arcs["stats"]["max_radius"] == pytest.approx(5.0)
    assert body["stats"]["min_radius"] == pytest.approx(5.0)
    only_lines = approximate_path_one(
        PathJob(PathFromData("M 0 0 L 1 1 L 2 0"), 0.1), DEFAULT_LIMITS
    )
    assert isinstance(only_lines, Encoded)
    whole = strict_body(only_lines)["stats"]
    assert (whole["min_radius"], whole["max_radius"], whole["arc_count"]) == (None, None, 0)


def test_approximate_path_one_returns_errors_as_values() -> None:
    malformed = approximate_path_one(PathJob(PathFromData("M 0 0 L 1"), 0.1), DEFAULT_LIMITS)
    assert isinstance(malformed, GeometryError)
    assert malformed.field == "path"
    assert "at character 9" in malformed.message
    degenerate = PathFromSegments(
        (
            SubpathForm((0.0, 0.0), (LineTo((1.0, 0.0)),)),
            SubpathForm((5.0, 5.0), (LineTo((6.0, 5.0)), ArcAbout((6.0, 5.0), 45.0))),
        )
    )
    bad = approximate_path_one(PathJob(degenerate, 0.1), DEFAULT_LIMITS)
    assert isinstance(bad, GeometryError)
    assert bad.field == "path.subpaths[1].segments[1]"
    floor = approximate_path_one(PathJob(PathFromData(MIXED), 1e-14), DEFAULT_LIMITS)
    assert isinstance(floor, GeometryError)
    assert floor.kind == "tolerance_floor"
    assert floor.limit is not None
    assert floor.limit > 1e-14
    capped = approximate_path_one(PathJob(PathFromData(MIXED), 0.01), Limits(max_segments=5))
    assert isinstance(capped, GeometryError)
    assert (capped.kind, capped.limit) == ("segment_limit", 5)
    inputs = approximate_path_one(PathJob(PathFromData(MIXED, 3), 0.1), DEFAULT_LIMITS)
    assert isinstance(inputs, GeometryError)
    assert (inputs.field, inputs.kind, inputs.limit) == ("path", "segment_limit", 3)
    unknown = approximate_path_one(PathJob(PathFromData(MIXED), 0.1, "greedy"), DEFAULT_LIMITS)
    assert isinstance(unknown, GeometryError)
    assert unknown.field == "strategy"
    too_large = approximate_path_one(
        PathJob(PathFromData("M 0 0 L 3e6 0"), 0.1, outputs=(("gcode", GcodeOptions(100.0)),)),
        DEFAULT_LIMITS,
    )
    assert isinstance(too_large, GcodeError)


def test_approximate_path_one_adds_one_program_for_the_whole_path() -> None:
    options = GcodeOptions(feed_rate=300.0, safe_z=2.0, cut_z=-0.5)
    encoded = approximate_path_one(
        PathJob(PathFromData(MIXED), 0.05, outputs=(("gcode", options),)), DEFAULT_LIMITS
    )
    assert isinstance(encoded, Encoded)
    body = strict_body(encoded)
    program = gcode_reader.read(body["gcode"])
    assert program.ended
    assert len(program.cuts) == body["stats"]["segment_count"]
    assert sum(m.motion == 0 and m.block.has("X") for m in program.moves) == 2
    # The program does not change the approximation.
    plain = approximate_path_one(PathJob(PathFromData(MIXED), 0.05), DEFAULT_LIMITS)
    assert isinstance(plain, Encoded)
    assert {**strict_body(plain), "gcode": body["gcode"]} == body


def test_a_chunk_keeps_the_order_and_isolates_a_bad_job() -> None:
    jobs = [
        PathJob(PathFromData(MIXED), 0.05),
        PathJob(PathFromData("M 0 0 L 1 1 X"), 0.05),
        PathJob(JSON_FORM, 0.1, "fewest-arcs"),
        PathJob(PathFromData(MIXED), 1e-14),
        PathJob(PathFromData("M 0 0 Q 5 10 10 0"), 0.01, outputs=(("gcode", GcodeOptions(50.0)),)),
        PathJob(PathFromData("M 0 0 L 3e6 0"), 0.1, outputs=(("gcode", GcodeOptions(50.0)),)),
        PathJob(PathFromData("M 0 0 L 1 0"), 0.1),
    ]
    results = approximate_path_chunk(jobs, DEFAULT_LIMITS)
    assert [type(r) for r in results] == [
        Encoded,
        GeometryError,
        Encoded,
        GeometryError,
        Encoded,
        GcodeError,
        Encoded,
    ]
    for job, result in zip(jobs, results, strict=True):
        alone = approximate_path_one(job, DEFAULT_LIMITS)
        if isinstance(result, Encoded):
            assert isinstance(alone, Encoded)
            assert result.body == alone.body
        else:
            assert str(result) == str(alone)
    assert isinstance(results[1], GeometryError)
    assert "at character 12" in results[1].message
    assert approximate_path_chunk([], DEFAULT_LIMITS) == []


def test_render_draws_every_subpath_as_an_svg() -> None:
    job = PathJob(PathFromData(MIXED), 0.05, outputs=(("svg", None),))
    document = render(job, DEFAULT_LIMITS)
    assert isinstance(document, Document)
    assert document.media_type == "image/svg+xml"
    root = ET.fromstring(document.body)
    assert root.tag == f"{SVG}svg"
    curves = [p for p in root.iter(f"{SVG}polyline") if p.get("stroke") == "black"]
    assert len(curves) == 2
    result = approximate_path(parse_path_data(MIXED), 0.05)
    arcs = result.stats.arc_count
    assert len(list(root.iter(f"{SVG}circle"))) == arcs
    legend = " ".join(t.text or "" for t in root.iter(f"{SVG}text"))
    assert f"{arcs} arcs, {result.stats.line_count} lines" in legend
    bad = render(PathJob(PathFromData("M 0 0 L"), 0.05, outputs=(("svg", None),)), DEFAULT_LIMITS)
    assert isinstance(bad, GeometryError)
    assert bad.field == "path"


def test_render_writes_the_program_when_that_is_the_output() -> None:
    job = PathJob(PathFromData(MIXED), 0.05, outputs=(("gcode", GcodeOptions(100.0)),))
    document = render(job, DEFAULT_LIMITS)
    assert isinstance(document, Document)
    assert document.media_type == "text/x-gcode"
    assert gcode_reader.read(document.body.decode()).ended


@pytest.mark.parametrize(
    "job",
    [
        PathJob(PathFromData(MIXED, 100), 0.05, "fewest-arcs", (("gcode", GcodeOptions(1.0)),)),
        PathJob(JSON_FORM, 0.1, outputs=(("svg", None),)),
    ],
    ids=["svg-data", "json-form"],
)
def test_path_jobs_and_their_results_cross_the_process_boundary(job: PathJob) -> None:
    again = pickle.loads(pickle.dumps(job))
    assert again == job
    assert again.path.build() == job.path.build()
    result = approximate_path_one(again, DEFAULT_LIMITS)
    assert isinstance(result, Encoded)
    assert pickle.loads(pickle.dumps(result)) == result
    error = approximate_path_one(again._replace(tolerance=1e-14), DEFAULT_LIMITS)
    assert isinstance(error, GeometryError)
    copy = pickle.loads(pickle.dumps(error))
    assert (copy.field, copy.kind, copy.limit, copy.message) == (
        error.field,
        error.kind,
        error.limit,
        error.message,
    )
