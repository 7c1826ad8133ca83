"""The loop every strategy shares (``fit/batch.pyx``): frames in, world rows out."""

from __future__ import annotations

import math

import numpy as np
import pytest

from arcspline.geometry import COLUMN, STRATEGIES, Spiral, approximate
from arcspline.geometry.fit.batch import FIELDS, FRAME_FIELDS, frame_table

SPIRALS = [
    Spiral.from_parameters((1.5, 3.0), (1.0, 0.0), 51.34, 0.41574),
    Spiral.from_parameters((1.5, 3.0), (1.0, 0.0), 51.34, -0.41574),
    Spiral.from_parameters((-7e3, 2e4), (-0.3, 0.9), 80.0, 3e-3),
    Spiral.from_parameters((0.25, -0.5), (0.0, -1.0), 5.0, 40.0),
]


@pytest.mark.parametrize("strategy", sorted(STRATEGIES))
@pytest.mark.parametrize("spiral", SPIRALS, ids=lambda s: f"theta={s.turn_angle_deg:.4g}")
def test_joints_are_shared_exactly_and_the_ends_are_the_spirals(
    spiral: Spiral, strategy: str
) -> None:
    table = approximate(spiral, 1e-4 * spiral.chord, strategy).table
    start = table[:, [COLUMN["start_x"], COLUMN["start_y"]]]
    end = table[:, [COLUMN["end_x"], COLUMN["end_y"]]]
    # u = 0 is B0 and u = 1 the stored B3, to the bit; each joint is one pair of numbers.
    assert tuple(start[0]) == tuple(spiral.start)
    assert tuple(end[-1]) == tuple(spiral.end_point)
    np.testing.assert_array_equal(start[1:], end[:-1])
    np.testing.assert_array_equal(table[1:, COLUMN["u_start"]], table[:-1, COLUMN["u_end"]])


def test_a_spirals_frame_holds_what_the_kernels_read() -> None:
    spiral = SPIRALS[2]
    frame = dict(zip(FRAME_FIELDS, spiral.frame, strict=True))
    assert (frame["x0"], frame["y0"]) == spiral.start
    assert (frame["cos_phi"], frame["sin_phi"]) == spiral.start_tangent
    assert frame["scale"] == spiral.a
    assert frame["mirror"] == spiral.turn_direction
    theta = spiral.turn_angle_rad
    canonical = (3.0, 0.0, 1.2 * math.cos(theta) ** 2 - 1.0, 0.0, 0.0, 0.0)
    coefficients = tuple(frame[f] for f in ("x1", "x2", "x3", "y1", "y2"))
    assert (*coefficients, frame["w1"]) == canonical
    assert frame["y3"] == pytest.approx(1.2 * math.cos(theta) * math.sin(theta), rel=1e-15)
    assert frame["w2"] == 0.0
    assert (frame["end_x"], frame["end_y"]) == spiral.end_point
    assert (frame["chord"], frame["coordinate_scale"]) == (spiral.chord, spiral.coordinate_scale)
    assert set(COLUMN) == set(FIELDS)


def test_tables_of_the_wrong_shape_are_refused() -> None:
    frames = frame_table([s.frame for s in SPIRALS])
    fit = STRATEGIES["subdivide"]
    with pytest.raises(ValueError, match="frames"):
        fit(frames[:, :5].copy(), np.full(4, 0.01), 100, 1e-10)
    with pytest.raises(ValueError, match="tolerances"):
        fit(frames, np.full(3, 0.01), 100, 1e-10)
    with pytest.raises(ValueError, match="numbers"):
        frame_table([(1.0, 2.0)])


def test_lines_where_arcs_would_be_numerically_flat() -> None:
    # A turn of 1e-9°: every arc's sweep is below 1e-10 rad, so each is its chord.
    flat = Spiral.from_parameters((0.0, 0.0), (1.0, 1.0), 1e-9, 1e-4)
    spline = approximate(flat, 1e-6 * flat.chord)
    table = spline.table
    assert spline.stats.line_count == len(table) > 0
    assert np.all(table[:, COLUMN["is_arc"]] == 0.0)
    assert np.all(np.isinf(table[:, COLUMN["radius"]]))
    chord = np.hypot(
        table[:, COLUMN["end_x"]] - table[:, COLUMN["start_x"]],
        table[:, COLUMN["end_y"]] - table[:, COLUMN["start_y"]],
    )
    np.testing.assert_allclose(table[:, COLUMN["length"]], chord, rtol=1e-15)
    assert spline.stats.min_radius is None
    assert math.isclose(spline.stats.spline_length, float(chord.sum()), rel_tol=1e-12)


@pytest.mark.parametrize("strategy", sorted(STRATEGIES))
def test_the_tables_hold_exactly_the_rows_the_spirals_own(strategy: str) -> None:
    # Enough arcs for several tables, with refusals among them (a bad tolerance, one below
    # the floor) that must leave no rows behind.
    spirals = SPIRALS * 25
    tolerances = np.array([1e-7 * s.chord for s in spirals])
    tolerances[7], tolerances[11] = math.nan, 1e-12 * spirals[11].chord
    tables, where, _, status, _ = STRATEGIES[strategy](
        frame_table([s.frame for s in spirals]), tolerances, 1000, 1e-10
    )
    assert len(tables) > 1
    assert status[7] != 0
    assert status[11] != 0
    owned = np.zeros(len(tables), dtype=np.int64)
    for i in np.flatnonzero(status == 0):
        block, begin, end = where[i]
        assert begin == owned[block]  # rows follow one another, no gaps
        owned[block] = end
    assert [len(t) for t in tables] == owned.tolist()
    assert all(np.isfinite(t[:, COLUMN["length"]]).all() for t in tables)
