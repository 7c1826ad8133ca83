"""GcodeOptions validation and GcodeError: every bad option is refused, naming its field."""

from __future__ import annotations

import math
import pickle
from typing import Any

import pytest

from arcspline.geometry import ArcSpline, Spiral, approximate
from arcspline.outputs.gcode import (
    DEFAULT_DECIMALS,
    MAX_DECIMALS,
    MIN_DECIMALS,
    GcodeError,
    GcodeOptions,
    write_program,
)

from .cases import spiral, spline


def test_defaults_resolve_per_units() -> None:
    mm = GcodeOptions(feed_rate=600)
    inch = GcodeOptions(feed_rate=20, units="inch")
    assert (mm.resolved_decimals, inch.resolved_decimals) == (4, 5)
    assert DEFAULT_DECIMALS == {"mm": 4, "inch": 5}
    assert min(DEFAULT_DECIMALS.values()) >= MIN_DECIMALS
    assert max(DEFAULT_DECIMALS.values()) <= MAX_DECIMALS
    assert mm.decimals is None
    assert mm.plunge_feed_rate is None
    z = GcodeOptions(feed_rate=600, safe_z=5, cut_z=-1)
    assert z.resolved_plunge_feed_rate == 600
    assert (
        GcodeOptions(
            feed_rate=600, safe_z=5, cut_z=-1, plunge_feed_rate=100
        ).resolved_plunge_feed_rate
        == 100
    )


BAD: list[tuple[str, dict[str, Any]]] = [
    ("feed_rate", {"feed_rate": 0}),
    ("feed_rate", {"feed_rate": -5.0}),
    ("feed_rate", {"feed_rate": math.nan}),
    ("feed_rate", {"feed_rate": math.inf}),
    ("feed_rate", {"feed_rate": True}),
    ("feed_rate", {"feed_rate": "fast"}),
    ("feed_rate", {"feed_rate": 1e-5}),  # rounds to F0 at 4 decimals
    ("feed_rate", {"feed_rate": 2e6}),
    ("units", {"units": "cm"}),
    ("decimals", {"decimals": MIN_DECIMALS - 1}),
    ("decimals", {"decimals": MAX_DECIMALS + 1}),
    ("decimals", {"decimals": 3.5}),
    ("decimals", {"decimals": True}),
    ("arc_format", {"arc_format": "ijk"}),
    ("line_numbers", {"line_numbers": "yes"}),
    ("comments", {"comments": 1}),
    ("cut_z", {"safe_z": 5.0}),
    ("safe_z", {"cut_z": -1.0}),
    ("safe_z", {"safe_z": -1.0, "cut_z": 0.0}),
    ("safe_z", {"safe_z": 1.0, "cut_z": 1.0}),
    ("safe_z", {"safe_z": 1.00001, "cut_z": 1.0, "decimals": 3}),  # equal once rounded
    ("safe_z", {"safe_z": math.inf, "cut_z": 0.0}),
    ("cut_z", {"safe_z": 1.0, "cut_z": math.nan}),
    ("plunge_feed_rate", {"plunge_feed_rate": 100.0}),
    ("plunge_feed_rate", {"safe_z": 5.0, "cut_z": 0.0, "plunge_feed_rate": 0.0}),
    ("plunge_feed_rate", {"safe_z": 5.0, "cut_z": 0.0, "plunge_feed_rate": math.nan}),
    ("min_arc_length", {"min_arc_length": 0.0}),
    ("min_arc_length", {"min_arc_length": -1.0}),
    ("max_radius", {"max_radius": math.inf}),
    ("max_radius", {"max_radius": math.nan}),
]


@pytest.mark.parametrize(("field", "overrides"), BAD, ids=lambda v: str(v))
def test_bad_option_is_refused_naming_its_field(field: str, overrides: dict[str, Any]) -> None:
    with pytest.raises(GcodeError) as caught:
        GcodeOptions(**{"feed_rate": 600.0, **overrides})
    assert caught.value.field == field
    assert caught.value.message
    assert str(caught.value).startswith(f"{field}: ")
    assert isinstance(caught.value, ValueError)


def test_error_survives_pickling() -> None:
    error = GcodeError("decimals", "too few for this tolerance")
    copy = pickle.loads(pickle.dumps(error))
    assert type(copy) is GcodeError
    assert (copy.field, copy.message, str(copy)) == (error.field, error.message, str(error))


def test_spiral_beyond_the_coordinate_bound_is_refused() -> None:
    far = Spiral.from_parameters(
        start=(2e6, 0.0), start_tangent=(1.0, 0.0), turn_angle_deg=30.0, end_curvature=0.5
    )
    with pytest.raises(GcodeError) as caught:
        write_program(approximate(far, 1e-2), far, GcodeOptions(feed_rate=600))
    assert caught.value.field == "spiral"


def test_spline_that_breaks_its_stated_tolerance_is_refused_not_written() -> None:
    # A real approximation labelled with a tolerance it does not keep: the writer measures
    # every block itself and will not vouch for the program.
    real = spline("paper")
    mislabelled = ArcSpline(real.table, real.stats, real.tolerance / 100, real.strategy)
    with pytest.raises(GcodeError) as caught:
        write_program(mislabelled, spiral("paper"), GcodeOptions(feed_rate=600, decimals=6))
    assert caught.value.field == "decimals"
    assert "deviate" in caught.value.message
