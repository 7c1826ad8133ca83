"""Curve types: one module each (today the Walton–Meek spiral, ``spiral.py``).

A curve is an immutable value that the rest of the package uses through :class:`Curve`:
the fitting kernels read its :attr:`~Curve.frame`; the G-code planner measures its pieces
against lines and circles; the preview draws it. A request gives a curve as a
:class:`CurveSpec`, which builds it.
"""

from __future__ import annotations

from typing import Protocol

from ..spline import FloatArray, Point
from .spiral import Spiral, SpiralFromControlPoints, SpiralFromParameters


class Curve(Protocol):
    """What the package needs of a curve (the parameter ``u`` runs over :attr:`domain`:
    ``[0, 1]`` for a spiral, ``[0, pieces]`` for a subpath of a path)."""

    @property
    def frame(self) -> tuple[float, ...]:
        """The kernels' input row (``fit.batch.FRAME_FIELDS``)."""

    @property
    def domain(self) -> tuple[float, float]:
        """The range of the parameter ``u``."""

    @property
    def start(self) -> Point:
        """The point at ``u = 0``, exactly as given."""

    @property
    def end_point(self) -> Point:
        """The point at ``u = 1``, exactly as stored."""

    @property
    def chord(self) -> float:
        """Distance between the end points: the reference of relative tolerances."""

    @property
    def coordinate_scale(self) -> float:
        """The largest coordinate magnitude that defines the curve (for rounding margins)."""

    def eval(self, u: float | FloatArray) -> FloatArray:
        """Points at ``u``: shape ``(..., 2)`` for ``u`` of shape ``(...)``."""

    def line_deviations(
        self, u0: FloatArray, u1: FloatArray, start: FloatArray, end: FloatArray
    ) -> FloatArray:
        """Exact largest distance from each piece ``[u0, u1]`` to the line ``start→end``."""

    def circle_deviations(
        self,
        u0: FloatArray,
        u1: FloatArray,
        centre: FloatArray,
        r_start: FloatArray,
        r_end: FloatArray,
    ) -> FloatArray:
        """Exact largest distance from each piece ``[u0, u1]`` to the farther of two circles
        about ``centre``."""


class CurveSpec(Protocol):
    """A curve as a request gives it: a small picklable value that builds (and validates)
    the curve where it is needed, in a worker."""

    def build(self) -> Curve:
        """The curve; raises :class:`~arcspline.geometry.GeometryError` if it is invalid."""


__all__ = ["Curve", "CurveSpec", "Spiral", "SpiralFromControlPoints", "SpiralFromParameters"]
