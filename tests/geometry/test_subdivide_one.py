"""The one-spiral subdivision in floats keeps exactly the biarcs of the batch subdivision.

``subdivide_one`` is an accelerator: it must return the batch path's kept biarcs bit for bit
(same pieces, same numbers, same order), or ``None`` where the batch path has to decide.
(``tests/geometry/test_properties.py`` holds whole results alone and in a batch equal.)
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from arcspline.geometry import canonical, roots
from arcspline.geometry import subdivide_one as subdivide_one_module
from arcspline.geometry.subdivide import MAX_LEVELS, Kept, subdivide
from arcspline.geometry.subdivide_one import MAX_PIECES, kept, subdivide_one
from tests.geometry.test_properties import PROPERTY

PAPER_THETA_DEG = 51.34
#: The paper's size a for its example (§1): tolerances below are in units of a.
PAPER_A = 25 * math.tan(math.radians(51.34)) / (54 * 0.41574 * math.cos(math.radians(51.34)))


def _both(theta_deg: float, tolerance: float, max_biarcs: int = 5_000) -> tuple[Kept, Kept | None]:
    k, m = canonical.coefficients(np.array([math.radians(theta_deg)]))
    batch = subdivide(k, m, np.array([tolerance]), max_biarcs)
    rows = subdivide_one(float(k[0]), float(m[0]), tolerance, max_biarcs)
    return batch.kept, None if rows is None else kept(rows)


def _assert_identical(batch: Kept, one: Kept | None) -> None:
    assert one is not None
    assert np.array_equal(batch.spiral, one.spiral)
    for group in ("biarcs", "deviation"):
        left, right = getattr(batch, group), getattr(one, group)
        for name, a, b in zip(left._fields, left, right, strict=True):
            # Bit for bit: equal as arrays and with the same bytes (signed zeros included).
            assert a.tobytes() == b.tobytes(), f"{group}.{name}"


@pytest.mark.parametrize("tolerance", [0.1, 0.01, 1e-3, 1e-4, 1e-5])
def test_table1_tolerances_are_bit_identical(tolerance: float) -> None:
    batch, one = _both(PAPER_THETA_DEG, tolerance / PAPER_A)
    _assert_identical(batch, one)
    assert one is not None
    assert 2 * len(one.spiral) == {0.1: 4, 0.01: 8, 1e-3: 12, 1e-4: 26, 1e-5: 54}[tolerance]


@pytest.mark.parametrize(
    ("theta_deg", "tolerance"),
    [
        (1e-6, 1e-9),  # nearly straight
        (0.01, 1e-10),
        (30.0, 1e-7),
        (89.0, 1e-3),
        (89.99, 1e-6),  # the first piece's cubic has a near-double root: safeguarded Newton
        (89.9999, 1e-9),
    ],
)
def test_extremes_are_bit_identical(theta_deg: float, tolerance: float) -> None:
    batch, one = _both(theta_deg, tolerance)
    _assert_identical(batch, one)


def test_a_root_the_plain_steps_miss_comes_from_the_array_version(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    # Near θ = 90° the cubic of the piece [0, 1] has a near-double root: the float version
    # hands that one root to the safeguarded array iteration, and still agrees bit for bit.
    handed = []
    original = roots.one_root

    def counting(*args: object) -> float:
        handed.append(args)
        return original(*args)  # type: ignore[arg-type]

    monkeypatch.setattr(subdivide_one_module, "one_root", counting)
    batch, one = _both(89.99, 1e-6)
    assert handed
    _assert_identical(batch, one)


def test_the_segment_limit_is_left_to_the_batch_path() -> None:
    batch_kept, one = _both(PAPER_THETA_DEG, 1e-5 / PAPER_A, max_biarcs=26)
    k, m = canonical.coefficients(np.array([math.radians(PAPER_THETA_DEG)]))
    assert subdivide(k, m, np.array([1e-5 / PAPER_A]), 26).failure == ["segment_limit"]
    assert one is None
    # Exactly at the limit both finish, with the same 27 biarcs.
    batch_kept, one = _both(PAPER_THETA_DEG, 1e-5 / PAPER_A, max_biarcs=27)
    _assert_identical(batch_kept, one)


def test_many_pieces_are_left_to_the_batch_path() -> None:
    # Far more pieces than MAX_PIECES: the numpy levels are faster. (The cap also keeps every
    # piece here shallower than the batch path's level cap.)
    assert MAX_PIECES < MAX_LEVELS
    batch, one = _both(PAPER_THETA_DEG, 1e-12)
    assert 2 * len(batch.spiral) > MAX_PIECES
    assert one is None
    batch, one = _both(PAPER_THETA_DEG, 1e-7)
    assert MAX_PIECES / 4 < 2 * len(batch.spiral) - 1 <= MAX_PIECES
    _assert_identical(batch, one)


def test_a_piece_too_short_to_split_is_left_to_the_batch_path() -> None:
    # A nearly straight spiral at a tolerance of 1e-16 of its size: some piece's split point
    # comes within a few ulps of its end.
    k, m = canonical.coefficients(np.array([math.radians(0.01)]))
    assert subdivide(k, m, np.array([1e-16]), 20_000).failure == ["precision"]
    assert subdivide_one(float(k[0]), float(m[0]), 1e-16, 20_000) is None


@pytest.mark.parametrize(("k", "m"), [(math.nan, 0.5), (0.2, math.inf)])
def test_non_finite_numbers_are_kept_as_the_batch_path_keeps_them(k: float, m: float) -> None:
    # (The core refuses such results; here only the agreement of the two paths is at stake.)
    rows = subdivide_one(k, m, 1e-3, 100)
    with np.errstate(all="ignore"):
        batch = subdivide(np.array([k]), np.array([m]), np.array([1e-3]), 100)
    assert rows is not None
    assert not np.isfinite(np.array(rows)).all()
    _assert_identical(batch.kept, kept(rows))


@PROPERTY
@given(
    theta_deg=st.floats(1e-4, 89.999),
    tolerance=st.floats(-11.0, 0.0).map(lambda e: 10**e),
)
def test_random_spirals_are_bit_identical(theta_deg: float, tolerance: float) -> None:
    batch, one = _both(theta_deg, tolerance)
    if 2 * len(batch.spiral) - 1 > MAX_PIECES:  # pieces looked at: each split adds two
        assert one is None
    else:
        _assert_identical(batch, one)
