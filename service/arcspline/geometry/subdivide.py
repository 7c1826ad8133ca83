"""Recursive subdivision (paper §5), run breadth-first over a whole batch of spirals.

``ApproxCubicSpiral`` keeps a piece's biarc when its deviation δ ≤ τ and otherwise splits the
piece at ``u_d``, where δ occurs. The recursion tree of each spiral is walked level by level;
every level of every spiral in the batch is one set of numpy operations over all pending
pieces, so the Python overhead is per level, not per piece or per spiral. The pieces a spiral
keeps are exactly those of the depth-first recursion; they are put back in parameter order.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import NamedTuple, TypeVar

import numpy as np
import numpy.typing as npt

from .biarc import Biarcs, incentre_biarcs
from .deviation import Deviation, max_deviation, split_parameter
from .types import FloatArray

IntArray = npt.NDArray[np.intp]

#: A level cap far beyond any real recursion depth: a piece that cannot be split any further
#: in double precision stops the spiral (``precision`` failure) long before this.
MAX_LEVELS = 2_000

#: A piece whose split point lies within this many ulps (of its end) of either end cannot be
#: split any further in double precision.
STUCK_ULPS = 4.0

_EPS = float(np.finfo(np.float64).eps)

_T = TypeVar("_T", Biarcs, Deviation)


class Kept(NamedTuple):
    """The biarcs a batch keeps, sorted by spiral then parameter (canonical frame)."""

    spiral: IntArray
    biarcs: Biarcs
    deviation: Deviation


@dataclass(frozen=True, slots=True)
class Subdivision:
    """What :func:`subdivide` found: the kept biarcs and, per spiral, why it stopped early.

    ``failure[i]`` is ``""`` for a spiral that finished, else ``"segment_limit"`` or
    ``"precision"`` (a piece became too short to split in double precision).
    """

    kept: Kept
    failure: list[str]


def subdivide(k: FloatArray, m: FloatArray, tolerance: FloatArray, max_biarcs: int) -> Subdivision:
    """Walton & Meek's subdivision for canonical spirals ``(k, m)`` at canonical tolerances.

    A spiral stops with ``segment_limit`` as soon as the biarcs it has kept plus the pieces
    still pending exceed ``max_biarcs`` (each pending piece yields at least one biarc).
    """
    n = k.shape[0]
    failure = [""] * n
    failed = np.zeros(n, dtype=bool)
    any_failed = False
    # One spiral (the latency case) counts in Python integers; a batch per spiral.
    kept_one = 0
    kept_count = np.zeros(n, dtype=np.intp)
    spiral = np.arange(n, dtype=np.intp)
    u0, u1 = np.zeros(n), np.ones(n)
    # Every level's pieces and which of them are split (the others are kept); the kept rows
    # are gathered once at the end, not field by field at every level.
    levels: list[tuple[IntArray, Biarcs, Deviation, npt.NDArray[np.bool_]]] = []
    for _ in range(MAX_LEVELS):
        if spiral.size == 0:
            break
        kk, mm = k[spiral], m[spiral]
        biarcs = incentre_biarcs(kk, mm, u0, u1)
        deviation = max_deviation(kk, mm, biarcs, split_parameter(kk, mm, biarcs))
        split = deviation.value > tolerance[spiral]
        levels.append((spiral, biarcs, deviation, split))
        split_count = int(np.count_nonzero(split))
        if split_count == 0:
            break
        going = np.flatnonzero(split)
        spiral, lo, hi, at = spiral[going], u0[going], u1[going], deviation.u[going]
        # A piece too short to split in double precision stops its spiral.
        stuck = np.minimum(at - lo, hi - at) <= STUCK_ULPS * _EPS * hi
        if np.count_nonzero(stuck):
            any_failed = True
            _fail(failure, failed, spiral[stuck], "precision")
        # Each pending piece yields at least one more biarc.
        if n == 1:
            kept_one += split.size - split_count
            if kept_one + 2 * split_count > max_biarcs:
                any_failed = True
                _fail(failure, failed, spiral[:1], "segment_limit")
        else:
            pending = np.bincount(spiral, minlength=n)
            kept_count += np.bincount(levels[-1][0], minlength=n) - pending
            over = kept_count + 2 * pending > max_biarcs
            if np.count_nonzero(over):
                any_failed = True
                _fail(failure, failed, np.flatnonzero(over), "segment_limit")
        if any_failed:
            going = np.flatnonzero(~failed[spiral])
            spiral, lo, hi, at = spiral[going], lo[going], hi[going], at[going]
        spiral = np.concatenate((spiral, spiral))
        u0, u1 = np.concatenate((lo, at)), np.concatenate((at, hi))
    else:
        _fail(failure, failed, np.unique(spiral), "precision")
    return Subdivision(kept=_ordered(levels, failed), failure=failure)


def _fail(failure: list[str], failed: npt.NDArray[np.bool_], which: IntArray, why: str) -> None:
    for i in which.tolist():
        if not failed[i]:
            failed[i] = True
            failure[i] = why


def _ordered(
    levels: list[tuple[IntArray, Biarcs, Deviation, npt.NDArray[np.bool_]]],
    failed: npt.NDArray[np.bool_],
) -> Kept:
    """The kept pieces of spirals that did not fail, by spiral then parameter."""
    if not levels:
        empty = np.zeros(0)
        return Kept(
            spiral=np.zeros(0, dtype=np.intp),
            biarcs=Biarcs(*([empty] * len(Biarcs._fields))),
            deviation=Deviation(*([empty] * len(Deviation._fields))),
        )
    spiral = np.concatenate([s for s, _, _, _ in levels])
    split = np.concatenate([o for _, _, _, o in levels])
    u0 = np.concatenate([b.u0 for _, b, _, _ in levels])
    keep = np.flatnonzero(~(split | failed[spiral]))
    order = keep[np.lexsort((u0[keep], spiral[keep]))]
    biarcs = _gather([b for _, b, _, _ in levels], order)
    deviation = _gather([d for _, _, d, _ in levels], order)
    return Kept(spiral=spiral[order], biarcs=biarcs, deviation=deviation)


def merge(parts: list[Kept]) -> Kept:
    """Kept biarcs from several sources as one, by spiral (each part is in parameter order
    within each of its spirals, and no two parts share a spiral)."""
    if len(parts) == 1:
        return parts[0]
    spiral = np.concatenate([p.spiral for p in parts])
    order = np.argsort(spiral, kind="stable")
    return Kept(
        spiral=spiral[order],
        biarcs=_gather([p.biarcs for p in parts], order),
        deviation=_gather([p.deviation for p in parts], order),
    )


def _take(columns: _T, index: npt.NDArray[np.bool_] | IntArray) -> _T:
    return type(columns)(*(column[index] for column in columns))


def _gather(parts: list[_T], order: IntArray) -> _T:
    """Rows ``order`` of the parts stacked end to end."""
    first = parts[0]
    if len(parts) == 1:
        return _take(first, order)
    return type(first)(*(np.concatenate(column)[order] for column in zip(*parts, strict=True)))
