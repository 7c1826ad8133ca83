"""Recursive subdivision (paper §5), run breadth-first over a whole batch of spirals.

``ApproxCubicSpiral`` keeps a piece's biarc when its deviation δ ≤ τ and otherwise splits the
piece at ``u_d``, where δ occurs. The recursion tree of each spiral is walked level by level;
every level of every spiral in the batch is one set of numpy operations over all pending
pieces, so the Python overhead is per level, not per piece or per spiral. The pieces a spiral
keeps are exactly those of the depth-first recursion; they are put back in parameter order.
"""

from __future__ import annotations

from dataclasses import dataclass, fields
from typing import TypeVar

import numpy as np
import numpy.typing as npt

from .biarc import Biarcs, incentre_biarcs
from .deviation import Deviation, max_deviation, split_parameter
from .types import FloatArray

IntArray = npt.NDArray[np.intp]

#: A level cap far beyond any real recursion depth: a piece that cannot be split any further
#: in double precision stops the spiral (``precision`` failure) long before this.
MAX_LEVELS = 2_000

_EPS = float(np.finfo(np.float64).eps)

_T = TypeVar("_T", Biarcs, Deviation)


@dataclass(frozen=True, slots=True)
class Kept:
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


def subdivide(
    k: FloatArray, m: FloatArray, tolerance: FloatArray, max_biarcs: int
) -> Subdivision:
    """Walton & Meek's subdivision for canonical spirals ``(k, m)`` at canonical tolerances.

    A spiral stops with ``segment_limit`` as soon as the biarcs it has kept plus the pieces
    still pending exceed ``max_biarcs`` (each pending piece yields at least one biarc).
    """
    n = k.shape[0]
    failure = [""] * n
    failed = np.zeros(n, dtype=bool)
    kept_count = np.zeros(n, dtype=np.intp)
    spiral = np.arange(n, dtype=np.intp)
    u0, u1 = np.zeros(n), np.ones(n)
    kept: list[tuple[IntArray, Biarcs, Deviation]] = []
    for _ in range(MAX_LEVELS):
        if spiral.size == 0:
            break
        kk, mm = k[spiral], m[spiral]
        biarcs = incentre_biarcs(kk, mm, u0, u1)
        deviation = max_deviation(kk, mm, biarcs, split_parameter(kk, mm, biarcs))
        ok = deviation.value <= tolerance[spiral]
        if ok.any():
            kept.append((spiral[ok], _take(biarcs, ok), _take(deviation, ok)))
            kept_count += np.bincount(spiral[ok], minlength=n)
        split = ~ok
        spiral, lo, hi, at = spiral[split], u0[split], u1[split], deviation.u[split]
        stuck = (at - lo <= 4.0 * _EPS * hi) | (hi - at <= 4.0 * _EPS * hi)
        _fail(failure, failed, spiral[stuck], "precision")
        pending = 2 * np.bincount(spiral, minlength=n)
        _fail(failure, failed, np.flatnonzero(kept_count + pending > max_biarcs), "segment_limit")
        live = ~failed[spiral]
        spiral, lo, hi, at = spiral[live], lo[live], hi[live], at[live]
        spiral = np.concatenate([spiral, spiral])
        u0, u1 = np.concatenate([lo, at]), np.concatenate([at, hi])
    else:
        _fail(failure, failed, np.unique(spiral), "precision")
    return Subdivision(kept=_ordered(kept, failed), failure=failure)


def _fail(failure: list[str], failed: npt.NDArray[np.bool_], which: IntArray, why: str) -> None:
    for i in which.tolist():
        if not failed[i]:
            failed[i] = True
            failure[i] = why


def _ordered(kept: list[tuple[IntArray, Biarcs, Deviation]], failed: npt.NDArray[np.bool_]) -> Kept:
    if not kept:
        empty = np.zeros(0)
        return Kept(
            spiral=np.zeros(0, dtype=np.intp),
            biarcs=Biarcs(*([empty] * len(fields(Biarcs)))),
            deviation=Deviation(*([empty] * len(fields(Deviation)))),
        )
    spiral = np.concatenate([s for s, _, _ in kept])
    biarcs = _concat([b for _, b, _ in kept])
    deviation = _concat([d for _, _, d in kept])
    order = np.lexsort((biarcs.u0, spiral))
    order = order[~failed[spiral[order]]]
    return Kept(spiral=spiral[order], biarcs=_take(biarcs, order), deviation=_take(deviation, order))


def _take(columns: _T, index: npt.NDArray[np.bool_] | IntArray) -> _T:
    return type(columns)(*(getattr(columns, f.name)[index] for f in fields(columns)))


def _concat(parts: list[_T]) -> _T:
    first = parts[0]
    return type(first)(
        *(np.concatenate([getattr(p, f.name) for p in parts]) for f in fields(first))
    )
