"""The cubic Bézier spiral of Walton & Meek (1996) (docs/method.md §1).

Five parameters define it: start point ``B0``, unit start tangent ``T0``, turn angle
``0 < θ < 90°`` and end curvature ``c ≠ 0`` (``c < 0`` turns clockwise: the mirror image)::

    a = 25·tan θ / (54·|c|·cos θ)        b = 5·tan θ / (9·|c|)
    B1 = B0 + a·T0,   B2 = B1 + a·T0,   B3 = B2 + b·T1

Up to a similarity (translate ``B0`` to the origin, rotate ``T0`` onto +x, mirror if
``c < 0``, divide by ``a``) every such spiral is the *canonical* spiral of its turn angle::

    Q(u) = (3u + k·u³, m·u³),   k = 1.2·cos²θ − 1,   m = 1.2·cos θ·sin θ

which is the curve piece the kernels fit (``curves/piece.pxd``); this module
holds the spiral as the user gave it, evaluates it in world coordinates and maps canonical
results back.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from functools import cached_property
from typing import NamedTuple

import numpy as np

from ..errors import GeometryError
from ..fit.batch import PIECE_KINDS, frame_table
from ..measure import circle_deviations, line_deviations
from ..spline import FloatArray, Point
from . import bezier
from .piece import spiral_length

#: Control points are accepted as "of the paper's form" when each condition holds to this
#: relative accuracy: enough for coordinates printed with ~7 significant digits.
FORM_RTOL = 1e-6

#: Coordinates and the spiral's size ``a`` stay within ``[1/MAX_MAGNITUDE, MAX_MAGNITUDE]`` so
#: that squares, products and quotients of them stay finite and normal in double precision.
MAX_MAGNITUDE = 1e150
#: A spiral smaller than this fraction of its coordinates would be lost in their rounding.
MIN_RELATIVE_SIZE = 1e-12


def _finite(field: str, *values: float) -> None:
    if not all(math.isfinite(v) for v in values):
        raise GeometryError(field, "must be finite numbers (no NaN or Infinity)")


def _pair(field: str, value: Sequence[float]) -> tuple[float, float]:
    if len(value) != 2:
        raise GeometryError(field, f"must have 2 coordinates, got {len(value)}")
    x, y = float(value[0]), float(value[1])
    _finite(field, x, y)
    return x, y


@dataclass(frozen=True)
class Spiral:
    """A cubic Bézier spiral in world coordinates (paper §1).

    Build it with :meth:`from_parameters` or :meth:`from_control_points`, which validate.
    ``turn_angle_rad`` is positive; the sign of ``end_curvature`` is the turning direction.
    """

    start: Point
    start_tangent: Point
    turn_angle_rad: float
    end_curvature: float

    @classmethod
    def from_parameters(
        cls,
        start: Sequence[float],
        start_tangent: Sequence[float],
        turn_angle_deg: float,
        end_curvature: float,
    ) -> Spiral:
        """The paper's five parameters; ``start_tangent`` is any non-zero vector."""
        sx, sy = _pair("start", start)
        tx, ty = _pair("start_tangent", start_tangent)
        norm = math.hypot(tx, ty)
        if not norm > 0.0:
            raise GeometryError("start_tangent", "must be a non-zero vector")
        _finite("turn_angle_deg", turn_angle_deg)
        if not 0.0 < turn_angle_deg < 90.0:
            raise GeometryError(
                "turn_angle_deg",
                f"must lie strictly between 0 and 90 degrees, got {turn_angle_deg}",
            )
        _finite("end_curvature", end_curvature)
        if end_curvature == 0.0:
            raise GeometryError(
                "end_curvature", "must be non-zero (its sign is the turning direction)"
            )
        spiral = cls(
            start=Point(sx, sy),
            start_tangent=Point(tx / norm, ty / norm),
            turn_angle_rad=math.radians(turn_angle_deg),
            end_curvature=float(end_curvature),
        )
        if not 1.0 / MAX_MAGNITUDE <= spiral.a <= MAX_MAGNITUDE:
            raise GeometryError(
                "end_curvature",
                f"gives a spiral of size a = {spiral.a:.3g}, outside the supported "
                f"[{1.0 / MAX_MAGNITUDE:g}, {MAX_MAGNITUDE:g}]",
            )
        if max(abs(sx), abs(sy)) > MAX_MAGNITUDE:
            raise GeometryError("start", f"coordinates must not exceed {MAX_MAGNITUDE:g} in size")
        if spiral.a < MIN_RELATIVE_SIZE * max(abs(sx), abs(sy)):
            raise GeometryError(
                "end_curvature",
                f"gives a spiral of size a = {spiral.a:.3g}, too small to be placed at "
                f"coordinates of {max(abs(sx), abs(sy)):.3g} in double precision "
                f"(needs at least {MIN_RELATIVE_SIZE:g} of them)",
            )
        return spiral

    @classmethod
    def from_control_points(cls, points: Sequence[Sequence[float]]) -> Spiral:
        """Four control points of the paper's form; θ and c are recovered from them.

        The form is ``B1 − B0 = B2 − B1 = a·T0`` and ``B3 − B2 = b·T1`` with
        ``b / a = 1.2·cos θ``, θ the angle from ``T0`` to ``T1`` (``0 < |θ| < 90°``).
        """
        field = "control_points"
        if len(points) != 4:
            raise GeometryError(field, f"must be 4 points, got {len(points)}")
        b = np.array([_pair(f"{field}[{i}]", p) for i, p in enumerate(points)], dtype=np.float64)
        d0, d1, d2 = b[1] - b[0], b[2] - b[1], b[3] - b[2]
        a_len = float(np.hypot(*d0))
        b_len = float(np.hypot(*d2))
        if not (a_len > 0.0 and b_len > 0.0):
            raise GeometryError(field, "consecutive points must be distinct (B0≠B1, B2≠B3)")
        mismatch = float(np.hypot(*(d1 - d0))) / a_len
        if mismatch > FORM_RTOL:
            raise GeometryError(
                field,
                "B2 − B1 must equal B1 − B0 (the paper's form); they differ by "
                f"{mismatch:.3g} of |B1 − B0| (allowed {FORM_RTOL:g})",
            )
        t0 = (d0 + d1) / (2.0 * a_len)
        t0 /= np.hypot(*t0)
        t1 = d2 / b_len
        theta = math.atan2(float(t0[0] * t1[1] - t0[1] * t1[0]), float(t0 @ t1))
        theta_deg = math.degrees(abs(theta))
        if not 0.0 < theta_deg < 90.0:
            raise GeometryError(
                field,
                "the angle from B1 − B0 to B3 − B2 must lie strictly between 0 and 90 degrees "
                f"in size, got {theta_deg:.6g}",
            )
        ratio = b_len / a_len
        expected = 1.2 * math.cos(abs(theta))
        if abs(ratio - expected) > FORM_RTOL * expected:
            raise GeometryError(
                field,
                f"|B3 − B2| / |B1 − B0| must equal 1.2·cos θ = {expected:.9g}, got {ratio:.9g} "
                f"(off by {abs(ratio - expected) / expected:.3g} relative, allowed {FORM_RTOL:g})",
            )
        curvature = 5.0 * math.tan(abs(theta)) / (9.0 * b_len)
        return cls.from_parameters(
            start=b[0].tolist(),
            start_tangent=t0.tolist(),
            turn_angle_deg=theta_deg,
            end_curvature=math.copysign(curvature, theta),
        )

    # -- derived quantities ------------------------------------------------------------

    @property
    def turn_direction(self) -> int:
        """+1 for a left (anticlockwise) turn, −1 for the mirror image."""
        return 1 if self.end_curvature > 0.0 else -1

    @property
    def turn_angle_deg(self) -> float:
        return math.degrees(self.turn_angle_rad)

    @cached_property
    def a(self) -> float:
        """``|B1 − B0|``: also the scale of the canonical frame (``inf`` where a curvature
        of denormal size makes the denominator vanish; :meth:`from_parameters` refuses it)."""
        th = self.turn_angle_rad
        denominator = 54.0 * abs(self.end_curvature) * math.cos(th)
        return 25.0 * math.tan(th) / denominator if denominator > 0.0 else math.inf

    @cached_property
    def b(self) -> float:
        """``|B3 − B2|``."""
        denominator = 9.0 * abs(self.end_curvature)
        return 5.0 * math.tan(self.turn_angle_rad) / denominator if denominator > 0.0 else math.inf

    @cached_property
    def end_tangent(self) -> Point:
        phi = self.turn_direction * self.turn_angle_rad
        c, s = math.cos(phi), math.sin(phi)
        tx, ty = self.start_tangent
        return Point(c * tx - s * ty, s * tx + c * ty)

    @cached_property
    def _points(self) -> tuple[Point, Point, Point, Point]:
        # B1 = B0 + a·T0, B2 = B1 + a·T0, B3 = B2 + b·T1, in floats: a batch builds
        # thousands of spirals, and numpy would spend microseconds on each of these sums.
        (x0, y0), (tx, ty), (ux, uy) = self.start, self.start_tangent, self.end_tangent
        a, b = self.a, self.b
        x1, y1 = x0 + a * tx, y0 + a * ty
        x2, y2 = x1 + a * tx, y1 + a * ty
        return self.start, Point(x1, y1), Point(x2, y2), Point(x2 + b * ux, y2 + b * uy)

    @cached_property
    def control_points(self) -> FloatArray:
        """``B0..B3`` as a ``(4, 2)`` array."""
        return np.array(self._points, dtype=np.float64)

    @property
    def end_point(self) -> Point:
        """``B3``, as stored (``control_points[3]``)."""
        return self._points[3]

    @cached_property
    def chord(self) -> float:
        """``|B3 − B0|``: the spiral's size, the reference for relative tolerances."""
        (x0, y0), (x3, y3) = self.start, self.end_point
        return math.hypot(x3 - x0, y3 - y0)

    @cached_property
    def coordinate_scale(self) -> float:
        """The largest coordinate magnitude of the control points (for rounding margins)."""
        return max(abs(v) for point in self._points for v in point)

    @property
    def domain(self) -> tuple[float, float]:
        return (0.0, 1.0)

    @cached_property
    def frame(self) -> tuple[float, ...]:
        """What the kernels need of the spiral, in ``fit.batch.FRAME_FIELDS`` order: the
        similarity from the canonical spiral (``B0``, ``T0``, ``a``, the turning direction),
        the stored end point ``B3``, the chord, the coordinate scale and the canonical
        spiral's coefficients ``X = 3u + k·u³``, ``Y = m·u³``."""
        (x0, y0), (tx, ty), (x3, y3) = self.start, self.start_tangent, self.end_point
        c, s = math.cos(self.turn_angle_rad), math.sin(self.turn_angle_rad)
        return (
            x0, y0, tx, ty, self.a, float(self.turn_direction), x3, y3, self.chord,
            self.coordinate_scale, 3.0, 0.0, 1.2 * c * c - 1.0, 0.0, 0.0, 1.2 * c * s,
            0.0, 0.0, float(PIECE_KINDS["fit"]),
        )  # fmt: skip

    # -- evaluation (Bernstein form) ---------------------------------------------------

    def eval(self, u: float | FloatArray) -> FloatArray:
        """``Q(u)`` by de Casteljau; shape ``(..., 2)`` for ``u`` of shape ``(...)``."""
        return bezier.point(self.control_points, u)

    def deriv(self, u: float | FloatArray) -> FloatArray:
        """``Q'(u)``."""
        return bezier.derivative(self.control_points, u)

    def deriv2(self, u: float | FloatArray) -> FloatArray:
        """``Q''(u)``."""
        return bezier.second_derivative(self.control_points, u)

    def curvature(self, u: float | FloatArray) -> FloatArray:
        """Signed curvature ``κ = Q'×Q'' / ‖Q'‖³`` (positive turning left)."""
        d1, d2 = self.deriv(u), self.deriv2(u)
        cross = d1[..., 0] * d2[..., 1] - d1[..., 1] * d2[..., 0]
        result: FloatArray = cross / np.hypot(d1[..., 0], d1[..., 1]) ** 3
        return result

    def arclen(self, u0: float = 0.0, u1: float = 1.0) -> float:
        """Arc length over ``[u0, u1]``: the canonical spiral's (adaptive Gauss–Legendre,
        docs/method.md §6) times the scale ``a``."""
        return self.a * spiral_length(self.turn_angle_rad, u0, u1)

    def line_deviations(
        self, u0: FloatArray, u1: FloatArray, start: FloatArray, end: FloatArray
    ) -> FloatArray:
        """Exact largest distance from each piece ``[u0, u1]`` to the line ``start→end``
        (``measure.pyx``, on the spiral's piece)."""
        return line_deviations(self._frames, np.zeros(len(u0), np.int64), u0, u1, start, end)

    def circle_deviations(
        self,
        u0: FloatArray,
        u1: FloatArray,
        centre: FloatArray,
        r_start: FloatArray,
        r_end: FloatArray,
    ) -> FloatArray:
        """Exact largest distance from each piece ``[u0, u1]`` to the farther of two circles
        about ``centre`` (``measure.pyx``, on the spiral's piece)."""
        zero = np.zeros(len(u0), np.int64)
        return circle_deviations(self._frames, zero, u0, u1, centre, r_start, r_end)

    @cached_property
    def _frames(self) -> FloatArray:
        return frame_table([self.frame])


# How a request gives a spiral: named tuples (they cross the worker boundary by the
# thousand, and pickle several times faster than dataclasses); ``build`` validates.


class SpiralFromParameters(NamedTuple):
    """The paper's five parameters (:meth:`Spiral.from_parameters`)."""

    start: tuple[float, float]
    start_tangent: tuple[float, float]
    turn_angle_deg: float
    end_curvature: float

    def build(self) -> Spiral:
        return Spiral.from_parameters(
            self.start, self.start_tangent, self.turn_angle_deg, self.end_curvature
        )


class SpiralFromControlPoints(NamedTuple):
    """Four control points of the paper's form (:meth:`Spiral.from_control_points`)."""

    control_points: tuple[tuple[float, float], ...]

    def build(self) -> Spiral:
        return Spiral.from_control_points(self.control_points)
