"""The broad phase: which pairs of bounding boxes overlap, found through a uniform grid in
numpy rather than by trying every pair (docs/offsets.md §4).

Each box is entered in every grid cell it covers; pairs are drawn within each cell and kept
when their boxes overlap (each pair once: in the cell of its overlap's lower left corner).
The cell is the median box size (or a sixth of the grown boxes' median size, when they are
grown by a margin far larger than the others), so a box covers few cells; a box that would
cover more than ``_MAX_CELLS`` cells (a long arc across the drawing) is paired by a direct
vectorised test against every box instead.
"""

from __future__ import annotations

import numpy as np

from ..path_spline import IntArray
from ..spline import FloatArray

#: A box covering more grid cells than this is tested against all boxes directly.
_MAX_CELLS = 64
#: A box of the median size of the grown set covers about this many cells across.
_GROWN_CELLS = 6
#: The grid has at most this many cells across, whatever the spread of the boxes.
_MAX_ACROSS = 1 << 20
#: Box pairs tested at once for the large boxes (bounds the memory to ~10 MB).
_CHUNK = 1 << 23


def overlapping(
    a: FloatArray, b: FloatArray | None = None, margin: float = 0.0
) -> tuple[IntArray, IntArray]:
    """Pairs ``(i, j)`` of boxes (rows x_min, y_min, x_max, y_max) that overlap once ``a``'s
    are grown by ``margin``: ``i`` indexes ``a``, ``j`` indexes ``b``; with ``b`` omitted,
    the pairs of ``a`` with itself, ``i < j``."""
    same = b is None
    grown = a + np.array([-margin, -margin, margin, margin])
    other = grown if b is None else b
    empty = np.zeros(0, dtype=np.int64)
    if not len(grown) or not len(other):
        return empty, empty
    both = np.vstack([grown, other])
    span = float(max(both[:, 2].max() - both[:, 0].min(), both[:, 3].max() - both[:, 1].min()))
    # Boxes grown by a margin far larger than the boxes of the other set cover at most about
    # 7 × 7 cells: few enough to enter, small enough that a cell holds few of the others.
    cell = max(_median_size(other), _median_size(grown) / _GROWN_CELLS, span / _MAX_ACROSS, 1e-300)
    origin = both[:, :2].min(axis=0)
    ia, ja = _cells(grown, origin, cell)
    ib, jb = _cells(other, origin, cell)
    big_a, big_b = _big(grown, origin, cell), _big(other, origin, cell)
    i, j, key = _same_cell(ia, ja, ib, jb)
    keep = _overlap_rows(grown[i], other[j])
    i, j, key = i[keep], j[keep], key[keep]
    # Each pair once: in the cell holding the lower left corner of the boxes' overlap.
    corner = np.maximum(grown[i, :2], other[j, :2])
    keep = key == _key(corner, origin, cell)
    if same:  # both orders were drawn
        keep &= i < j
    found_i, found_j = [i[keep]], [j[keep]]
    for rows, against, flip in ((np.flatnonzero(big_a), other, False),
                                (np.flatnonzero(big_b), grown, True)):  # fmt: skip
        if flip and same:
            break  # the same boxes: the first pass found these pairs
        for chunk in np.array_split(rows, max(1, len(rows) * len(against) // _CHUNK)):
            k, hit = np.nonzero(_overlap_grid(grown[chunk] if not flip else other[chunk], against))
            # a pair of two large boxes is found by the pass over the first set only
            if flip:
                mine = ~big_a[hit]
            elif same:
                mine = ~big_a[hit] | (chunk[k] < hit)
            else:
                mine = np.ones(len(k), dtype=bool)
            k, hit = k[mine], hit[mine]
            found_i.append(chunk[k] if not flip else hit)
            found_j.append(hit if not flip else chunk[k])
    i = np.concatenate(found_i).astype(np.int64)
    j = np.concatenate(found_j).astype(np.int64)
    if same:
        i, j = np.minimum(i, j), np.maximum(i, j)
        keep = i < j
        i, j = i[keep], j[keep]
    return i, j


def _key(points: FloatArray, origin: FloatArray, cell: float) -> IntArray:
    """The grid cell key of each point."""
    xy = np.floor((points - origin) / cell).astype(np.int64)
    return np.asarray(xy[:, 0] * (_MAX_ACROSS * 4) + xy[:, 1])


def _median_size(boxes: FloatArray) -> float:
    return float(np.median(np.maximum(boxes[:, 2] - boxes[:, 0], boxes[:, 3] - boxes[:, 1])))


def _big(boxes: FloatArray, origin: FloatArray, cell: float) -> np.ndarray:
    lo = np.floor((boxes[:, :2] - origin) / cell)
    hi = np.floor((boxes[:, 2:] - origin) / cell)
    count = (hi[:, 0] - lo[:, 0] + 1) * (hi[:, 1] - lo[:, 1] + 1)
    return np.asarray(count > _MAX_CELLS)


def _cells(boxes: FloatArray, origin: FloatArray, cell: float) -> tuple[IntArray, IntArray]:
    """(box, cell key) for every grid cell each small box covers."""
    lo = np.floor((boxes[:, :2] - origin) / cell).astype(np.int64)
    hi = np.floor((boxes[:, 2:] - origin) / cell).astype(np.int64)
    nx, ny = hi[:, 0] - lo[:, 0] + 1, hi[:, 1] - lo[:, 1] + 1
    count = np.where(nx * ny > _MAX_CELLS, 0, nx * ny)
    box = np.repeat(np.arange(len(boxes)), count)
    k = np.arange(len(box)) - np.repeat(np.cumsum(count) - count, count)
    x = lo[box, 0] + k % nx[box]
    y = lo[box, 1] + k // nx[box]
    return box, x * (_MAX_ACROSS * 4) + y


def _same_cell(
    ia: IntArray, ka: IntArray, ib: IntArray, kb: IntArray
) -> tuple[IntArray, IntArray, IntArray]:
    """Every pair (a entry, b entry) that shares a cell key, with the key."""
    order_a, order_b = np.argsort(ka, kind="stable"), np.argsort(kb, kind="stable")
    ka, ia, kb, ib = ka[order_a], ia[order_a], kb[order_b], ib[order_b]
    keys = np.intersect1d(ka, kb)
    a0, a1 = np.searchsorted(ka, keys), np.searchsorted(ka, keys, side="right")
    b0, b1 = np.searchsorted(kb, keys), np.searchsorted(kb, keys, side="right")
    na, nb = a1 - a0, b1 - b0
    per_key = na * nb
    key_of = np.repeat(np.arange(len(keys)), per_key)
    k = np.arange(len(key_of)) - np.repeat(np.cumsum(per_key) - per_key, per_key)
    left = ia[a0[key_of] + k // nb[key_of]]
    right = ib[b0[key_of] + k % nb[key_of]]
    return left, right, keys[key_of]


def _overlap_grid(a: FloatArray, b: FloatArray) -> np.ndarray:
    """Whether box ``a[i]`` overlaps box ``b[j]``, as an ``(len(a), len(b))`` array."""
    return np.asarray(
        (b[None, :, 0] <= a[:, None, 2]) & (a[:, None, 0] <= b[None, :, 2])
        & (b[None, :, 1] <= a[:, None, 3]) & (a[:, None, 1] <= b[None, :, 3])
    )  # fmt: skip


def _overlap_rows(a: FloatArray, b: FloatArray) -> np.ndarray:
    return np.asarray(
        (b[:, 0] <= a[:, 2]) & (a[:, 0] <= b[:, 2]) & (b[:, 1] <= a[:, 3]) & (a[:, 1] <= b[:, 3])
    )
