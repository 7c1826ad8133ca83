"""Read an ``ApproximateResponse`` body back into objects the independent oracle accepts."""

from __future__ import annotations

import math
from dataclasses import dataclass
from types import SimpleNamespace
from typing import Any

import numpy as np

from tests.support import oracle


@dataclass(frozen=True)
class JsonSpline:
    """The shape ``support.oracle.check`` reads: segments in order, stats, tolerance."""

    segments: tuple[Any, ...]
    stats: Any
    tolerance: float

    def __len__(self) -> int:
        return len(self.segments)


def spline_from_json(body: dict[str, Any]) -> JsonSpline:
    segments = tuple(
        SimpleNamespace(
            **{
                key: tuple(value) if isinstance(value, list) else value
                for key, value in segment.items()
            }
        )
        for segment in body["segments"]
    )
    stats = SimpleNamespace(**body["stats"])
    return JsonSpline(segments=segments, stats=stats, tolerance=body["stats"]["tolerance"])


def control_points(spiral: dict[str, Any]) -> np.ndarray:
    """The four control points of a request's spiral: as given, or from the paper's §1
    formulas in the oracle's exact arithmetic (:func:`oracle.paper_control_points`)::

    a = 25·tan θ / (54·|c|·cos θ),  b = 5·tan θ / (9·|c|),
    B1 = B0 + a·T0,  B2 = B1 + a·T0,  B3 = B2 + b·T1  (T1: T0 turned by ±θ).
    """
    if "control_points" in spiral:
        return np.array(spiral["control_points"], dtype=np.float64)
    return oracle.paper_control_points(
        spiral["start"], spiral["start_tangent"], spiral["turn_angle_deg"], spiral["end_curvature"]
    )


def same_json(a: Any, b: Any, rel: float = 1e-12) -> bool:
    """Equal JSON values, numbers to ``rel`` (the core's batched path may round differently)."""
    if isinstance(a, dict) and isinstance(b, dict):
        return a.keys() == b.keys() and all(same_json(a[k], b[k], rel) for k in a)
    if isinstance(a, list) and isinstance(b, list):
        return len(a) == len(b) and all(same_json(x, y, rel) for x, y in zip(a, b, strict=True))
    if isinstance(a, float) or isinstance(b, float):
        return (
            isinstance(a, int | float)
            and isinstance(b, int | float)
            and math.isclose(a, b, rel_tol=rel, abs_tol=1e-300)
        )
    return bool(a == b)
