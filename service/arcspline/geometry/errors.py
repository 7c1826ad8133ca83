"""The one error type of the geometry core."""

from __future__ import annotations

from typing import Literal

ErrorKind = Literal[
    "invalid_input", "tolerance_floor", "segment_limit", "precision", "crossing", "tool_too_large"
]


class GeometryError(ValueError):
    """An input outside the method's domain, or a limit that the input would exceed.

    ``field`` names the offending input by the core's parameter name (``turn_angle_deg``,
    ``end_curvature``, ``start_tangent``, ``control_points``, ``tolerance``, ...); ``kind``
    says which family of problem it is, so callers can count and map errors without parsing
    text; ``limit`` is the bound that was crossed, where there is one.
    """

    def __init__(
        self,
        field: str,
        message: str,
        *,
        kind: ErrorKind = "invalid_input",
        limit: float | None = None,
    ) -> None:
        super().__init__(f"{field}: {message}")
        self.field = field
        self.message = message
        self.kind: ErrorKind = kind
        self.limit = limit

    def __reduce__(self) -> tuple[object, ...]:
        # Keyword-only arguments do not survive the default pickling, and these errors
        # cross the process-pool boundary.
        return (_rebuild, (self.field, self.message, self.kind, self.limit))


def _rebuild(field: str, message: str, kind: ErrorKind, limit: float | None) -> GeometryError:
    return GeometryError(field, message, kind=kind, limit=limit)
