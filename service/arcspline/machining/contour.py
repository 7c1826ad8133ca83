"""The tool-centre paths of one contour (docs/machining.md §4–§6, §9).

A closed contour is turned to its cutting direction and offset by the tool radius to the
tool's side (``geometry.offset.offset_subpath``; cut ``on``: the contour itself); each loop
is begun where lead arcs fit and cut at its tabs. Under controller compensation the contour
itself is what the program states, with lead arcs of radius ``R + r`` about the centres of
the tool centre's leads (radius ``R``); the tool centre's loop is still made, begun at the
matching point, for the answer and its preview.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Literal, NamedTuple, cast

from arcspline.geometry import CircularArc, GeometryError, Point
from arcspline.geometry.offset import OffsetOptions, SubpathOffset, crossings, signed_area
from arcspline.geometry.offset import Side as OffsetSide
from arcspline.geometry.offset.subpath import offset_chains

from .chains import Chain, Element, chain_length, reversed_chain, tangent_at
from .leads import (
    Obstacles,
    Start,
    approach,
    begun_at,
    candidates,
    choose_starts,
    lead_in,
    lead_out,
    nearest_start,
)
from .options import MachiningOptions
from .sides import CutPlan, runs_clockwise, tool_on_left
from .tabs import fits, with_tabs

Role = Literal["lead_in", "cut", "tab", "lead_out"]
#: Under controller compensation, a concave arc must be larger than the tool radius by this
#: fraction of it: the controller's offset arc, of radius ``R − r``, must not vanish into the
#: rounding of its words (LinuxCNC refuses radii below 1.27 µm).
CONCAVE_MARGIN = 1e-3


class Piece(NamedTuple):
    """One tool-centre path before ordering (and, under compensation, what is programmed)."""

    plan: CutPlan
    segments: Chain
    roles: tuple[Role, ...]
    programmed: Chain
    programmed_roles: tuple[Role, ...]
    approach: tuple[Point, Point] | None


class Context(NamedTuple):
    """What every contour's paths are made with; ``warnings`` collects ``(source, words)``,
    ``refused`` the refusals of contours left uncut (raised if nothing else is cut)."""

    options: MachiningOptions
    obstacles: Obstacles
    snap: float
    warnings: list[tuple[int, str]]
    refused: list[GeometryError]

    def leave_uncut(self, index: int, refusal: GeometryError) -> None:
        """Contour ``index`` is not cut, for ``refusal``'s reason: a warning names it."""
        self.refused.append(refusal)
        self.warnings.append((index, f"{refusal.message}; left uncut"))


def _oriented(loop: Chain, clockwise: bool) -> Chain:
    return loop if (signed_area(loop) < 0.0) == clockwise else reversed_chain(loop)


class Prepared(NamedTuple):
    """A contour ready to be offset: its plan (side, direction, depth, sense) and the
    contour itself, turned to its cutting direction when closed."""

    source: int
    plan: CutPlan
    contour: Chain
    closed: bool

    @property
    def offset(self) -> bool:
        """Whether its tool path is an offset of it (a closed contour cut inside or out)."""
        return self.closed and self.plan.cut != "on"


def prepared(
    index: int,
    chain: Chain,
    closed: bool,
    plan: CutPlan,
    options: MachiningOptions,
    may_cross: bool = True,
) -> Prepared:
    """Contour ``index`` checked and turned: refused a side if it crosses itself (and, under
    controller compensation, if it has a concave arc the controller refuses). ``may_cross``
    false says it is known not to meet itself (``contours_of``), sparing the search."""
    if plan.cut != "on" and may_cross:
        crossed = crossings(chain, True)
        if crossed:
            x, y = crossed[0]
            raise GeometryError(
                f"path.subpaths[{index}]",
                f"crosses itself at ({x:.6g}, {y:.6g}): its inside is undefined; cut it 'on' "
                "its line, or redraw it",
                kind="crossing",
            )
    if not closed:
        return Prepared(index, plan._replace(clockwise=None), chain, closed)
    clockwise = runs_clockwise(plan.cut, options.direction)
    contour = _oriented(chain, clockwise)
    if plan.cut != "on" and options.compensation == "controller":
        # Refused before the offset, whose notes would say it less plainly.
        left = tool_on_left(options.direction)
        _refuse_tight_concave_arcs(index, contour, left, options.tool_radius)
    return Prepared(index, plan._replace(clockwise=clockwise), contour, closed)


def offsets(contours: Sequence[Prepared], options: MachiningOptions) -> list[SubpathOffset]:
    """The tool centre's loops of every contour to offset, at once (one vectorised pass of
    the core over all of them): each contour (turned to its cutting direction) offset by the
    tool radius to the tool's side of travel; the loops run the contour's way."""
    side: OffsetSide = "left" if tool_on_left(options.direction) else "right"
    return offset_chains(
        [(c.contour, True) for c in contours],
        OffsetOptions(options.tool_radius, side, options.join),
    )


def contour_paths(
    contours: Sequence[Prepared],
    offset_of: Mapping[int, SubpathOffset],
    context: Context,
) -> list[Piece]:
    """The tool-centre paths of every contour, given the offsets of those cut inside or out
    (by source index). The start points of all loops are chosen together
    (:func:`.leads.choose_starts`)."""
    options = context.options
    left = tool_on_left(options.direction)
    wanted, r = options.resolved_lead_radius, options.tool_radius
    pieces: list[Piece] = []
    loops: list[tuple[Prepared, Chain]] = []
    for contour in contours:
        if not contour.closed:
            pieces.append(_open_piece(contour.contour, contour.plan))
        elif not contour.offset:
            pieces.append(_closed_on_piece(contour.contour, contour.plan))
        else:
            found = _tool_loops(contour.source, offset_of[contour.source], context)
            loops += [(contour, loop) for loop in found]
    if options.compensation == "controller":
        # The programmed contours are begun where leads fit; the tool centre's loop (one:
        # the offset of a contour the controller can cut does not split) follows.
        starts = choose_starts(
            [c.contour for c, _ in loops], left, wanted, r, context.obstacles, inset=r
        )
        for (contour, loop), (start, radius) in zip(loops, starts, strict=True):
            pieces.append(_controller_piece(contour, loop, start, radius, context))
    else:
        starts = choose_starts([loop for _, loop in loops], left, wanted, r, context.obstacles)
        for (contour, _), (start, radius) in zip(loops, starts, strict=True):
            pieces.append(_computed_piece(contour, start, radius, context))
    return pieces


def _tool_loops(index: int, done: SubpathOffset, context: Context) -> list[Chain]:
    """The loops of one contour's offset. Notes of narrow parts become warnings (refusals
    under controller compensation, whose controller would gouge them)."""
    options = context.options
    controller = options.compensation == "controller"
    for note in done.notes:
        if controller and note.kind != "vanished":
            raise GeometryError(
                f"path.subpaths[{index}]",
                f"{note.message}; the controller would gouge it under cutter compensation: "
                "use compensation 'computed', or a smaller tool",
                kind="tool_too_large",
            )
        if note.kind != "vanished":
            context.warnings.append((index, note.message))
    if not done.subpaths:
        context.leave_uncut(index, GeometryError(
            f"path.subpaths[{index}]",
            f"the tool (diameter {options.tool_diameter:g}) does not fit this contour: "
            "its offset vanishes",
            kind="tool_too_large",
        ))  # fmt: skip
        return []
    # The core's offsets are made of lines and arcs only.
    return [cast(Chain, tuple(sub.segments)) for sub in done.subpaths]


def _open_piece(chain: Chain, plan: CutPlan) -> Piece:
    roles: tuple[Role, ...] = _all_cut(chain)
    return Piece(plan, chain, roles, chain, roles, None)


def _closed_on_piece(loop: Chain, plan: CutPlan) -> Piece:
    """A closed contour cut on its line: begun at the midpoint of its best element, no
    leads (either side is the part)."""
    begun = begun_at(loop, candidates(loop)[0])
    roles: tuple[Role, ...] = _all_cut(begun)
    return Piece(plan, begun, roles, begun, roles, None)


def _computed_piece(contour: Prepared, start: Start, radius: float, context: Context) -> Piece:
    index, plan = contour.source, contour.plan
    _warn_leads(index, context.options.resolved_lead_radius, radius, context)
    cut, cut_roles = _tabbed(index, start.loop, plan, context)
    segments, roles = _assembled(start.lead_in, cut, cut_roles, start.lead_out)
    return Piece(plan, segments, roles, segments, roles, None)


def _controller_piece(
    contour: Prepared, loop: Chain, start: Start, radius: float, context: Context
) -> Piece:
    """Under compensation: the contour begun where the leads fit (tool centre's leads of
    radius ``R``, programmed ones of ``R + r``), and the tool centre's loop begun at the
    matching point, for the answer."""
    index, plan = contour.source, contour.plan
    options = context.options
    r = options.tool_radius
    left = tool_on_left(options.direction)
    wanted = options.resolved_lead_radius
    if start.lead_in is None or start.lead_out is None:
        raise GeometryError(
            f"path.subpaths[{index}]",
            f"no lead arc (radius {wanted:g} down to {wanted / 16:g}) fits this contour to turn "
            "cutter compensation on: use compensation 'computed'",
            kind="tool_too_large",
        )
    _warn_leads(index, wanted, radius, context)
    programmed, programmed_roles = _assembled(
        start.lead_in, *_tabbed(index, start.loop, plan, context), start.lead_out
    )
    ends = approach(start.lead_in, start.lead_out, r)
    # The tool centre's loop, begun where the controller puts the tool: r to the waste side
    # of the programmed start (a smooth point of the contour).
    lx, ly = start.lead_in.center
    px, py = start.lead_in.end
    reach = start.lead_in.radius
    tool_start = Point(px + (lx - px) * r / reach, py + (ly - py) * r / reach)
    tool_loop = nearest_start(loop, tool_start, context.snap)
    direction = tangent_at(tool_loop[0], 0.0)
    first = tool_loop[0].start
    cut, cut_roles = _tabbed(index, tool_loop, plan, context, quiet=True)
    segments, roles = _assembled(
        lead_in(first, direction, left, radius), cut, cut_roles,
        lead_out(first, direction, left, radius),
    )  # fmt: skip
    return Piece(plan, segments, roles, programmed, programmed_roles, ends)


def _refuse_tight_concave_arcs(index: int, contour: Chain, left: bool, r: float) -> None:
    """LinuxCNC refuses an arc on whose concave side the tool is, when its radius is not
    larger than the tool's ("tool radius not less than arc radius with comp"); one barely
    larger leaves the controller an arc too small to cut (:data:`CONCAVE_MARGIN`)."""
    for j, element in enumerate(contour):
        if not isinstance(element, CircularArc):
            continue
        if (element.sweep_rad > 0.0) == left and element.radius <= r * (1.0 + CONCAVE_MARGIN):
            raise GeometryError(
                f"path.subpaths[{index}]",
                f"has a concave arc of radius {element.radius:.6g} (element {j}), not "
                f"larger than the tool radius {r:g}: a controller refuses it under cutter "
                "compensation; use compensation 'computed'",
                kind="tool_too_large",
            )


def _warn_leads(index: int, wanted: float, radius: float, context: Context) -> None:
    if wanted > 0.0 and radius == 0.0:
        context.warnings.append(
            (index, f"no lead arc of radius {wanted:g} down to {wanted / 16:g} keeps clear of "
                    "the contours: cut without lead arcs, entering the tool path at its start")
        )  # fmt: skip


def _tabbed(
    index: int, loop: Chain, plan: CutPlan, context: Context, quiet: bool = False
) -> tuple[Chain, tuple[Role, ...]]:
    """The loop cut at its tabs (outside contours only), with each piece's role."""
    tabs = context.options.tabs
    if tabs is None or plan.cut != "outside":
        return loop, _all_cut(loop)
    diameter = float(context.options.tool_diameter)
    if not fits(chain_length(loop), tabs, diameter):
        if not quiet:
            context.warnings.append(
                (index, f"too short for {tabs.count} tabs of width {tabs.width:g} (each takes "
                        f"{tabs.width + diameter:g} of the tool path): cut without tabs")
            )  # fmt: skip
        return loop, _all_cut(loop)
    pieces, on_tab = with_tabs(loop, tabs, diameter, context.snap)
    tab: Role = "tab"
    cut: Role = "cut"
    return pieces, tuple(tab if t else cut for t in on_tab)


def _all_cut(chain: Chain) -> tuple[Role, ...]:
    cut: Role = "cut"
    return (cut,) * len(chain)


def _assembled(
    first: CircularArc | None,
    cut: Chain,
    cut_roles: tuple[Role, ...],
    last: CircularArc | None,
) -> tuple[Chain, tuple[Role, ...]]:
    segments: list[Element] = list(cut)
    roles: list[Role] = list(cut_roles)
    if first is not None:
        segments.insert(0, first)
        roles.insert(0, "lead_in")
    if last is not None:
        segments.append(last)
        roles.append("lead_out")
    return tuple(segments), tuple(roles)
