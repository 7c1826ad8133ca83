"""The plan of a program: one block per segment of the arc spline, each the first of its
candidate forms (line or arc; ``R``, then ``I``/``J``, then the chord) whose read-back path
stays within ``tolerance + q`` of its spiral piece, measured exactly."""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import NamedTuple

import numpy as np
import numpy.typing as npt

from arcspline.geometry import ArcSpline, Curve, SegmentColumns

from .arcs import MAX_ARC_WORD, ArcRows, ArcWords, encode_rows, words_at
from .lattice import FloatArray, IntArray, to_lattice
from .options import MAX_COORDINATE, GcodeError, GcodeOptions

#: Sweeps below this are cut as lines: Grbl (single precision) reads a clockwise sweep under
#: 5e-7 rad as a full circle; this leaves a factor of 20.
MIN_SWEEP_RAD = 1e-5
#: Arcs with a radius below this many units in the last place are cut as lines: their
#: rounded centre would carry no information.
MIN_RADIUS_ULPS = 2
#: Arcs with a radius below this are cut as lines: LinuxCNC refuses an arc whose radius, as
#: read from its words, is below its RADIUS_TOLERANCE (0.00005 in, 1.27 µm) as a "zero-radius
#: arc"; twice that leaves room for the rounding of the words.
MIN_RADIUS: dict[str, float] = {"mm": 2 * 0.00127, "inch": 2 * 0.00005}


class Plan(NamedTuple):
    """The rounded start and one cut move per segment: ``G1`` where ``arcs[i]`` is ``None``."""

    start: tuple[int, int]
    ends: list[tuple[int, int]]
    arcs: list[ArcWords | None]
    deviation: FloatArray


def _must_be_lines(
    cols: SegmentColumns, start: IntArray, end: IntArray, decimals: int, units: str
) -> npt.NDArray[np.bool_]:
    """The core's own lines, and arcs a controller could take for a full circle or refuse:
    rounded ends that coincide, a sweep below :data:`MIN_SWEEP_RAD`, a radius of a few units
    in the last place or below :data:`MIN_RADIUS`."""
    q = 10.0**-decimals
    return np.asarray(
        ~cols.is_arc
        | np.all(start == end, axis=1)
        | (np.abs(cols.sweep_rad) < MIN_SWEEP_RAD)
        | (cols.radius < max(MIN_RADIUS_ULPS * q, MIN_RADIUS[units])),
        dtype=np.bool_,
    )


def _flat_arcs(cols: SegmentColumns, decimals: int) -> npt.NDArray[np.bool_]:
    """Arcs whose sagitta ``2r·sin²(sweep/4)`` is below half a unit in the last place: the
    precision cannot tell them from their chord."""
    radius = np.where(cols.is_arc, cols.radius, 0.0)  # lines carry an infinite radius
    sagitta = 2.0 * radius * np.sin(0.25 * np.abs(cols.sweep_rad)) ** 2
    return np.asarray(cols.is_arc & (sagitta < 0.5 * 10.0**-decimals), dtype=np.bool_)


def _optional_lines(
    spline: ArcSpline, curve: Curve, options: GcodeOptions
) -> npt.NDArray[np.bool_]:
    """Arcs that ``min_arc_length``/``max_radius`` ask for as lines, where the chord keeps
    within the tolerance (measured before rounding, like the arcs themselves)."""
    cols = spline.columns
    wanted = np.zeros(len(cols), dtype=np.bool_)
    if options.min_arc_length is not None:
        wanted |= cols.length < options.min_arc_length
    if options.max_radius is not None:
        wanted |= cols.radius > options.max_radius
    wanted &= cols.is_arc
    rows = np.flatnonzero(wanted)
    if len(rows):
        dev = curve.line_deviations(
            cols.u_start[rows], cols.u_end[rows], cols.start[rows], cols.end[rows]
        )
        wanted[rows[dev > spline.tolerance]] = False
    return wanted


def _measure(
    curve: Curve,
    cols: SegmentColumns,
    rounded: FloatArray,
    rows: IntArray,
    arcs: Sequence[ArcWords | None],
) -> FloatArray:
    """The deviation of each block ``rows[k]`` (written as ``arcs[k]``) from its spiral piece;
    infinite for an arc that a controller would cut the long way round."""
    dev = np.empty(len(rows))
    u0, u1 = cols.u_start[rows], cols.u_end[rows]
    is_line = np.array([w is None for w in arcs], dtype=np.bool_)
    if np.any(is_line):
        r = rows[is_line]
        dev[is_line] = curve.line_deviations(u0[is_line], u1[is_line], rounded[r], rounded[r + 1])
    words = [w for w in arcs if w is not None]
    if words:
        on = ~is_line
        dev[on] = curve.circle_deviations(
            u0[on],
            u1[on],
            np.array([w.centre for w in words], dtype=np.float64),
            np.array([w.r_start for w in words]),
            np.array([w.r_end for w in words]),
        )
        wrong_way = np.abs(np.array([w.sweep_rad for w in words]) - cols.sweep_rad[rows[on]])
        dev[on] = np.where(wrong_way > 0.5 * math.pi, np.inf, dev[on])
    return dev


def plan_program(spline: ArcSpline, curve: Curve, options: GcodeOptions) -> Plan:
    """One block per segment: the first of its choices whose read-back path stays within
    ``tolerance + q`` of its spiral piece, measuring all segments at once per round."""
    d = options.resolved_decimals
    cols = spline.columns
    n = len(cols)
    if not curve.coordinate_scale < MAX_COORDINATE:
        raise GcodeError(
            "spiral", f"has coordinates beyond ±{MAX_COORDINATE:g}, too large to write"
        )
    # Joints are rounded once each, so consecutive blocks meet exactly; the ends are the
    # curve's own end points.
    joints = np.concatenate([[curve.start], cols.start[1:], [curve.end_point]], axis=0)
    lattice = to_lattice(joints, d)
    rounded = lattice / 10.0**d
    start, end = lattice[:-1], lattice[1:]
    limit = spline.tolerance + 10.0**-d
    must = _must_be_lines(cols, start, end, d, options.units)
    prefer = _flat_arcs(cols, d) | _optional_lines(spline, curve, options)
    choices: list[list[ArcWords | None]] = [[None] for _ in range(n)]
    rows = np.flatnonzero(~must)
    if len(rows):
        arcs = ArcRows(
            start[rows], end[rows], cols.center[rows], cols.radius[rows], cols.sweep_rad[rows]
        )
        forms = encode_rows(arcs, d, options.arc_format)
        for k, i in enumerate(rows.tolist()):
            ccw = bool(cols.sweep_rad[i] > 0.0)
            words: list[ArcWords | None] = [words_at(f, k, ccw) for f in forms if f.ok[k]]
            choices[i] = [None, *words] if prefer[i] else [*words, None]
    chosen: list[ArcWords | None] = [c[0] for c in choices]
    deviation = np.full(n, np.inf)
    rank = np.zeros(n, dtype=np.int64)
    rows = np.arange(n)
    while len(rows):
        deviation[rows] = _measure(curve, cols, rounded, rows, [chosen[i] for i in rows])
        over = rows[deviation[rows] > limit]
        rows = np.array([i for i in over if rank[i] + 1 < len(choices[i])], dtype=np.int64)
        for i in rows.tolist():
            rank[i] += 1
            chosen[i] = choices[i][rank[i]]
    worst = int(np.argmax(deviation))
    if not deviation[worst] <= limit:
        if not must[worst] and len(choices[worst]) == 1:
            raise GcodeError(
                "spiral",
                f"segment {worst} is an arc of radius {cols.radius[worst]:.6g} {options.units}, "
                f"too large to write (I, J and R are bounded by {MAX_ARC_WORD:g}), and its "
                f"chord would deviate from the curve by {deviation[worst]:.3g}, more than "
                f"tolerance + 10^-{d} = {limit:.3g}; a smaller tolerance gives smaller arcs",
            )
        raise GcodeError(
            "decimals",
            f"{d} decimals are too few for tolerance {spline.tolerance:g}: segment {worst} "
            f"would deviate from the curve by {deviation[worst]:.3g} {options.units}, more "
            f"than tolerance + 10^-{d} = {limit:.3g}; use more decimals or a larger tolerance",
        )
    return Plan(
        start=(int(lattice[0, 0]), int(lattice[0, 1])),
        ends=[(int(x), int(y)) for x, y in end],
        arcs=chosen,
        deviation=deviation,
    )
