"""A drawing's contours as tool-centre paths in cutting order (docs/machining.md §8).

Per contour: its cut side (:mod:`.nesting`, :mod:`.sides`) and its tool paths
(:mod:`.contour`: offset, turned, begun where leads fit, cut at its tabs). The paths are put
in cutting order (:mod:`.order`) and fitted again as one path (``approximate_path``: exact
lines and arcs come back as themselves), keeping for every output row what it is: lead-in,
cut, tab or lead-out, through the input segment it answers for (``SubpathSpline.sources``).
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import NamedTuple

from arcspline.geometry import (
    DEFAULT_LIMITS,
    GeometryError,
    Limits,
    Path,
    PathSpline,
    Point,
    Subpath,
    approximate_path,
)
from arcspline.geometry.offset import contours_of

from .chains import Chain
from .contour import Context, Role, contour_paths, offsets, prepared
from .leads import Obstacles
from .nesting import nesting
from .options import MachiningOptions, check
from .order import cutting_order
from .sides import CutPlan, cut_side

#: Pieces shorter than this fraction of the coordinates are not made when cutting at tabs.
SNAP_RTOL = 1e-9


class Machined(NamedTuple):
    """Tool-centre paths in cutting order and how each is cut.

    ``spline`` holds one subpath per tool-centre path (lead arcs included); ``contours``,
    ``roles`` and ``approaches`` are per subpath of it, ``roles`` per row of its spline.
    ``warnings`` are ``(source subpath, words)``. ``rapid_length`` is the XY length of the
    rapids from the origin through every path in order. ``programmed`` is what the program
    states: ``spline`` itself, or under controller compensation the contours with their lead
    arcs (``programmed_roles`` per row of it; ``approaches`` the start of the straight entry
    move and the end of the exit move per subpath).
    """

    spline: PathSpline
    contours: tuple[CutPlan, ...]
    roles: tuple[tuple[Role, ...], ...]
    warnings: tuple[tuple[int, str], ...]
    rapid_length: float
    source_max_deviation: float
    options: MachiningOptions
    programmed: PathSpline
    programmed_roles: tuple[tuple[Role, ...], ...]
    approaches: tuple[tuple[Point, Point] | None, ...]


def machine(
    spline: PathSpline, options: MachiningOptions, limits: Limits = DEFAULT_LIMITS
) -> Machined:
    """The tool-centre paths that cut every subpath of ``spline`` with ``options``.

    A contour the tool does not fit (its offset vanishes) is left uncut, with a warning
    naming it; when nothing at all is left to cut, that refusal is raised. Raises
    :class:`GeometryError` naming ``machining.<field>`` for invalid options, and
    ``path.subpaths[i]`` for an open contour asked a side, a contour that crosses itself
    asked a side (kind ``crossing``), or, under controller compensation, a contour with a
    concave arc tighter than the tool radius."""
    check(options)
    if options.compensation == "controller" and options.resolved_lead_radius == 0.0:
        raise GeometryError(
            "machining.lead_radius",
            "controller compensation needs lead arcs (the controller offsets them on the way "
            "in): give a lead radius > 0, or compensation 'computed'",
        )
    cleaned = contours_of(spline)
    contours, closed = cleaned.chains, cleaned.closed
    nest = nesting(contours, closed)
    sides = [cut_side(options.cut, closed[i], nest.depth[i], i) for i in range(len(contours))]
    scale = max(
        (abs(c) for chain in contours for e in chain for p in (e.start, e.end) for c in p),
        default=1.0,
    )
    loops = [(i, note.message) for i, note in cleaned.notes()]
    context = Context(options, Obstacles(contours), SNAP_RTOL * max(scale, 1.0), loops, [])
    ready = [
        prepared(
            i,
            tuple(chain),
            closed[i],
            CutPlan(i, sides[i], options.direction, nest.depth[i], None),
            options,
            cleaned.crossed[i],
        )
        for i, chain in enumerate(contours)
    ]
    to_offset = [c for c in ready if c.offset]
    offset_of = dict(zip((c.source for c in to_offset), offsets(to_offset, options), strict=True))
    pieces = contour_paths(ready, offset_of, context)
    if not pieces and context.refused:
        raise context.refused[0]
    if options.entry == "ramp":
        # A profile the tool had to plunge into; lines cut "on" have no leads at all.
        plunging = {
            p.plan.source
            for p in pieces
            if p.plan.cut != "on" and p.programmed_roles[0] != "lead_in"
        }
        for source in sorted(plunging):
            context.warnings.append(
                (source, "no lead-in arc to ramp down along: the tool plunges into this one")
            )
    # A path waits for the paths of the contours directly inside its contour (which wait in
    # turn for theirs).
    paths_of: list[list[int]] = [[] for _ in contours]
    for k, piece in enumerate(pieces):
        paths_of[piece.plan.source].append(k)
    inner: list[list[int]] = [[] for _ in contours]
    for i, parent in enumerate(nest.parent):
        if parent is not None:
            inner[parent] += paths_of[i]
    waits = [inner[p.plan.source] for p in pieces]
    entries = [p.approach[0] if p.approach else p.programmed[0].start for p in pieces]
    exits = [p.approach[1] if p.approach else p.programmed[-1].end for p in pieces]
    order = cutting_order(entries, exits, waits)
    ordered = [pieces[k] for k in order.order]
    fitted, roles = _fit([(p.segments, p.roles) for p in ordered], spline.tolerance, limits)
    if options.compensation == "controller":
        programmed, programmed_roles = _fit(
            [(p.programmed, p.programmed_roles) for p in ordered], spline.tolerance, limits
        )
    else:
        programmed, programmed_roles = fitted, roles
    return Machined(
        spline=fitted,
        contours=tuple(p.plan for p in ordered),
        roles=roles,
        warnings=tuple(sorted(context.warnings, key=lambda w: w[0])),
        rapid_length=order.rapid_length,
        source_max_deviation=spline.stats.max_deviation + cleaned.moved,
        options=options,
        programmed=programmed,
        programmed_roles=programmed_roles,
        approaches=tuple(p.approach for p in ordered),
    )


def _fit(
    paths: Sequence[tuple[Chain, tuple[Role, ...]]], tolerance: float, limits: Limits
) -> tuple[PathSpline, tuple[tuple[Role, ...], ...]]:
    """The chains fitted as one path (lines and arcs come back as themselves) and the role
    of every output row, through the input segment it answers for."""
    path = Path(tuple(Subpath(segments, _is_loop(segments)) for segments, _ in paths))
    fitted = approximate_path(path, tolerance, "subdivide", limits)
    roles = tuple(
        tuple(given[int(k)] for k in sub.sources().segment)
        for sub, (_, given) in zip(fitted.subpaths, paths, strict=True)
    )
    return fitted, roles


def _is_loop(segments: Chain) -> bool:
    return segments[-1].end == segments[0].start


__all__ = ["Machined", "Role", "machine"]
