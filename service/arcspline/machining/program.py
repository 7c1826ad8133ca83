"""A machining program (docs/machining.md §9): per tool path, every depth pass before the
next path; per pass a retract to ``safe_z``, a rapid to the start, the entry (plunge, or a
helical ramp down the lead-in arc), the cut with its tabs, and the lead-out; ``M2``.

Every XY block comes from :func:`arcspline.outputs.gcode.plan.plan_program`, so the
rounding guarantee of docs/gcode.md holds for the tool path: consecutive blocks meet
exactly, arcs carry I/J (or R) computed from the rounded ends, and every block is measured
against its exact line or arc before the program is written.

* Plunge: ``G1 Z<level>`` at the plunge feed at the start of the lead-in.
* Ramp: from the stock top Z0 at the lead-in's start, down to the pass level along the lead-in
  (a helix: its G2/G3 carry a Z word, linear in the length travelled). Each pass starts at Z0
  again, so it cuts at most one step below the ramp before it. Without a lead-in there is
  nothing to ramp on: the pass plunges (the plan warned of it).
* Tabs: on passes below the tab top (``cut_z + height``) the tool rises to the tab top at the
  start of each tab and goes back down at its end (``G1 Z`` at the plunge feed).
* Controller compensation: at ``safe_z``, from a point behind the lead-in along its tangent,
  ``G41.1 D<diameter>`` (``G42.1`` for the tool on the right; ``G41 D<n>``/``G42 D<n>`` with
  a tool number) and a straight entry move (two tool radii) onto the lead-in's start; the
  tool goes down there. After the lead-out, a retract to ``safe_z``, ``G40`` and a straight
  exit move along the lead-out's end tangent.
"""

from __future__ import annotations

import re
from collections.abc import Iterator, Sequence

import numpy as np

from arcspline.outputs.gcode import GcodeError, GcodeOptions
from arcspline.outputs.gcode.lattice import feed_word, fixed_point, to_lattice
from arcspline.outputs.gcode.plan import Plan, plan_program
from arcspline.outputs.gcode.program import numbered

from .options import MachiningOptions
from .plan import Machined, Role
from .sides import tool_on_left

_PARENS = re.compile(r"[()]")


class _Blocks:
    """The program's lines, with the feed word written only where the feed changes."""

    def __init__(self, decimals: int, feed: str, plunge: str) -> None:
        self.d = decimals
        self.feed, self.plunge = feed, plunge
        self.current = feed  # the preamble sets the cutting feed
        self.lines: list[str] = []
        self.z: int | None = None

    def add(self, text: str) -> None:
        self.lines.append(text)

    def fed(self, text: str, feed: str) -> None:
        if feed != self.current:
            text += f" {feed}"
            self.current = feed
        self.lines.append(text)

    def rapid_z(self, z: int) -> None:
        if self.z != z:
            self.lines.append(f"G0 Z{fixed_point(z, self.d)}")
            self.z = z

    def feed_z(self, z: int) -> None:
        if self.z != z:
            self.fed(f"G1 Z{fixed_point(z, self.d)}", self.plunge)
            self.z = z

    def xy(self, point: tuple[int, int]) -> str:
        return f"X{fixed_point(point[0], self.d)} Y{fixed_point(point[1], self.d)}"


def write_machining(machined: Machined, options: GcodeOptions) -> str:
    """The program that cuts ``machined`` (see the module's docstring).

    Raises :class:`GcodeError` without ``safe_z``/``cut_z`` (``cut_z``), with tabs whose top
    reaches ``safe_z``, and as :func:`~arcspline.outputs.gcode.write_program` does for
    decimals too coarse for the tolerance or coordinates too large.
    """
    if options.safe_z is None or options.cut_z is None:
        raise GcodeError("cut_z", "a machining program needs safe_z and cut_z (the depth to cut)")
    d = options.resolved_decimals
    tabs = machined.options.tabs
    levels = options.pass_levels
    tab_top = None
    if tabs is not None:
        tab_top = levels[-1] + round(float(tabs.height) * 10**d)
        if tab_top >= round(options.safe_z * 10**d):
            raise GcodeError(
                "cut_z",
                f"the tabs' top (cut_z + {tabs.height:g}) reaches safe_z {options.safe_z:g}: "
                "lower the tabs or raise safe_z",
            )
    subpaths = machined.programmed.subpaths
    plans = [plan_program(sub.spline, sub.curve, options) for sub in subpaths]
    blocks = _Blocks(
        d, feed_word(options.feed_rate, d), feed_word(options.resolved_plunge_feed_rate, d)
    )
    if options.comments:
        for text in _header(machined, plans, options):
            blocks.add(f"({_PARENS.sub('', text)})")
    units = "G21" if options.units == "mm" else "G20"
    blocks.add(f"G17 {units} G90 G91.1 G94 {blocks.feed}")
    if any(a is not None for a in machined.approaches):
        blocks.add("G40")  # no compensation left on from before this program
    safe = round(options.safe_z * 10**d)
    for k, plan in enumerate(plans):
        lengths = subpaths[k].spline.columns.length.tolist()
        for level in levels:
            _pass(blocks, machined, k, plan, lengths, level, safe, tab_top)
    blocks.rapid_z(safe)
    blocks.add("M2")
    return numbered(blocks.lines, options)


def _pass(
    blocks: _Blocks,
    machined: Machined,
    k: int,
    plan: Plan,
    lengths: Sequence[float],
    level: int,
    safe: int,
    tab_top: int | None,
) -> None:
    """One depth pass of tool path ``k``."""
    d = blocks.d
    roles = machined.programmed_roles[k]
    approach = machined.approaches[k]
    mopts = machined.options
    blocks.rapid_z(safe)
    if approach is not None:
        entry, exit_ = (
            tuple(p) for p in to_lattice(np.array(approach, dtype=np.float64), d).tolist()
        )
        blocks.add(f"G0 {blocks.xy(entry)}")
    else:
        blocks.add(f"G0 {blocks.xy(plan.start)}")
    ramp_rows = 0
    while ramp_rows < len(roles) and roles[ramp_rows] == "lead_in":
        ramp_rows += 1
    stock_top = 0
    ramp = mopts.entry == "ramp" and ramp_rows > 0 and level < stock_top < safe
    if approach is not None:
        # Compensation is turned on above the stock: the entry move ends with the tool
        # where the compensated lead-in starts, and the tool goes down there.
        blocks.add(_compensation(mopts, d))
        blocks.fed(f"G1 {blocks.xy(plan.start)}", blocks.feed)
    blocks.feed_z(stock_top if ramp else level)
    ramp_z = _ramp(lengths[:ramp_rows], stock_top, level) if ramp else []
    lifted = tab_top is not None and level < tab_top
    for i, (end, arc) in enumerate(zip(plan.ends, plan.arcs, strict=True)):
        role: Role = roles[i]
        if role == "tab" and lifted and (i == 0 or roles[i - 1] != "tab"):
            assert tab_top is not None
            blocks.feed_z(tab_top)
        words = blocks.xy(end)
        if arc is not None:
            if arc.radius is not None:
                words += f" R{fixed_point(arc.radius, d)}"
            else:
                assert arc.offset is not None
                words += f" I{fixed_point(arc.offset[0], d)} J{fixed_point(arc.offset[1], d)}"
        if i < len(ramp_z):
            words += f" Z{fixed_point(ramp_z[i], d)}"
            blocks.z = ramp_z[i]
        code = "G1" if arc is None else "G3" if arc.ccw else "G2"
        blocks.fed(f"{code} {words}", blocks.feed)
        if role == "tab" and lifted and (i + 1 == len(roles) or roles[i + 1] != "tab"):
            blocks.feed_z(level)
    if approach is not None:
        blocks.rapid_z(safe)
        blocks.add("G40")
        blocks.fed(f"G1 {blocks.xy(exit_)}", blocks.feed)


def _compensation(mopts: MachiningOptions, d: int) -> str:
    """``G41.1 D<diameter>`` (``G42.1`` for the tool right of travel), or ``G41 D<n>``/
    ``G42 D<n>`` naming a tool of the controller's table."""
    left = tool_on_left(mopts.direction)
    if mopts.tool_number is not None:
        return f"{'G41' if left else 'G42'} D{mopts.tool_number}"
    diameter = fixed_point(round(float(mopts.tool_diameter) * 10**d), d)
    return f"{'G41.1' if left else 'G42.1'} D{diameter}"


def _ramp(lengths: Sequence[float], top: int, level: int) -> list[int]:
    """The Z (units in the last place) at the end of each ramp row: linear in the length
    travelled from ``top`` to ``level``, the last exactly ``level``."""
    total = sum(lengths)
    out, run = [], 0.0
    for size in lengths:
        run += size
        out.append(top + round((level - top) * run / total))
    out[-1] = level
    return out


def _header(machined: Machined, plans: Sequence[Plan], options: GcodeOptions) -> Iterator[str]:
    units = options.units
    d = options.resolved_decimals
    mopts = machined.options
    comp = "computed tool-centre paths"
    if mopts.compensation == "controller":
        code = "G41" if tool_on_left(mopts.direction) else "G42"
        comp = (
            f"controller compensation {code} D{mopts.tool_number}"
            if mopts.tool_number is not None
            else f"controller compensation {code}.1 D{mopts.tool_diameter:g}"
        )
    yield "arcspline: machining program, spindle clockwise M3"
    yield f"tool diameter {mopts.tool_diameter:g} {units}, {comp}"
    counts = {
        side: sum(c.cut == side for c in machined.contours) for side in ("outside", "inside", "on")
    }
    yield (
        f"{len(machined.contours)} tool paths: {counts['outside']} outside, {counts['inside']} "
        f"inside, {counts['on']} on the line; rapids {machined.rapid_length:.6g} {units}"
    )
    for n, cut in enumerate(machined.contours, start=1):
        sense = (
            "" if cut.clockwise is None else (", clockwise" if cut.clockwise else ", anticlockwise")
        )
        yield (
            f"path {n}: toolpath {cut.source}, {cut.cut}, {cut.direction}{sense}, depth {cut.depth}"
        )
    levels = options.pass_levels
    yield (
        f"depth: {len(levels)} passes from Z{fixed_point(levels[0], d)} to "
        f"Z{fixed_point(levels[-1], d)}, entry {mopts.entry} (down a lead-in where there is one), "
        "every pass of a path before the next path"
    )
    if mopts.tabs is not None:
        top = levels[-1] + round(float(mopts.tabs.height) * 10**d)
        yield (
            f"tabs: {mopts.tabs.count} per outside path, {mopts.tabs.width:g} {units} wide, "
            f"top Z{fixed_point(top, d)}"
        )
    measured = max(float(plan.deviation.max()) for plan in plans)
    yield (
        f"measured max deviation of the program from the tool paths {measured:.6g} {units}, "
        f"{d} decimals"
    )
    for source, words in machined.warnings:
        yield f"warning: toolpath {source}: {words}"
