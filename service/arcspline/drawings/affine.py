"""Affine maps of the plane, applied exactly to path segments (docs/drawings.md §2).

A drawing's transforms (SVG's ``transform`` and viewBox, DXF's INSERT and OCS) compose into
one :class:`Affine` per element, applied once to its segments. Béziers map by their control
points (affine invariance); a circular arc stays a circular arc under a similarity, a mirror
reversing its sweep; under any other map it becomes an elliptical arc, and an elliptical
arc maps to an elliptical arc: the image of ``centre + M·(cos φ, sin φ)`` is
``centre' + L·M·(cos φ, sin φ)``, and the singular value decomposition
``L·M = R(α)·diag(σ₁, σ₂)·R(β)`` gives its principal axes σ₁ ≥ |σ₂| at rotation α and the new
parameter φ + β (σ₂ < 0, a mirror, flips the parameter and so the sweep). End points are
mapped by :meth:`Affine.apply` alone, so segments that met bit for bit still do.
"""

from __future__ import annotations

import math
from typing import NamedTuple

from arcspline.geometry.curves.segments import (
    CircularArc,
    Cubic,
    EllipticalArc,
    Line,
    Quadratic,
    Segment,
    Subpath,
)
from arcspline.geometry.spline import Point

#: Relative size below which a map's determinant counts as zero (the map collapses the plane
#: onto a line or a point: nothing of the drawing can be cut).
SINGULAR_RTOL = 1e-12
#: Relative mismatch of the singular values below which a map counts as a similarity.
SIMILARITY_RTOL = 1e-12


class SingularMapError(ValueError):
    """The map collapses the plane (zero scale, a degenerate matrix)."""


def _cos_sin_deg(angle_deg: float) -> tuple[float, float]:
    """cos and sin of an angle in degrees, exact at multiples of 90° (rotate(90) must map
    (1, 0) to (0, 1), not to (6e-17, 1))."""
    quarter, rest = divmod(angle_deg, 90.0)
    if rest == 0.0:
        return ((1.0, 0.0), (0.0, 1.0), (-1.0, 0.0), (0.0, -1.0))[int(quarter) % 4]
    angle_rad = math.radians(angle_deg)
    return math.cos(angle_rad), math.sin(angle_rad)


class Affine(NamedTuple):
    """``x' = a·x + c·y + e``, ``y' = b·x + d·y + f``: SVG's ``matrix(a b c d e f)``."""

    a: float = 1.0
    b: float = 0.0
    c: float = 0.0
    d: float = 1.0
    e: float = 0.0
    f: float = 0.0

    @classmethod
    def translate(cls, tx: float, ty: float = 0.0) -> Affine:
        return cls(1.0, 0.0, 0.0, 1.0, tx, ty)

    @classmethod
    def scale(cls, sx: float, sy: float | None = None) -> Affine:
        return cls(sx, 0.0, 0.0, sx if sy is None else sy, 0.0, 0.0)

    @classmethod
    def rotate_deg(cls, angle_deg: float, cx: float = 0.0, cy: float = 0.0) -> Affine:
        """Rotation by ``angle_deg`` (from +x towards +y) about ``(cx, cy)``."""
        cos, sin = _cos_sin_deg(angle_deg)
        turn = cls(cos, sin, -sin, cos, 0.0, 0.0)
        if cx == 0.0 and cy == 0.0:
            return turn
        return cls.translate(cx, cy) @ turn @ cls.translate(-cx, -cy)

    @classmethod
    def skew_x_deg(cls, angle_deg: float) -> Affine:
        return cls(1.0, 0.0, math.tan(math.radians(angle_deg)), 1.0, 0.0, 0.0)

    @classmethod
    def skew_y_deg(cls, angle_deg: float) -> Affine:
        return cls(1.0, math.tan(math.radians(angle_deg)), 0.0, 1.0, 0.0, 0.0)

    def __matmul__(self, other: object) -> Affine:
        """``self @ other``: ``other`` first, then ``self`` (as SVG's ``transform`` lists)."""
        if not isinstance(other, Affine):
            return NotImplemented
        a, b, c, d, e, f = self
        return Affine(
            a * other.a + c * other.b,
            b * other.a + d * other.b,
            a * other.c + c * other.d,
            b * other.c + d * other.d,
            a * other.e + c * other.f + e,
            b * other.e + d * other.f + f,
        )

    def apply(self, point: Point) -> Point:
        x, y = point
        return Point(self.a * x + self.c * y + self.e, self.b * x + self.d * y + self.f)

    @property
    def determinant(self) -> float:
        return self.a * self.d - self.b * self.c

    @property
    def is_identity(self) -> bool:
        return self == Affine()

    def is_singular(self) -> bool:
        """True when the map collapses the plane, relative to the size of its linear part."""
        size = max(abs(self.a), abs(self.b), abs(self.c), abs(self.d))
        return not (math.isfinite(self.determinant) and size > 0.0) or (
            abs(self.determinant) <= SINGULAR_RTOL * size * size
        )


class _Axes(NamedTuple):
    """``L = R(rotation)·diag(major, minor)·R(shift)``; ``minor < 0`` for a mirror."""

    rotation_rad: float
    major: float
    minor: float
    shift_rad: float


def _axes(p: float, q: float, r: float, s: float) -> _Axes:
    """The singular value decomposition of the 2×2 matrix ``[[p, q], [r, s]]`` in closed form
    (rotations on both sides; the sign of the second value carries the determinant's)."""
    e, f = (p + s) / 2.0, (p - s) / 2.0
    g, h = (r + q) / 2.0, (r - q) / 2.0
    big, small = math.hypot(e, h), math.hypot(f, g)
    a1, a2 = math.atan2(g, f), math.atan2(h, e)
    return _Axes((a2 + a1) / 2.0, big + small, big - small, (a2 - a1) / 2.0)


def _elliptical(
    m: Affine,
    start: Point,
    end: Point,
    center: Point,
    rx: float,
    ry: float,
    rotation_rad: float,
    start_angle_rad: float,
    sweep_rad: float,
) -> EllipticalArc:
    cos, sin = math.cos(rotation_rad), math.sin(rotation_rad)
    # L·R(rotation)·diag(rx, ry)
    p, q = (m.a * cos + m.c * sin) * rx, (-m.a * sin + m.c * cos) * ry
    r, s = (m.b * cos + m.d * sin) * rx, (-m.b * sin + m.d * cos) * ry
    axes = _axes(p, q, r, s)
    phi, sweep = start_angle_rad + axes.shift_rad, sweep_rad
    if axes.minor < 0.0:  # diag(σ₁, −σ₂)·(cos φ, sin φ) = diag(σ₁, σ₂)·(cos −φ, sin −φ)
        phi, sweep = -phi, -sweep
    return EllipticalArc(
        m.apply(start), m.apply(end), m.apply(center), axes.major, abs(axes.minor),
        axes.rotation_rad, math.remainder(phi, math.tau), sweep,
    )  # fmt: skip


def _similarity_scale(m: Affine) -> float | None:
    """The map's scale when it is a similarity (rotation, uniform scale, maybe a mirror)."""
    axes = _axes(m.a, m.c, m.b, m.d)
    major, minor = axes.major, abs(axes.minor)
    return major if major - minor <= SIMILARITY_RTOL * major else None


def transform_segment(segment: Segment, m: Affine) -> Segment:
    """``segment`` mapped by ``m``, exactly (module docstring). Raises
    :class:`SingularMapError` when ``m`` collapses the plane."""
    if m.is_singular():
        raise SingularMapError(f"the transform {tuple(m)} collapses the plane")
    match segment:
        case Line(start, end):
            return Line(m.apply(start), m.apply(end))
        case Quadratic(start, control, end):
            return Quadratic(m.apply(start), m.apply(control), m.apply(end))
        case Cubic(start, control1, control2, end):
            return Cubic(m.apply(start), m.apply(control1), m.apply(control2), m.apply(end))
        case CircularArc(start, end, center, radius, start_angle_rad, sweep_rad):
            scale = _similarity_scale(m)
            if scale is None:
                return _elliptical(
                    m, start, end, center, radius, radius, 0.0, start_angle_rad, sweep_rad
                )
            orientation = 1.0 if m.determinant > 0.0 else -1.0
            # (a, b), the image of (1, 0), is at angle τ; the point at angle θ goes to τ + θ,
            # or to τ − θ under a mirror.
            turn_rad = math.atan2(m.b, m.a)
            return CircularArc(
                m.apply(start), m.apply(end), m.apply(center), radius * scale,
                math.remainder(turn_rad + orientation * start_angle_rad, math.tau),
                orientation * sweep_rad,
            )  # fmt: skip
        case EllipticalArc(start, end, center, rx, ry, rotation_rad, start_angle_rad, sweep_rad):
            return _elliptical(
                m, start, end, center, rx, ry, rotation_rad, start_angle_rad, sweep_rad
            )
    raise TypeError(f"not a segment: {segment!r}")  # pragma: no cover - exhaustive above


def transform_subpath(subpath: Subpath, m: Affine) -> Subpath:
    """Every segment of ``subpath`` mapped by ``m`` (still chained bit for bit)."""
    if m.is_identity:
        return subpath
    return Subpath(tuple(transform_segment(s, m) for s in subpath.segments), subpath.closed)
