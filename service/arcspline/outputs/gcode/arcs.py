"""Arcs on the lattice of representable numbers: the words (``I``/``J`` or ``R``) of an arc
between rounded end points, and the centre and radii a controller derives from them.

The centre is chosen for the *rounded* ends: on their perpendicular bisector, the point whose
circle fits the true arc best; for ``I``/``J``, the lattice point near it whose start and end
radii agree; for ``R``, its rounded radius, except near half circles.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import NamedTuple

import numpy as np
import numpy.typing as npt

from .lattice import FloatArray, IntArray
from .options import ArcFormat

#: Largest magnitude of a centre offset or radius written (I, J, R). A nearly straight arc
#: of a large spiral has a far centre; up to this bound (15 digits at 6 decimals) its
#: lattice point is still exact in double precision. Farther centres are cut as chords.
MAX_ARC_WORD = 1e9
#: ``R`` is not used for an arc whose sweep is within this of a half circle: there the
#: centre moves by ``δR / cos(sweep/2)`` for a rounding ``δR`` of the radius.
HALF_CIRCLE_MARGIN_DEG = 5.0


class ArcWords(NamedTuple):
    """One arc block as a controller reads it.

    ``offset`` is ``(I, J)``, the centre minus the rounded start, and ``radius`` the signed
    ``R`` word, both in units in the last place (integers); exactly one of them is set.
    ``centre``, ``r_start``, ``r_end`` and ``sweep_rad`` are what a controller computes from
    the words (world units).
    """

    ccw: bool
    offset: tuple[int, int] | None
    radius: int | None
    centre: tuple[float, float]
    r_start: float
    r_end: float
    sweep_rad: float


class ArcRows(NamedTuple):
    """Arcs to encode, one row each: rounded ends (lattice integers), true centre, radius and
    signed sweep."""

    start: IntArray
    end: IntArray
    centre: FloatArray
    radius: FloatArray
    sweep_rad: FloatArray


class EncodedArcs(NamedTuple):
    """Encoded arcs, one row each; ``ok`` is false where the form does not apply."""

    ok: npt.NDArray[np.bool_]
    words: IntArray  # (n, 2) I, J or (n, 1) R
    centre: FloatArray
    r_start: FloatArray
    r_end: FloatArray
    sweep_rad: FloatArray


#: Points of each arc at which fits are compared (ends included).
_FIT_POINTS = 9
_GOLDEN = (math.sqrt(5.0) - 1.0) / 2.0


def _controller_sweeps(
    start: FloatArray, end: FloatArray, centre: FloatArray, ccw: npt.NDArray[np.bool_]
) -> FloatArray:
    """The sweep a controller cuts from ``start`` to ``end`` about ``centre``, signed, of
    magnitude in ``(0, 2π]``: an end angle not strictly past the start is a full turn."""
    a = np.arctan2(start[:, 1] - centre[:, 1], start[:, 0] - centre[:, 0])
    b = np.arctan2(end[:, 1] - centre[:, 1], end[:, 0] - centre[:, 0])
    turn = 2.0 * np.pi
    up = np.where(b > a, b - a, b - a + turn)
    down = np.where(b < a, b - a, b - a - turn)
    return np.asarray(np.where(ccw, up, down), dtype=np.float64)


def _fit_points(arcs: ArcRows, start: FloatArray) -> FloatArray:
    """Points of each true arc, ``(n, _FIT_POINTS, 2)``, from the rounded start's angle."""
    c = arcs.centre
    a0 = np.arctan2(start[:, 1] - c[:, 1], start[:, 0] - c[:, 0])
    angle = a0[:, None] + arcs.sweep_rad[:, None] * np.linspace(0.0, 1.0, _FIT_POINTS)
    ring = np.stack([np.cos(angle), np.sin(angle)], axis=-1)
    return np.asarray(c[:, None, :] + arcs.radius[:, None, None] * ring, dtype=np.float64)


def _gap(
    points: FloatArray, centre: FloatArray, r_start: FloatArray, r_end: FloatArray
) -> FloatArray:
    """Largest distance from ``points`` (``(n, k, 2)``) to the circles of radius ``r_start``
    and ``r_end`` about ``centre`` (``(n, …, 2)``, broadcast)."""
    rho = np.hypot(points[..., 0] - centre[..., 0:1], points[..., 1] - centre[..., 1:2])
    far = np.maximum(np.abs(rho - r_start[..., None]), np.abs(rho - r_end[..., None]))
    return np.asarray(far.max(axis=-1), dtype=np.float64)


def _best_fit_centres(arcs: ArcRows, decimals: int) -> FloatArray:
    """For each arc, the centre on the perpendicular bisector of the rounded ends whose circle
    is nearest the true arc (minimax over :data:`_FIT_POINTS` points, by golden section).

    The search starts from the bisector point nearest the true centre; the window is wide
    where the shape barely depends on the centre (a flat arc) and narrow near half circles.
    """
    scale = 10.0**decimals
    s, e = arcs.start / scale, arcs.end / scale
    mid = 0.5 * (s + e)
    chord = e - s
    half = 0.5 * np.hypot(chord[:, 0], chord[:, 1])
    normal = np.stack([-chord[:, 1], chord[:, 0]], axis=1) / (2.0 * half[:, None])
    t0 = np.einsum("nj,nj->n", arcs.centre - mid, normal)
    bulge = np.maximum(1.0 - np.cos(0.5 * np.abs(arcs.sweep_rad)), 1e-300)
    width = np.clip(4.0 / scale / bulge, 1.0 / scale, 0.5 * arcs.radius)
    points = _fit_points(arcs, s)

    def misfit(t: FloatArray) -> FloatArray:
        centre = mid + t[:, None] * normal
        r = np.hypot(t, half)
        return _gap(points, centre, r, r)

    lo, hi = t0 - width, t0 + width
    x1, x2 = hi - _GOLDEN * (hi - lo), lo + _GOLDEN * (hi - lo)
    f1, f2 = misfit(x1), misfit(x2)
    for _ in range(48):
        left = f1 <= f2
        lo, hi = np.where(left, lo, x1), np.where(left, x2, hi)
        new = np.where(left, hi - _GOLDEN * (hi - lo), lo + _GOLDEN * (hi - lo))
        fn = misfit(new)
        x1, x2 = np.where(left, new, x2), np.where(left, x1, new)
        f1, f2 = np.where(left, fn, f2), np.where(left, f1, fn)
    best = np.where(f1 <= f2, x1, x2)
    # Keep the nearest point unless the fit is clearly better: a flat arc fits many circles
    # about equally, and the one nearest the true centre keeps the true radius.
    better = misfit(best) < misfit(t0) - 0.05 / scale
    best = np.where(better, best, t0)
    return np.asarray(mid + best[:, None] * normal, dtype=np.float64)


def _encode_ij(arcs: ArcRows, ideal: FloatArray, decimals: int) -> EncodedArcs:
    """``I``/``J``: of the lattice points within one unit of the ideal centre, those whose
    start and end radii agree within ``q·min(1, √2·sin(|sweep|/2))`` (one always does), and
    of those the one whose circle is nearest the true arc."""
    scale = 10.0**decimals
    s, e = arcs.start / scale, arcs.end / scale
    base = np.rint((ideal - s) * scale)
    steps = np.array([(i, j) for i in (-1, 0, 1) for j in (-1, 0, 1)], dtype=np.float64)
    offset = base[:, None, :] + steps[None, :, :]  # (n, 9, 2), integers held exactly
    centre = s[:, None, :] + offset / scale
    near = np.hypot(*np.moveaxis(centre - ideal[:, None, :], -1, 0)) <= 1.0 / scale
    d = (arcs.end - arcs.start).astype(np.float64)[:, None, :]
    r_s = np.hypot(offset[..., 0], offset[..., 1])
    r_e = np.hypot(offset[..., 0] - d[..., 0], offset[..., 1] - d[..., 1])
    # r_s − r_e = (r_s² − r_e²) / (r_s + r_e) = (2·off − D)·D / (r_s + r_e), in units.
    mismatch = np.abs(np.sum((2.0 * offset - d) * d, axis=-1)) / np.maximum(r_s + r_e, 1.0)
    bound = np.minimum(1.0, math.sqrt(2.0) * np.sin(0.5 * np.abs(arcs.sweep_rad)))
    agree = near & (mismatch <= bound[:, None] * (1.0 + 1e-9))
    allowed = np.where(np.any(agree, axis=1)[:, None], agree, near)
    points = _fit_points(arcs, s)
    gap = _gap(points[:, None, :, :], centre, r_s / scale, r_e / scale)
    pick = np.argmin(np.where(allowed, gap, np.inf), axis=1)
    rows = np.arange(len(pick))
    chosen = centre[rows, pick]
    ccw = arcs.sweep_rad > 0.0
    return EncodedArcs(
        ok=np.ones(len(pick), dtype=np.bool_),
        words=offset[rows, pick].astype(np.int64),
        centre=chosen,
        r_start=r_s[rows, pick] / scale,
        r_end=r_e[rows, pick] / scale,
        sweep_rad=_controller_sweeps(s, e, chosen, ccw),
    )


def _encode_r(arcs: ArcRows, ideal: FloatArray, decimals: int) -> EncodedArcs:
    """``R``: the ideal circle's radius, rounded, negative past a half circle, with the
    centre a controller derives from it (LinuxCNC's ``arc_data_r``). Not used within
    :data:`HALF_CIRCLE_MARGIN_DEG` of a half circle, nor where the rounded radius no longer
    spans the chord."""
    scale = 10.0**decimals
    s, e = arcs.start / scale, arcs.end / scale
    major = np.abs(arcs.sweep_rad) > np.pi
    r_units = np.rint(np.hypot(*(ideal - s).T) * scale)
    abs_r = r_units / scale
    chord = e - s
    half = 0.5 * np.hypot(chord[:, 0], chord[:, 1])
    near_half = np.abs(np.degrees(np.abs(arcs.sweep_rad)) - 180.0) < HALF_CIRCLE_MARGIN_DEG
    ok = ~near_half & (r_units > 0) & (half < abs_r * (1.0 - 1e-9))
    ccw = arcs.sweep_rad > 0.0
    # Left of the chord for a minor anticlockwise arc; a major arc takes the other side.
    side = np.where(ccw != major, 1.0, -1.0)
    normal = side[:, None] * np.stack([-chord[:, 1], chord[:, 0]], axis=1) / (2.0 * half[:, None])
    offset = np.sqrt(np.maximum(abs_r**2 - half**2, 0.0))
    centre = 0.5 * (s + e) + offset[:, None] * normal
    return EncodedArcs(
        ok=ok,
        words=np.where(major, -r_units, r_units).astype(np.int64)[:, None],
        centre=centre,
        r_start=abs_r,
        r_end=abs_r,
        sweep_rad=_controller_sweeps(s, e, centre, ccw),
    )


def encode_rows(arcs: ArcRows, decimals: int, arc_format: ArcFormat) -> list[EncodedArcs]:
    """The forms to try for each arc, best first: ``R`` (if asked for), then ``I``/``J``."""
    ideal = _best_fit_centres(arcs, decimals)
    forms = [_encode_ij(arcs, ideal, decimals)]
    if arc_format == "r":
        forms.insert(0, _encode_r(arcs, ideal, decimals))
    for form in forms:
        # A far centre (a nearly straight arc) may not be written; the chord is tried instead.
        form.ok[np.any(np.abs(form.words) >= MAX_ARC_WORD * 10.0**decimals, axis=1)] = False
    return forms


def words_at(form: EncodedArcs, i: int, ccw: bool) -> ArcWords:
    w = form.words[i]
    return ArcWords(
        ccw=ccw,
        offset=(int(w[0]), int(w[1])) if len(w) == 2 else None,
        radius=int(w[0]) if len(w) == 1 else None,
        centre=(float(form.centre[i, 0]), float(form.centre[i, 1])),
        r_start=float(form.r_start[i]),
        r_end=float(form.r_end[i]),
        sweep_rad=float(form.sweep_rad[i]),
    )


def encode_arc(
    start: tuple[int, int],
    end: tuple[int, int],
    centre: Sequence[float],
    radius: float,
    sweep_rad: float,
    decimals: int,
    arc_format: ArcFormat = "ij",
) -> ArcWords:
    """The words of one arc from the rounded ``start`` to the rounded ``end`` (lattice
    integers: units in the last place) that best reproduce the arc about ``centre`` of
    ``radius`` turning by ``sweep_rad`` (signed, anticlockwise positive).

    The ideal centre is the point of the rounded ends' perpendicular bisector whose circle
    is nearest the true arc. ``I``/``J``: a lattice point within one unit of it, with start
    and end radii within ``q·min(1, √2·sin(|sweep|/2))`` of each other. ``R`` (when
    ``arc_format`` is ``"r"``): the ideal radius, rounded, negative past a half circle; not
    within :data:`HALF_CIRCLE_MARGIN_DEG` of one, where ``I``/``J`` is returned instead.
    """
    if tuple(start) == tuple(end):
        raise ValueError("an arc needs distinct end points")
    arcs = ArcRows(
        start=np.array([start], dtype=np.int64),
        end=np.array([end], dtype=np.int64),
        centre=np.array([centre], dtype=np.float64),
        radius=np.array([radius], dtype=np.float64),
        sweep_rad=np.array([sweep_rad], dtype=np.float64),
    )
    forms = encode_rows(arcs, decimals, arc_format)
    form = next((f for f in forms if f.ok[0]), forms[-1])
    return words_at(form, 0, sweep_rad > 0.0)
