"""Random spirals, tolerances and options: a program is either written correctly (accepted
by rs274, within tolerance + one unit in the last place, one move per segment) or refused
with a GcodeError that names why."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

from arcspline.geometry import GeometryError, Spiral, approximate
from arcspline.outputs.gcode import MAX_COORDINATE, GcodeError, GcodeOptions, write_program
from tests.support import gcode_reader, oracle
from tests.support.rs274 import Rs274

from . import readback

spirals = st.builds(
    dict,
    start=st.tuples(st.floats(-100, 100), st.floats(-100, 100)),
    direction_deg=st.floats(-180, 180),
    turn_angle_deg=st.floats(0.01, 89.9),
    curvature_exp=st.floats(-3, 2),
    clockwise=st.booleans(),
    tolerance_exp=st.floats(-5, -1),
    strategy=st.sampled_from(["subdivide", "fewest-arcs"]),
)
precisions = st.sampled_from([("mm", 3), ("mm", 4), ("inch", 4), ("inch", 5), ("mm", 6)])


@settings(
    max_examples=20,
    deadline=None,
    suppress_health_check=[HealthCheck.function_scoped_fixture, HealthCheck.filter_too_much],
)
@given(case=spirals, precision=precisions, arc_format=st.sampled_from(["ij", "r"]))
def test_random_programs_are_correct_or_refused(
    rs274: Rs274, case: dict, precision: tuple[str, int], arc_format: str
) -> None:
    angle = math.radians(case["direction_deg"])
    curvature = 10 ** case["curvature_exp"] * (-1 if case["clockwise"] else 1)
    spiral = Spiral.from_parameters(
        start=case["start"],
        start_tangent=(math.cos(angle), math.sin(angle)),
        turn_angle_deg=case["turn_angle_deg"],
        end_curvature=curvature,
    )
    try:
        spline = approximate(
            spiral, spiral.chord * 10 ** case["tolerance_exp"], strategy=case["strategy"]
        )
    except GeometryError:
        assume(False)
    units, decimals = precision
    options = GcodeOptions(feed_rate=900, units=units, decimals=decimals, arc_format=arc_format)  # type: ignore[arg-type]
    if np.max(np.abs(spiral.control_points)) >= MAX_COORDINATE:
        # The only refusal these inputs may meet: coordinates too large to write.
        with pytest.raises(GcodeError) as caught:
            write_program(spline, spiral, options)
        assert caught.value.field == "spiral"
        return
    text = write_program(spline, spiral, options)
    program = gcode_reader.read(text)
    assert len(program.cuts) == len(spline)
    q = 10.0**-decimals
    for move in program.cuts:
        if move.motion in (2, 3):
            assert move.r_start is not None
            assert move.r_end is not None
            assert move.sweep_rad is not None
            assert abs(move.r_end - move.r_start) <= q * (1 + 1e-6)
            assert abs(move.sweep_rad) < math.pi
    measured = readback.deviation(spiral, spline, program)
    slack = oracle.rounding_slack(np.asarray(spiral.control_points))
    assert measured <= spline.tolerance + q + slack
    verdict = rs274.run(text)
    assert verdict.accepted, verdict.describe()
