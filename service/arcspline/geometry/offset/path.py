"""The offset of a fitted path, every subpath, fitted again (docs/offsets.md §6)."""

from __future__ import annotations

from collections.abc import Sequence
from typing import NamedTuple

from ..curves.segments import Path, Subpath
from ..errors import GeometryError
from ..limits import Limits
from ..path_spline import PathSpline
from ..paths import approximate_path
from .chain import crossings, elements_of, excise_loops, meets_itself, signed_area
from .subpath import offset_chains
from .types import Element, OffsetNote, OffsetOptions, Side


class OffsetPath(NamedTuple):
    """A path's offset: the offset subpaths fitted again (``None`` only if there are none,
    which :func:`offset_path` refuses instead), each output subpath's source subpath, the
    notes by source subpath, and the source fit's largest deviation — the offset lies within
    it of the exact offset of what was drawn (docs/offsets.md §6)."""

    spline: PathSpline | None
    origin: tuple[int, ...]
    notes: tuple[tuple[int, OffsetNote], ...]
    source_max_deviation: float


class Contours(NamedTuple):
    """A fitted path's subpaths as chains of lines and arcs, ready to offset: each with its
    loops shorter than twice the tolerance cut out (docs/offsets.md §2), whether it still
    meets itself, and how far the cutting moved any chain (``moved``: half the longest loop
    cut out), which adds to the deviation bound."""

    chains: tuple[tuple[Element, ...], ...]
    closed: tuple[bool, ...]
    crossed: tuple[bool, ...]
    loops: tuple[float, ...]  # per chain: the length of the longest loop cut out, or 0

    @property
    def moved(self) -> float:
        return 0.5 * max(self.loops, default=0.0)

    def notes(self) -> list[tuple[int, OffsetNote]]:
        """A note for every chain that had loops cut out, saying how far that moved it."""
        return [
            (i, OffsetNote(
                "loop",
                f"closes over itself by a loop {loop:.3g} long (the drawing's rounding), cut "
                f"out: the tool may cut into that loop by up to {0.5 * loop:.3g}",
            ))
            for i, loop in enumerate(self.loops)
            if loop > 0.0
        ]  # fmt: skip


def contours_of(spline: PathSpline) -> Contours:
    """Every subpath of ``spline`` as a chain (:func:`elements_of`), tiny loops cut out."""
    sources = [elements_of(sub.spline) for sub in spline.subpaths]
    closed = tuple(sub.closed for sub in spline.subpaths)
    crossed = meets_itself(list(zip(sources, closed, strict=True)))
    chains: list[tuple[Element, ...]] = []
    loops: list[float] = []
    for elements, is_closed, hit in zip(sources, closed, crossed, strict=True):
        loop = 0.0
        if hit:
            # Loops shorter than twice the tolerance lie within it of a point: the drawing's
            # rounding (an outline closed over itself by a hair), cut out before offsetting.
            excised = excise_loops(elements, is_closed, 2.0 * spline.tolerance)
            loop = excised.longest_loop
            elements = excised.elements
        chains.append(tuple(elements))
        loops.append(loop)
    return Contours(tuple(chains), closed, tuple(crossed), tuple(loops))


#: The note of an open contour asked inside/outside, which has neither.
_LEFT_OUT = OffsetNote("open", "is open: it has no inside or outside; left out")


def offset_path(spline: PathSpline, options: OffsetOptions, limits: Limits) -> OffsetPath:
    """Offset every subpath of a fitted path (docs/offsets.md §6): "inside"/"outside" of a
    closed contour is its left when it runs anticlockwise (positive :func:`signed_area`),
    else its right; open contours take only "left"/"right". The results are fitted again at
    the source's tolerance and strategy, so input lines and arcs come back as themselves.

    An open contour, which has no inside or outside, is left out with a note naming it
    (kind ``open``) when one is asked for, as is a contour that vanishes. Raises
    :class:`GeometryError` for a contour that crosses itself when inside/outside is asked
    (kind ``crossing``: its inside is undefined), and when nothing is left: the first open
    contour's refusal, or ``tool_too_large`` when every contour vanishes."""
    contours = contours_of(spline)
    chains: list[tuple[tuple[Element, ...], bool]] = []
    sides: list[Side] = []
    notes: list[tuple[int, OffsetNote]] = contours.notes()
    refusals: list[GeometryError] = []
    for i, (elements, closed, crossed) in enumerate(
        zip(contours.chains, contours.closed, contours.crossed, strict=True)
    ):
        try:
            sides.append(_resolve(i, elements, closed, options.side, crossed))
        except GeometryError as refusal:
            if refusal.kind == "crossing":
                raise
            refusals.append(refusal)
            notes.append((i, _LEFT_OUT))
            sides.append("left")
            elements = ()
        chains.append((elements, closed))
    results = offset_chains(chains, options, sides)
    subpaths: list[Subpath] = []
    origin: list[int] = []
    for i, result in enumerate(results):
        subpaths += result.subpaths
        origin += [i] * len(result.subpaths)
        notes += [(i, note) for note in result.notes]
    if not subpaths:
        if refusals:
            raise refusals[0]
        raise GeometryError(
            "offset.distance",
            f"{options.distance:g}: every contour vanishes: the tool is larger than every feature",
            kind="tool_too_large",
        )
    notes.sort(key=lambda note: note[0])
    fitted = approximate_path(Path(tuple(subpaths)), spline.tolerance, spline.strategy, limits)
    return OffsetPath(
        fitted, tuple(origin), tuple(notes), spline.stats.max_deviation + contours.moved
    )


def _resolve(
    i: int, elements: Sequence[Element], closed: bool, side: Side, may_cross: bool
) -> Side:
    """Left or right for a contour's inside/outside: an anticlockwise contour (positive
    :func:`signed_area`) has its inside on its left (docs/offsets.md §6)."""
    if side in ("left", "right"):
        return side
    if not closed:
        raise GeometryError(
            "offset.side",
            f"inside/outside needs a closed contour: path.subpaths[{i}] is open",
        )
    crossing = crossings(elements, True) if may_cross else ()
    if crossing:
        x, y = crossing[0]
        raise GeometryError(
            f"path.subpaths[{i}]",
            f"crosses itself at ({x:.6g}, {y:.6g}): its inside is undefined",
            kind="crossing",
        )
    anticlockwise = signed_area(elements) > 0.0
    return "left" if (side == "inside") == anticlockwise else "right"
