"""Read an ``ApproximateResponse`` body back into objects the independent oracle accepts."""

from __future__ import annotations

import math
from dataclasses import dataclass
from types import SimpleNamespace
from typing import Any

import numpy as np


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
    """The four control points of a request's spiral, from the paper's §1 formulas::

    a = 25·tan θ / (54·|c|·cos θ),  b = 5·tan θ / (9·|c|),
    B1 = B0 + a·T0,  B2 = B1 + a·T0,  B3 = B2 + b·T1  (T1: T0 turned by ±θ).
    """
    if "control_points" in spiral:
        return np.array(spiral["control_points"], dtype=np.float64)
    theta = math.radians(spiral["turn_angle_deg"])
    c = spiral["end_curvature"]
    a = 25 * math.tan(theta) / (54 * abs(c) * math.cos(theta))
    b = 5 * math.tan(theta) / (9 * abs(c))
    t0 = np.array(spiral["start_tangent"], dtype=np.float64)
    t0 /= np.hypot(*t0)
    phi = math.copysign(theta, c)
    t1 = np.array([[math.cos(phi), -math.sin(phi)], [math.sin(phi), math.cos(phi)]]) @ t0
    b0 = np.array(spiral["start"], dtype=np.float64)
    return np.array([b0, b0 + a * t0, b0 + 2 * a * t0, b0 + 2 * a * t0 + b * t1])


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
