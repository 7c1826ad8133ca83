"""A DXF SPLINE (a NURBS curve) as our segments, exactly (docs/drawings.md §4).

The curve on its domain ``[U[p], U[n]]`` (``n`` control points, degree ``p``, knots ``U``) is
cut at its knots into Bézier pieces by blossoming: on the span ``[a, b] = [U[k], U[k+1]]`` the
Bézier control point ``i`` is the blossom ``f(a, …, a, b, …, b)`` (``p − i`` times ``a``,
``i`` times ``b``) of the local control points ``P[k−p … k]`` (de Boor's algorithm with a
different argument at each level; Ramshaw, "Blossoms are polar forms", 1989). This is knot
insertion to full multiplicity span by span (Boehm), so clamped, unclamped and periodic knot
vectors are the same code, and a rational curve is the same code in homogeneous coordinates
``(w·x, w·y, w)``. Work is ``O(n·p³)``.

Each piece becomes one segment: degree 1 a :class:`Line`, non-rational degree 2 and 3 a
:class:`Quadratic` or :class:`Cubic`. A rational quadratic piece with end weights normalised
to 1 has the middle weight ``w = w1 / √(w0·w2)`` (Farin, "Curves and Surfaces for CAGD",
§12.3): ``w = 1`` is a parabola (a :class:`Quadratic`), ``w < 1`` an ellipse, ``w > 1`` a
hyperbola, which our segments cannot hold. The ellipse has centre ``C = (M − w²·P1)/(1 − w²)``
(``M`` the chord's midpoint) and passes through ``S = (M + w·P1)/(1 + w)`` at ``t = ½``; it is
the unit circle's arc from ``−α`` to ``α`` mapped by the affine map with columns ``a = S − C``,
``b = (M − P0)/sin α`` and translation ``C``, where ``cos α = |M − C|/|S − C| = w``. A rational
cubic piece with equal weights is a plain cubic; one that is a degree-elevated rational
quadratic (``3·H1 − H0 = 3·H2 − H3`` in homogeneous coordinates) is read as that quadratic,
but only when the two sides agree to rounding (:func:`_lowered`). Any other rational cubic
cannot be held exactly (our curves are rational of degree ≤ 2): given a curve tolerance it is
replaced by plain cubics within a certified distance (``dxf_rational.py``), else refused.

Every test is translation-invariant: each span is blossomed in coordinates relative to its
first control point, so that its rounding is relative to its own extent, not to its distance
from the origin (a part drawn 10⁶ mm from the origin reads as it does at the origin).

Pieces chain bit for bit: each piece starts at the very point the previous one ended. A curve
whose end lies within ``CLOSE_RTOL`` of its start (relative to its extent) is closed by moving
its end onto its start, and that move is added to the reported approximation bound.
"""

from __future__ import annotations

import itertools
import math
import sys
from collections.abc import Sequence
from typing import NamedTuple

from arcspline.geometry.curves.segments import (
    CircularArc,
    Cubic,
    Line,
    Quadratic,
    Segment,
)
from arcspline.geometry.spline import Point

from .affine import Affine, SingularMapError, transform_segment
from .dxf_rational import CubicFit, Homogeneous, rational_cubic_fit

#: Weights within this relative distance of each other (or a normalised middle weight this
#: close to 1) count as equal: the curve is polynomial.
WEIGHT_RTOL = 1e-12
#: How far a rational cubic may be from the conic it is lowered to, in units in the last place
#: of the piece's extent: rounding only (:func:`_lowered`). Beyond it the piece is a general
#: rational cubic.
LOWERING_ULPS = 64.0
#: How close (relative to the curve's extent) a curve's end must be to its start for it to
#: count as closed; the end is then moved onto the start and the move is reported.
CLOSE_RTOL = 1e-9
#: Units in the last place of the curve's largest coordinate that its end may be from its
#: start and still close: far from the origin the end points' own rounding is that large.
CLOSE_ULPS = 16.0
#: ``max_t 2·t²·(1 − t)``, at ``t = 2/3``: how much of a cubic's third control point's move
#: reaches the curve (:func:`_lowered`).
_B2_TWO_THIRDS_MAX = 8.0 / 27.0
#: The highest degree read (a Bézier piece of higher degree has no segment type).
MAX_DEGREE = 3
#: The most cubics one spline's rational cubic pieces may become, all pieces together.
MAX_APPROXIMATING_CUBICS = 4096


class SplineRefusedError(ValueError):
    """The spline cannot be read as our segments; the message says why."""


class SplineData(NamedTuple):
    """A NURBS curve in the plane: degree, knots, control points, and weights (empty when the
    curve is not rational)."""

    degree: int
    knots: tuple[float, ...]
    control_points: tuple[Point, ...]
    weights: tuple[float, ...] = ()


class SplineSegments(NamedTuple):
    """The spline's Bézier pieces as segments, whether it closes, and notes on how it was
    read (a degree taken from the knots, fit points interpolated). ``approximated`` is the
    certified largest distance, in the spline's own units, between the curve and the
    segments: the cubics standing for its rational cubic pieces plus the move of its end onto
    its start that closed it (0 when every piece is exact and no end was moved), and
    ``approximating`` the number of those cubics."""

    segments: tuple[Segment, ...]
    closed: bool
    notes: tuple[str, ...]
    approximated: float = 0.0
    approximating: int = 0


def spline_segments(data: SplineData, curve_tolerance: float | None = None) -> SplineSegments:
    """The Bézier pieces of ``data`` as segments (module docstring). A rational cubic piece
    that is not an elevated conic becomes cubics within ``curve_tolerance`` (in the spline's
    own units), certified; with ``curve_tolerance`` None it is refused. Raises
    :class:`SplineRefusedError` saying why when the curve cannot be read."""
    degree, knots, points, weights = data
    _validate(data)
    rational = bool(weights) and any(
        abs(w - weights[0]) > WEIGHT_RTOL * weights[0] for w in weights
    )
    scales = weights if rational else [1.0] * len(points)
    homogeneous = [(w * x, w * y, w) for (x, y), w in zip(points, scales, strict=True)]
    segments: list[Segment] = []
    approximated, approximating = 0.0, 0
    for k in range(degree, len(points)):
        a, b = knots[k], knots[k + 1]
        if not a < b:
            continue
        args = [[a] * (degree - i) + [b] * i for i in range(degree + 1)]
        span = homogeneous[k - degree : k + 1]
        piece = [_blossom(span, knots, degree, k, arg) for arg in args]
        if not all(math.isfinite(c) for h in piece for c in h) or min(h[2] for h in piece) <= 0:
            raise SplineRefusedError(
                "its knots, weights or points overflow (or underflow) double precision"
            )
        if len(piece) == 4 and not _equal([h[2] for h in piece]):
            piece = _lowered(piece, _local_piece(points, scales, knots, k, args))
        start = segments[-1].end if segments else None
        if len(piece) == 4 and not _equal([h[2] for h in piece]):
            if curve_tolerance is None:
                raise SplineRefusedError(
                    "is a rational cubic that is not an elevated conic; only rational curves "
                    "of degree ≤ 2 can be held exactly (no curve tolerance was given to "
                    "approximate it)"
                )
            fit = _approximated(piece, start, curve_tolerance, approximating)
            cubics = [c for c in fit.cubics if not c.start == c.control1 == c.control2 == c.end]
            segments.extend(cubics)
            approximated = max(approximated, fit.bound)
            approximating += len(cubics)
            continue
        segment = _piece_segment(piece, start)
        if segment is not None:
            segments.append(segment)
    if not segments:
        raise SplineRefusedError("has no extent (all its pieces are points)")
    closed_segments, closed, gap = _closed(segments, points)
    # the closing move shifts the last end by the gap, and the last segment by at most that
    return SplineSegments(closed_segments, closed, (), approximated + gap, approximating)


def _local_piece(
    points: Sequence[Point], scales: Sequence[float], knots: Sequence[float], k: int,
    args: Sequence[Sequence[float]],
) -> tuple[Point, list[Homogeneous]]:  # fmt: skip
    """The span ``k``'s Bézier control points blossomed relative to its first control point
    (returned with them): a translation commutes with blossoming, and relative to it the
    blossoms round with the span's own extent, not with its distance from the origin."""
    degree = len(args) - 1
    origin = points[k - degree]
    local = [
        (w * (x - origin[0]), w * (y - origin[1]), w)
        for (x, y), w in zip(points[k - degree : k + 1], scales[k - degree : k + 1], strict=True)
    ]
    return origin, [_blossom(local, knots, degree, k, arg) for arg in args]


def _approximated(
    piece: list[Homogeneous], start: Point | None, tolerance: float, used: int
) -> CubicFit:
    """The cubics standing for a rational cubic piece (``dxf_rational.py``), within the
    spline's budget of ``MAX_APPROXIMATING_CUBICS`` of which ``used`` are taken."""
    if not (math.isfinite(tolerance) and tolerance > 0.0):
        raise SplineRefusedError(f"curve tolerance {tolerance!r} is not a number > 0")
    first = start if start is not None else _cartesian(piece[0])
    fit = rational_cubic_fit(piece, first, tolerance, MAX_APPROXIMATING_CUBICS - used)
    if fit is None:
        raise SplineRefusedError(
            f"is a rational cubic that needs more than {MAX_APPROXIMATING_CUBICS} cubics to "
            f"be within {tolerance:.3g} of it"
        )
    return fit


def _validate(data: SplineData) -> None:
    degree, knots, points, weights = data
    if degree < 1:
        raise SplineRefusedError(
            f"its {len(knots)} knots and {len(points)} control points make degree {degree}"
        )
    if degree > MAX_DEGREE:
        raise SplineRefusedError(f"degree {degree} is above {MAX_DEGREE}")
    if not all(math.isfinite(v) for v in (*knots, *weights, *(c for p in points for c in p))):
        raise SplineRefusedError("has a number that is not finite")
    if any(u > v for u, v in itertools.pairwise(knots)):
        raise SplineRefusedError("its knots decrease")
    if weights and len(weights) != len(points):
        raise SplineRefusedError(f"has {len(weights)} weights for {len(points)} control points")
    if any(w <= 0.0 for w in weights):
        raise SplineRefusedError("has a weight that is not > 0")
    # the knots do not decrease, so equal inner knots are neighbours: one pass counts them
    for knot, run in itertools.groupby(knots[degree + 1 : len(points)]):
        multiplicity = sum(1 for _ in run)
        if multiplicity > degree:
            raise SplineRefusedError(
                f"knot {knot!r} repeats {multiplicity} times, more than its degree "
                f"{degree}: the curve may break there"
            )


def _blossom(
    span: Sequence[Homogeneous], knots: Sequence[float], degree: int, k: int,
    args: Sequence[float],
) -> Homogeneous:  # fmt: skip
    """The blossom of the span ``[U[k], U[k+1])``'s curve at ``args`` (de Boor's algorithm,
    level ``r`` evaluated at ``args[r−1]``), from the span's control points ``P[k−p … k]``."""
    d = list(span)
    for r in range(1, degree + 1):
        u = args[r - 1]
        for j in range(degree, r - 1, -1):
            i = k - degree + j
            alpha = (u - knots[i]) / (knots[i + degree + 1 - r] - knots[i])
            p, q = d[j - 1], d[j]
            d[j] = (
                (1.0 - alpha) * p[0] + alpha * q[0],
                (1.0 - alpha) * p[1] + alpha * q[1],
                (1.0 - alpha) * p[2] + alpha * q[2],
            )
    return d[degree]


def _cartesian(h: Homogeneous) -> Point:
    return Point(h[0] / h[2], h[1] / h[2])


def _piece_segment(piece: list[Homogeneous], start: Point | None) -> Segment | None:
    """One Bézier piece (homogeneous control points) as a segment starting at ``start`` (the
    previous piece's end, kept bit for bit), or None when the piece is a single point."""
    first = start if start is not None else _cartesian(piece[0])
    last = _cartesian(piece[-1])
    weights = [h[2] for h in piece]
    if len(piece) == 4:  # equal weights: the caller lowered or approximated any other
        c1, c2 = _cartesian(piece[1]), _cartesian(piece[2])
        if first == last == c1 == c2:
            return None
        return Cubic(first, c1, c2, last)
    if len(piece) == 2:
        return None if first == last else Line(first, last)
    control = _cartesian(piece[1])
    w = weights[1] / math.sqrt(weights[0] * weights[2])
    if first == last == control:
        return None
    if abs(w - 1.0) <= WEIGHT_RTOL:
        return Quadratic(first, control, last)
    if w > 1.0:
        raise SplineRefusedError(f"has a hyperbolic piece (normalised weight {w:.17g} > 1)")
    return _elliptical(first, control, last, w)


def _equal(weights: Sequence[float]) -> bool:
    return all(abs(w - weights[0]) <= WEIGHT_RTOL * weights[0] for w in weights)


def _lowered(piece: list[Homogeneous], local: tuple[Point, list[Homogeneous]]) -> list[Homogeneous]:
    """A rational cubic ``piece`` as the rational quadratic it was elevated from, or the
    piece itself when it is not one to rounding; ``local`` is the same piece blossomed
    relative to a point near it (:func:`_local_piece`), where the test is made. Degree
    elevation gives ``H1 = (G0 + 2·G1)/3`` and ``H2 = (2·G1 + G2)/3``, so ``G1`` is ``(3·H1 −
    H0)/2`` and must equal ``(3·H2 − H3)/2``; their difference ``Δ`` moves ``H2`` by ``⅔·Δ``
    from the elevated quadratic's, and so the curve by

        R(t) − Q(t) = 2·t²·(1 − t)·(Δ_xy − (R(t) − P0)·Δ_w) / w_Q(t)

    with points taken relative to ``P0`` (``H_i − w_i·P0``: translation-invariant),
    ``|R(t) − P0| ≤ E = max_i |P_i − P0|`` (the convex hull) and ``w_Q(t) ≥ min(w0, g1,
    w3)``. The piece is lowered only when that bound is within ``LOWERING_ULPS`` of ``E``:
    the rounding of its own numbers."""
    origin, near = local
    w0 = near[0][2]
    p0x, p0y = near[0][0] / w0, near[0][1] / w0
    h0, h1, h2, h3 = ((x - w * p0x, y - w * p0y, w) for x, y, w in near)
    g1 = tuple((3.0 * b - a) / 2.0 for a, b in zip(h0, h1, strict=True))
    other = tuple((3.0 * b - a) / 2.0 for a, b in zip(h3, h2, strict=True))
    w_min = min(w0, g1[2], h3[2])
    if not w_min > 0.0:
        return piece
    extent = max(math.hypot(x / w, y / w) for x, y, w in (h1, h2, h3))
    dx, dy, dw = (x - y for x, y in zip(other, g1, strict=True))
    bound = _B2_TWO_THIRDS_MAX * (math.hypot(dx, dy) + extent * abs(dw)) / w_min
    if not bound <= LOWERING_ULPS * sys.float_info.epsilon * extent:
        return piece
    # G1 back where the piece is: + w·(P0 + origin)
    x0, y0 = p0x + origin[0], p0y + origin[1]
    return [piece[0], (g1[0] + g1[2] * x0, g1[1] + g1[2] * y0, g1[2]), piece[3]]


def _elliptical(p0: Point, p1: Point, p2: Point, w: float) -> Segment:
    """The ellipse arc of the rational quadratic ``(p0, p1, p2)`` with weights ``(1, w, 1)``,
    ``0 < w < 1`` (module docstring)."""
    mx, my = (p0[0] + p2[0]) / 2.0, (p0[1] + p2[1]) / 2.0
    w2 = w * w
    cx, cy = (mx - w2 * p1[0]) / (1.0 - w2), (my - w2 * p1[1]) / (1.0 - w2)
    sx, sy = (mx + w * p1[0]) / (1.0 + w), (my + w * p1[1]) / (1.0 + w)
    alpha = math.acos(w)
    sin_alpha = math.sqrt(1.0 - w2)
    ax, ay = sx - cx, sy - cy
    bx, by = (mx - p0[0]) / sin_alpha, (my - p0[1]) / sin_alpha
    unit = CircularArc(
        Point(w, -sin_alpha), Point(w, sin_alpha), Point(0.0, 0.0), 1.0, -alpha, 2.0 * alpha
    )
    try:
        arc = transform_segment(unit, Affine(ax, ay, bx, by, cx, cy))
    except SingularMapError as exc:
        if _between(p0, p1, p2):
            return Line(p0, p2)  # a conic with collinear control points is its chord
        raise SplineRefusedError("has a degenerate conic piece (collinear control points)") from exc
    return arc._replace(start=p0, end=p2)


def _between(p0: Point, p1: Point, p2: Point) -> bool:
    dx, dy = p2[0] - p0[0], p2[1] - p0[1]
    t = ((p1[0] - p0[0]) * dx + (p1[1] - p0[1]) * dy) / (dx * dx + dy * dy or 1.0)
    return 0.0 <= t <= 1.0


def _closed(
    segments: list[Segment], points: Sequence[Point]
) -> tuple[tuple[Segment, ...], bool, float]:
    """The segments, whether the curve closes, and how far its end was moved: when its end
    is within ``CLOSE_RTOL`` of its start, relative to the extent of its control points
    ``points`` (the curve lies in their hull; its distance from the origin does not count),
    or within the rounding of its coordinates, the last end is set to the first start,
    exactly."""
    first, last = segments[0].start, segments[-1].end
    xs, ys = [p[0] for p in points], [p[1] for p in points]
    extent = max(max(xs) - min(xs), max(ys) - min(ys))
    magnitude = max(abs(c) for c in (*first, *last))
    allowed = max(CLOSE_RTOL * extent, CLOSE_ULPS * sys.float_info.epsilon * magnitude)
    gap = math.hypot(last[0] - first[0], last[1] - first[1])
    closes = gap <= allowed and not (len(segments) == 1 and isinstance(segments[0], Line))
    if closes and last != first:
        segments[-1] = segments[-1]._replace(end=first)
        return tuple(segments), True, gap
    return tuple(segments), closes, 0.0
