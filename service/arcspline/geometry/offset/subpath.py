"""The offset of one chain of lines and arcs (docs/offsets.md §1–§5): the raw offset, the
global step, the kept slices stitched into loops (closed chains) or pieces (open ones)."""

from __future__ import annotations

import math
from collections.abc import Sequence

from ..curves.segments import Subpath
from ..errors import GeometryError
from ..segment_table import ARC_RTOL
from ..spline import Point
from .raw import RawChain, raw_offsets
from .stitch import attach, close, without_tiny
from .table import boxes, coordinate_scale, length, table_of
from .trim import Kept, Slice, keep_slices
from .types import Element, OffsetNote, OffsetOptions, Side, SubpathOffset

#: Two points closer than this fraction of the coordinate scale are one point.
POINT_RTOL = 1e-12
#: A slice nearer the source than ``d`` by more than this fraction of the coordinate scale is
#: removed (docs/offsets.md §5). A fitted arc's stored ends may lie ``ARC_RTOL`` (1e-9,
#: segment_table.py) off its circle, so its offset's ends may be that much nearer the
#: neighbouring source element than ``d``: ten times that keeps them.
KEEP_RTOL = 10 * ARC_RTOL
#: Slice ends closer than this fraction of the coordinate scale are one point when stitching:
#: a cluster of cut points (near-tangent crossings) is found as points a few ulps of the
#: crossing's ill-conditioning apart.
STITCH_RTOL = 1e-9


def offset_subpath(
    elements: Sequence[Element], closed: bool, options: OffsetOptions
) -> SubpathOffset:
    """The offset of a chain (``closed``: its last end is its first start) by
    ``options.distance`` to ``options.side`` ("left"/"right" of the direction of travel;
    callers resolve "inside"/"outside", docs/offsets.md §6). The result runs in the chain's
    direction of travel.

    >>> from arcspline.geometry.curves.segments import Line
    >>> square = [Line((0.0, 0.0), (1.0, 0.0)), Line((1.0, 0.0), (1.0, 1.0)),
    ...           Line((1.0, 1.0), (0.0, 1.0)), Line((0.0, 1.0), (0.0, 0.0))]
    >>> out = offset_subpath(square, True, OffsetOptions(0.25, "left"))
    >>> [tuple(s.start) for s in out.subpaths[0].segments]
    [(0.25, 0.25), (0.75, 0.25), (0.75, 0.75), (0.25, 0.75)]
    """
    (result,) = offset_chains([(elements, closed)], options)
    return result


def offset_chains(
    chains: Sequence[tuple[Sequence[Element], bool]],
    options: OffsetOptions,
    sides: Sequence[Side] | None = None,
) -> list[SubpathOffset]:
    """:func:`offset_subpath` of many chains at once (each to ``sides[i]``, default
    ``options.side``), every vectorised step running once for all of them: a drawing of
    thousands of small contours costs little more than one large one. Tolerances are relative
    to the coordinate scale of all the chains together."""
    _check(options)
    sides = [options.side] * len(chains) if sides is None else list(sides)
    for side in sides:
        if side not in ("left", "right"):
            raise GeometryError(
                "offset.side", f"a chain is offset to the left or right, got {side!r}"
            )
    d = options.distance
    present = [k for k, (elements, _) in enumerate(chains) if elements]
    if not present:
        return [SubpathOffset((), ()) for _ in chains]
    scale = max(d, max(coordinate_scale(table_of(chains[k][0])) for k in present))
    tol = POINT_RTOL * scale
    raws = raw_offsets(
        [(chains[k][0], chains[k][1], 1.0 if sides[k] == "left" else -1.0) for k in present],
        options,
        tol,
    )
    kept = keep_slices(
        [[r.element for r in raw.elements] for raw in raws],
        [chains[k][1] for k in present],
        [chains[k][0] for k in present],
        d,
        tol,
        KEEP_RTOL * scale,
        scale,
    )
    out = [SubpathOffset((), ()) for _ in chains]
    for k, raw, chain_kept in zip(present, raws, kept, strict=True):
        elements, closed = chains[k]
        out[k] = _result(elements, closed, raw, chain_kept, options, tol)
    return out


def _result(
    elements: Sequence[Element],
    closed: bool,
    raw: RawChain,
    kept: Kept,
    options: OffsetOptions,
    tol: float,
) -> SubpathOffset:
    """One chain's kept slices stitched, cleaned, filtered by size, with its notes."""
    notes: list[OffsetNote] = []
    if raw.collapsed:
        notes.append(_collapsed(raw.collapsed, options.distance))
    out = []
    near = STITCH_RTOL * tol / POINT_RTOL
    slices = [s for s in kept.slices if sum(length(e) for e in s.elements) > near]
    for chain, is_loop in _stitch(slices, closed, near):
        cleaned = without_tiny(chain, tol, is_loop)
        if cleaned and not _sliver(cleaned, is_loop, options.sliver, tol):
            out.append(Subpath(tuple(cleaned), is_loop))
    if closed and not out:  # what collapsed or was too narrow is all of it
        return SubpathOffset((), (_vanished(options.distance),))
    if closed and len(out) > 1:
        notes.append(OffsetNote("split", f"the offset splits into {len(out)} separate loops"))
    reached = {raw.elements[i].source for i in kept.used} | set(raw.collapsed)
    unreached = [k for k in range(len(elements)) if k not in reached]
    lost = sum(length(elements[k]) for k in unreached)
    if lost > tol:
        notes.append(_narrow(lost, len(unreached), options.distance))
    return SubpathOffset(tuple(out), tuple(notes))


def _check(options: OffsetOptions) -> None:
    d = options.distance
    if isinstance(d, bool) or not isinstance(d, int | float) or not (math.isfinite(d) and d > 0):
        raise GeometryError("offset.distance", f"must be a finite number > 0, got {d!r}")
    if options.join not in ("round", "mitre"):
        raise GeometryError("offset.join", f"must be 'round' or 'mitre', got {options.join!r}")
    limit = options.mitre_limit
    if not (isinstance(limit, int | float) and math.isfinite(limit) and limit >= 1.0):
        raise GeometryError("offset.mitre_limit", f"must be a finite number ≥ 1, got {limit!r}")
    sliver = options.sliver
    if not (isinstance(sliver, int | float) and math.isfinite(sliver) and sliver >= 0.0):
        raise GeometryError("offset.sliver", f"must be a finite number ≥ 0, got {sliver!r}")


def _stitch(slices: list[Slice], closed: bool, near: float) -> list[tuple[list[Element], bool]]:
    """Kept slices joined end to start (docs/offsets.md §5): closed loops, and for an open
    chain the open pieces (a slice whose start no other slice ends at begins one)."""
    index = _PointIndex(near)
    for k, s in enumerate(slices):
        index.add(s.start, k)
    used = [False] * len(slices)
    out: list[tuple[list[Element], bool]] = []
    if not closed:
        has_before = [False] * len(slices)
        for k, s in enumerate(slices):
            for m in index.find(s.end):
                if m != k:
                    has_before[m] = True
        firsts = [k for k in range(len(slices)) if not has_before[k]]
    else:
        firsts = []
    for k in [*firsts, *range(len(slices))]:
        if used[k]:
            continue
        chain: list[Element] = []
        current, loop = k, False
        while True:
            used[current] = True
            for e in slices[current].elements:
                attach(chain, e)
            if math.dist(slices[current].end, slices[k].start) <= near and (
                closed or k not in firsts
            ):
                loop = True
                break
            follow = [m for m in index.find(slices[current].end) if not used[m]]
            if not follow:
                break
            # Prefer the slice next along the raw chain (after ``current``, cyclically).
            current = min(follow, key=lambda m: (m - current) % len(slices))
        if loop:
            close(chain)
            out.append((chain, True))
        elif not closed:
            out.append((chain, False))
    return out


class _PointIndex:
    """Points by grid cell of size ``near``, to find those within ``near`` of a point."""

    def __init__(self, near: float) -> None:
        self._near = max(near, 1e-300)
        self._cells: dict[tuple[int, int], list[tuple[Point, int]]] = {}

    def _key(self, p: Point) -> tuple[int, int]:
        return (math.floor(p[0] / self._near), math.floor(p[1] / self._near))

    def add(self, p: Point, value: int) -> None:
        self._cells.setdefault(self._key(p), []).append((p, value))

    def find(self, p: Point) -> list[int]:
        kx, ky = self._key(p)
        return [
            v
            for dx in (-1, 0, 1)
            for dy in (-1, 0, 1)
            for q, v in self._cells.get((kx + dx, ky + dy), ())
            if math.dist(p, q) <= self._near
        ]


def _sliver(chain: list[Element], loop: bool, sliver: float, tol: float) -> bool:
    """Whether a result is smaller than ``sliver``: an open piece shorter, or a loop whose
    exact bounding box is narrower; or, whatever ``sliver``, no longer than ``tol``."""
    total = sum(length(e) for e in chain)
    if total <= tol or not loop:
        return total <= max(tol, sliver) if loop else total < max(tol, sliver)
    if sliver <= 0.0:
        return False
    box = boxes(table_of(chain))
    width = min(box[:, 2].max() - box[:, 0].min(), box[:, 3].max() - box[:, 1].min())
    return bool(width < sliver)


def _collapsed(which: list[int], d: float) -> OffsetNote:
    return OffsetNote(
        "collapsed",
        f"{len(which)} arc{'s' if len(which) != 1 else ''} of radius below the offset "
        f"distance {d:g} collapse{'s' if len(which) == 1 else ''} to nothing",
    )


def _vanished(d: float) -> OffsetNote:
    return OffsetNote(
        "vanished", f"the contour vanishes: it is nowhere wider than twice the distance {d:g}"
    )


def _narrow(lost: float, count: int, d: float) -> OffsetNote:
    return OffsetNote(
        "narrow",
        f"the offset cannot reach {lost:.6g} of the contour's length ({count} "
        f"element{'s' if count != 1 else ''}): features narrower than the tool "
        f"(distance {d:g})",
    )
