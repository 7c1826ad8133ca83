"""One spiral's arc spline assembled in floats equals the batch assembly bit for bit, and the
cases it leaves to the batch assembly are left to it."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import assume, given
from hypothesis import strategies as st

from arcspline.geometry import Spiral, canonical, min_tolerance
from arcspline.geometry.approximate import PLACEMENT_SCREEN_ULPS
from arcspline.geometry.assemble import Frames, segment_columns, spiral_lengths, splines
from arcspline.geometry.assemble_one import MAX_BIARCS, assemble_one, numpy_sum
from arcspline.geometry.subdivide_one import kept, subdivide_one
from arcspline.geometry.types import ArcSpline, SegmentColumns
from tests.geometry.test_properties import PROPERTY, relative_tolerances, spirals


def _rows(spiral: Spiral, tolerance: float) -> list[tuple[float, ...]] | None:
    k, m = canonical.coefficients(np.array([spiral.turn_angle_rad]))
    return subdivide_one(float(k[0]), float(m[0]), tolerance / spiral.a, 5_000)


def _both(spiral: Spiral, tolerance: float) -> tuple[ArcSpline, ArcSpline | None]:
    """The batch assembly and the float one, of the same kept biarcs."""
    scale = np.array([spiral.a])
    k, m = canonical.coefficients(np.array([spiral.turn_angle_rad]))
    rows = _rows(spiral, tolerance)
    assert rows is not None
    lengths = spiral_lengths(k, m, scale)
    columns = segment_columns(kept(rows), k, m, Frames.of([spiral]))
    (batch,) = splines(
        columns, np.zeros(2 * len(rows), dtype=np.intp), lengths, np.array([tolerance]), "s"
    )
    one = assemble_one(
        rows,
        spiral,
        float(k[0]),
        float(m[0]),
        tolerance,
        float(lengths[0]),
        "s",
        PLACEMENT_SCREEN_ULPS,
    )
    return batch, one


def _assert_identical(batch: ArcSpline, one: ArcSpline | None) -> None:
    assert one is not None
    for name in batch.columns.__slots__:
        a, b = getattr(batch.columns, name), getattr(one.columns, name)
        assert a.shape == b.shape, name
        assert a.tobytes() == b.tobytes(), name
    assert one.stats == batch.stats
    assert (one.tolerance, one.strategy) == (batch.tolerance, batch.strategy)
    # The plain values the float assembly keeps are those the batch's columns give.
    assert one.values() == batch.values()


PAPER = Spiral.from_parameters((1.5, 3.0), (1.0, 0.0), 51.34, 0.41574)


@pytest.mark.parametrize("tolerance", [0.1, 1e-3, 1e-5])
@pytest.mark.parametrize(
    "spiral",
    [
        PAPER,
        Spiral.from_parameters((10.0, -5.0), (0.3, -1.0), 30.0, -2.0),  # clockwise
        Spiral.from_parameters((1e6, -1e6), (-1.0, 2.0), 80.0, 1e-3),  # far and large
    ],
    ids=["paper", "clockwise", "far"],
)
def test_known_spirals_are_bit_identical(spiral: Spiral, tolerance: float) -> None:
    _assert_identical(*_both(spiral, tolerance * spiral.chord))


@PROPERTY
@given(spiral=spirals(), relative=relative_tolerances)
def test_random_spirals_are_bit_identical(spiral: Spiral, relative: float) -> None:
    tolerance = relative * spiral.chord
    assume(_rows(spiral, tolerance) is not None)  # not too many pieces to subdivide in floats
    batch, one = _both(spiral, tolerance)
    if len(batch) > 2 * MAX_BIARCS or _flat(batch) or _screened(batch, tolerance):
        assert one is None
    else:
        _assert_identical(batch, one)


def _flat(spline: ArcSpline) -> bool:
    return not spline.columns.is_arc.all()


def _screened(spline: ArcSpline, tolerance: float) -> bool:
    """Whether an arc's rounding could matter (``approximate._unplaceable_rows``' screen)."""
    c = spline.columns
    size = np.abs(c.center).max(axis=1) + c.radius
    return bool((c.max_deviation + PLACEMENT_SCREEN_ULPS * 2**-52 * size > tolerance).any())


def test_many_arcs_are_left_to_the_batch_assembly() -> None:
    batch, one = _both(PAPER, 1e-7 * PAPER.chord)
    assert len(batch) > 2 * MAX_BIARCS
    assert one is None


def test_a_numerically_flat_arc_is_left_to_the_batch_assembly() -> None:
    straight = Spiral.from_parameters((0.0, 0.0), (1.0, 1.0), 1e-9, 1e-4)
    batch, one = _both(straight, 1e-6 * straight.chord)
    assert _flat(batch)  # lines where arcs are flat
    assert one is None


def test_an_arc_whose_placement_needs_measuring_is_left_to_the_batch_assembly() -> None:
    # A small spiral far out, at a tolerance just above the floor: 64 ulps of the centres'
    # coordinates no longer fit beside the deviations.
    far = Spiral.from_parameters((1e9, 1e9), (1.0, 0.0), 45.0, 1.0)
    tolerance = 3e-5
    assert tolerance > min_tolerance(far)
    batch, one = _both(far, tolerance)
    assert _screened(batch, tolerance)
    assert one is None


@given(
    st.lists(
        st.floats(min_value=0.0, max_value=1e6, allow_subnormal=False)
        | st.floats(min_value=-1e-3, max_value=1e-3),
        min_size=1,
        max_size=300,
    )
)
def test_numpy_sum_adds_as_numpy_s_reduceat(values: list[float]) -> None:
    array = np.array(values)
    expected = float(np.add.reduceat(array, np.zeros(1, dtype=np.intp))[0])
    assert numpy_sum(values) == expected


def test_columns_and_values_convert_both_ways() -> None:
    batch, _ = _both(PAPER, 1e-3)
    first = batch.values()[0]
    line = (False, *first[1:4], float("inf"), first[5], 0.0, *first[7:])
    values = [line, *batch.values()[1:]]
    columns = SegmentColumns.from_values(values)
    assert columns.values() == values
    assert columns.is_arc.dtype == np.bool_
    assert columns.start.shape == (len(values), 2)
    empty = SegmentColumns.from_values([])
    assert empty.center.shape == (0, 2)
    assert empty.values() == []


def test_numpy_sum_adds_as_numpy_s_reduceat_at_every_length() -> None:
    rng = np.random.default_rng(7)
    for n in range(1, 301):  # past the pairwise block of 128, where numpy halves
        array = rng.uniform(0.0, 1.0, n) * 10.0 ** rng.uniform(-8.0, 3.0, n)
        expected = float(np.add.reduceat(array, np.zeros(1, dtype=np.intp))[0])
        assert numpy_sum(array.tolist()) == expected, n


def test_a_batch_spline_keeps_no_plain_values() -> None:
    # A batch's splines live until all are encoded: values kept by each would hold millions
    # of Python objects for the collector to walk (the batch endpoint ran 1.5x slower).
    batch, one = _both(PAPER, 1e-3)
    assert batch.values() == batch.values()
    assert batch.values() is not batch.values()
    assert one is not None
    assert one.values() is one.values()  # the float assembly's own storage


def test_a_segments_end_parameter_is_read_where_it_is_kept() -> None:
    batch, one = _both(PAPER, 1e-3)
    assert one is not None
    for spline in (batch, one):
        assert [spline.u_end(i) for i in range(len(spline))] == spline.columns.u_end.tolist()
