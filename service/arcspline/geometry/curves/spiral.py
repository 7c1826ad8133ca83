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

θ enters only through ``cos θ`` and ``sin θ``, each computed to a few ulps of itself: above
45° from the complement ``90° − θ`` (exact in degrees), since ``cos(radians(θ))`` near 90°
keeps only the absolute accuracy of ``radians(θ)`` and ``a ∝ 1/cos²θ`` would carry its
relative error (docs/method.md §1, "θ near 90°"). A spiral given by control points is fitted
as those very points (its frame is their cubic), so the answer is held to the given curve,
its ends and its end tangents (docs/method.md §1, "Control points").
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
from .piece import cubic_length

#: Control points are accepted as "of the paper's form" when each condition holds to this
#: relative accuracy: enough for coordinates printed with ~7 significant digits. The bound
#: keeps the input within the method's domain (a spiral: curvature monotone, turning less
#: than 90°); it does not bound the answer's accuracy, which is measured against the given
#: points themselves, as they are fitted.
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


def turn_cos_sin(turn_angle_deg: float) -> tuple[float, float]:
    """``(cos θ, sin θ)`` of a turn angle in degrees, ``0 ≤ θ ≤ 90``, each to a few ulps of
    itself. Above 45° they are the sine and cosine of the complement ``φ = 90° − θ``, which
    is exact in floating point (Sterbenz: ``θ`` within a factor two of 90): ``radians(θ)``
    rounds by ulps of π/2, which near 90° is a large relative error of ``cos θ``."""
    if turn_angle_deg <= 45.0:
        theta_rad = math.radians(turn_angle_deg)
        return math.cos(theta_rad), math.sin(theta_rad)
    phi_rad = math.radians(90.0 - turn_angle_deg)
    return math.sin(phi_rad), math.cos(phi_rad)


def local_cubic(
    points: Sequence[Point], tangent: Point, sigma: float, scale: float
) -> tuple[float, float, float, float, float, float]:
    """``(x1, x2, x3, y1, y2, y3)`` of the cubic Bézier ``points`` in the local frame at
    ``B0`` along the unit ``tangent``, mirrored by ``sigma = ±1`` and divided by ``scale``
    (docs/method.md §2): ``Q(u) − B0 = 3·d0·u + 3·(d1 − d0)·u² + (d2 − 2·d1 + d0)·u³``
    (``d_i = B_{i+1} − B_i``), each vector ``v`` written as ``(T·v, σ·T×v) / scale``. With
    ``tangent`` the direction of ``d0`` and ``scale = |d0|``, ``3·d0`` is ``(3, 0)`` exactly:
    the curve leaves ``B0`` along ``B1 − B0`` as given."""
    (x0, y0), (x1, y1), (x2, y2), (x3, y3) = points
    tx, ty = tangent
    # d1 − d0 and d2 − 2·d1 + d0 as differences of the legs (each leg formed once).
    ex, ey = (x2 - x1) - (x1 - x0), (y2 - y1) - (y1 - y0)
    fx, fy = (x3 - x2) - (x2 - x1) - ex, (y3 - y2) - (y2 - y1) - ey
    return (
        3.0, 3.0 * (tx * ex + ty * ey) / scale, (tx * fx + ty * fy) / scale,
        0.0, 3.0 * sigma * (tx * ey - ty * ex) / scale, sigma * (tx * fy - ty * fx) / scale,
    )  # fmt: skip


@dataclass(frozen=True)
class Spiral:
    """A cubic Bézier spiral in world coordinates (paper §1).

    Build it with :meth:`from_parameters` or :meth:`from_control_points`, which validate.
    ``turn_angle_rad`` is positive; the sign of ``end_curvature`` is the turning direction.
    ``cos_turn`` and ``sin_turn`` are ``cos θ`` and ``sin θ`` to a few ulps of themselves
    (:func:`turn_cos_sin`): everything derived from θ uses them. ``given`` holds the control
    points of a spiral given by them, exactly as given: those points are then the curve
    (its evaluation, its frame and its ends), and the other fields describe it.
    """

    start: Point
    start_tangent: Point
    turn_angle_rad: float
    end_curvature: float
    cos_turn: float
    sin_turn: float
    given: tuple[Point, Point, Point, Point] | None = None

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
        cos_turn, sin_turn = turn_cos_sin(float(turn_angle_deg))
        spiral = cls(
            start=Point(sx, sy),
            start_tangent=Point(tx / norm, ty / norm),
            turn_angle_rad=math.atan2(sin_turn, cos_turn),
            end_curvature=float(end_curvature),
            cos_turn=cos_turn,
            sin_turn=sin_turn,
        )
        spiral._check_size("end_curvature", "start")
        return spiral

    @classmethod
    def from_control_points(cls, points: Sequence[Sequence[float]]) -> Spiral:
        """Four control points of the paper's form; θ and c are recovered from them.

        The form is ``B1 − B0 = B2 − B1 = a·T0`` and ``B3 − B2 = b·T1`` with
        ``b / a = 1.2·cos θ``, θ the angle from ``T0`` to ``T1`` (``0 < |θ| < 90°``), each
        to :data:`FORM_RTOL`. The spiral is the given points' cubic, not the nearest one of
        the form: ``T0`` is the direction of ``B1 − B0``, ``T1`` that of ``B3 − B2``.
        """
        field = "control_points"
        if len(points) != 4:
            raise GeometryError(field, f"must be 4 points, got {len(points)}")
        b = np.array([_pair(f"{field}[{i}]", p) for i, p in enumerate(points)], dtype=np.float64)
        # Before any difference: two coordinates near the float range overflow when subtracted.
        if float(np.abs(b).max()) > MAX_MAGNITUDE:
            raise GeometryError(field, f"coordinates must not exceed {MAX_MAGNITUDE:g} in size")
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
        t0, t1 = d0 / a_len, d2 / b_len
        cross, dot = float(t0[0] * t1[1] - t0[1] * t1[0]), float(t0 @ t1)
        theta = math.atan2(cross, dot)
        theta_deg = math.degrees(abs(theta))
        if not (0.0 < theta_deg < 90.0 and dot > 0.0):
            raise GeometryError(
                field,
                "the angle from B1 − B0 to B3 − B2 must lie strictly between 0 and 90 degrees "
                f"in size, got {theta_deg:.6g}",
            )
        # cos θ and sin θ straight from the legs' directions: no angle in between.
        norm = math.hypot(dot, cross)
        cos_turn, sin_turn = dot / norm, abs(cross) / norm
        ratio = b_len / a_len
        expected = 1.2 * cos_turn
        if abs(ratio - expected) > FORM_RTOL * expected:
            raise GeometryError(
                field,
                f"|B3 − B2| / |B1 − B0| must equal 1.2·cos θ = {expected:.9g}, got {ratio:.9g} "
                f"(off by {abs(ratio - expected) / expected:.3g} relative, allowed {FORM_RTOL:g})",
            )
        rows = [Point(float(x), float(y)) for x, y in b]
        spiral = cls(
            start=rows[0],
            start_tangent=Point(float(t0[0]), float(t0[1])),
            turn_angle_rad=abs(theta),
            end_curvature=math.copysign(5.0 * sin_turn / (9.0 * b_len * cos_turn), theta),
            cos_turn=cos_turn,
            sin_turn=sin_turn,
            given=(rows[0], rows[1], rows[2], rows[3]),
        )
        spiral._check_size(field, field)
        return spiral

    def _check_size(self, size_field: str, start_field: str) -> None:
        """Refuse a spiral whose size or coordinates double precision cannot hold."""
        sx, sy = self.start
        if not 1.0 / MAX_MAGNITUDE <= self.a <= MAX_MAGNITUDE:
            raise GeometryError(
                size_field,
                f"gives a spiral of size a = {self.a:.3g}, outside the supported "
                f"[{1.0 / MAX_MAGNITUDE:g}, {MAX_MAGNITUDE:g}]",
            )
        if max(abs(sx), abs(sy)) > MAX_MAGNITUDE:
            raise GeometryError(
                start_field, f"coordinates must not exceed {MAX_MAGNITUDE:g} in size"
            )
        if self.a < MIN_RELATIVE_SIZE * max(abs(sx), abs(sy)):
            raise GeometryError(
                size_field,
                f"gives a spiral of size a = {self.a:.3g}, too small to be placed at "
                f"coordinates of {max(abs(sx), abs(sy)):.3g} in double precision "
                f"(needs at least {MIN_RELATIVE_SIZE:g} of them)",
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
        of denormal size makes the denominator vanish; :meth:`from_parameters` refuses it).
        From the parameters, ``25·sin θ / (54·|c|·cos²θ)``."""
        if self.given is not None:
            (x0, y0), (x1, y1) = self.given[0], self.given[1]
            return math.hypot(x1 - x0, y1 - y0)
        c, s = self.cos_turn, self.sin_turn
        denominator = 54.0 * abs(self.end_curvature) * c * c
        return 25.0 * s / denominator if denominator > 0.0 else math.inf

    @cached_property
    def b(self) -> float:
        """``|B3 − B2|``; from the parameters, ``5·sin θ / (9·|c|·cos θ)``."""
        if self.given is not None:
            (x2, y2), (x3, y3) = self.given[2], self.given[3]
            return math.hypot(x3 - x2, y3 - y2)
        denominator = 9.0 * abs(self.end_curvature) * self.cos_turn
        return 5.0 * self.sin_turn / denominator if denominator > 0.0 else math.inf

    @cached_property
    def end_tangent(self) -> Point:
        """``T1``: ``T0`` turned by θ in the turning direction (given control points: the
        direction of ``B3 − B2``)."""
        if self.given is not None:
            (x2, y2), (x3, y3) = self.given[2], self.given[3]
            length = math.hypot(x3 - x2, y3 - y2)
            return Point((x3 - x2) / length, (y3 - y2) / length)
        c, s = self.cos_turn, self.turn_direction * self.sin_turn
        tx, ty = self.start_tangent
        return Point(c * tx - s * ty, s * tx + c * ty)

    @cached_property
    def _points(self) -> tuple[Point, Point, Point, Point]:
        if self.given is not None:
            return self.given
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
        similarity from the local frame (``B0``, ``T0``, ``a``, the turning direction), the
        stored end point ``B3``, the chord, the coordinate scale and the curve's coefficients
        in the local frame: the canonical spiral's ``X = 3u + k·u³``, ``Y = m·u³``, or those
        of the given control points' cubic (:func:`local_cubic`)."""
        (x0, y0), (tx, ty), (x3, y3) = self.start, self.start_tangent, self.end_point
        if self.given is None:
            c, s = self.cos_turn, self.sin_turn
            coefficients = (3.0, 0.0, 1.2 * c * c - 1.0, 0.0, 0.0, 1.2 * c * s)
        else:
            sigma = float(self.turn_direction)
            coefficients = local_cubic(self.given, self.start_tangent, sigma, self.a)
        return (
            x0, y0, tx, ty, self.a, float(self.turn_direction), x3, y3, self.chord,
            self.coordinate_scale, *coefficients, 0.0, 0.0, float(PIECE_KINDS["fit"]),
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
        """Arc length over ``[u0, u1]``: the frame's piece's (adaptive Gauss–Legendre,
        docs/method.md §6) times the scale ``a``."""
        x1, x2, x3, y1, y2, y3 = self.frame[10:16]
        return self.a * cubic_length(x1, x2, x3, y1, y2, y3, u0, u1)

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
