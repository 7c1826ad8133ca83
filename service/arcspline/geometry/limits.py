"""Bounds that keep every request finite, and the smallest tolerance a curve allows."""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

from .fit.batch import tolerance_floor

if TYPE_CHECKING:
    from .curves import Curve


#: The largest segment limit the kernels take (a C ``int``).
MAX_SEGMENTS = 2**31 - 1


@dataclass(frozen=True, slots=True)
class Limits:
    """``max_segments`` caps the segments of one arc spline. ``min_relative_tolerance`` is
    the smallest tolerance accepted, as a fraction of the curve's chord; below it (or below
    what double precision can represent at the curve's coordinates) the core refuses rather
    than return an answer it cannot vouch for."""

    max_segments: int = 10_000
    min_relative_tolerance: float = 1e-10

    def __post_init__(self) -> None:
        count = self.max_segments
        if isinstance(count, bool) or not isinstance(count, int) or not 1 <= count <= MAX_SEGMENTS:
            raise ValueError(f"max_segments must be an integer in [1, {MAX_SEGMENTS}]")
        if not 0.0 < self.min_relative_tolerance < 1.0:
            raise ValueError("min_relative_tolerance must lie strictly between 0 and 1")


DEFAULT_LIMITS = Limits()


def min_tolerance(curve: Curve, limits: Limits = DEFAULT_LIMITS) -> float:
    """The smallest tolerance the core accepts for ``curve``: the larger of
    ``limits.min_relative_tolerance × chord`` and four rounding margins (32 ulps of the
    coordinate scale plus chord each), so that at least three quarters of the tolerance is
    left for the approximation itself (docs/method.md §8)."""
    return tolerance_floor(curve.chord, curve.coordinate_scale, limits.min_relative_tolerance)
