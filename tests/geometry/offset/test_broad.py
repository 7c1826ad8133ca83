"""The broad phase finds exactly the overlapping boxes, each pair once (against brute force)."""

from __future__ import annotations

import numpy as np
import pytest

from arcspline.geometry.offset.broad import overlapping


def _boxes(rng: np.random.Generator, n: int) -> np.ndarray:
    lo = rng.uniform(0, 100, (n, 2))
    size = rng.exponential(1.0, (n, 2))
    size += (rng.uniform(0, 1, (n, 1)) < 0.05) * rng.exponential(90.0, (n, 2))  # a few long
    return np.hstack([lo, lo + size])


def _overlap(a: np.ndarray, b: np.ndarray) -> bool:
    return bool(a[0] <= b[2] and b[0] <= a[2] and a[1] <= b[3] and b[1] <= a[3])


@pytest.mark.parametrize("seed", range(8))
def test_pairs_against_brute_force(seed: int) -> None:
    rng = np.random.default_rng(seed)
    a, b = _boxes(rng, int(rng.integers(1, 250))), _boxes(rng, int(rng.integers(1, 250)))
    margin = float(rng.uniform(0, 6))
    i, j = overlapping(a, b, margin)
    grown = a + np.array([-margin, -margin, margin, margin])
    truth = {(x, y) for x in range(len(a)) for y in range(len(b)) if _overlap(grown[x], b[y])}
    got = list(zip(i.tolist(), j.tolist(), strict=True))
    assert len(got) == len(set(got))
    assert set(got) == truth
    i, j = overlapping(a)
    truth = {(x, y) for x in range(len(a)) for y in range(x + 1, len(a)) if _overlap(a[x], a[y])}
    got = list(zip(i.tolist(), j.tolist(), strict=True))
    assert len(got) == len(set(got))
    assert set(got) == truth


def test_empty_sets() -> None:
    i, j = overlapping(np.zeros((0, 4)), np.ones((3, 4)))
    assert len(i) == len(j) == 0
