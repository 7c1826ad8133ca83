"""The tool-radius options: ``--offset`` (the contours moved by a distance, docs/cli.md
"Offsets and machining") and ``--tool-diameter`` with the options of a machining program,
as ``Annotated`` aliases, and what they change in a request (:class:`Tooling`): the
request's ``offset`` or ``machining`` block (docs/http-api.md), one or the other.

As for the other options, a given one replaces the field of the request's block and one not
given leaves it; the values are checked by the service (the same messages in local and
server mode). Here only what the command line itself decides: that an option has the block
it belongs to (``--side`` an offset, ``--cut`` a tool, ``--tab-width`` tabs), that offset
and machining are not asked together, and that a spiral (a single curve, no contour) takes
neither.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Annotated, Any, Literal

import typer

from .errors import UsageError

if TYPE_CHECKING:
    from .options import Kind

Side = Literal["left", "right", "inside", "outside"]
Join = Literal["round", "mitre"]
Cut = Literal["auto", "outside", "inside", "on"]
Direction = Literal["climb", "conventional"]
Compensation = Literal["computed", "controller"]
Block = Literal["offset", "machining"]

#: The request's blocks, and the option that asks for each.
BLOCKS: tuple[Block, ...] = ("offset", "machining")
_LEAD: dict[Block, str] = {"offset": "--offset", "machining": "--tool-diameter"}

#: The options of the ``offset`` block, by their field.
OFFSET_OPTIONS = {
    "distance": "--offset",
    "side": "--side",
    "join": "--join",
    "mitre_limit": "--mitre-limit",
}
#: The options of the ``machining`` block (``tabs`` apart), by their field.
MACHINING_OPTIONS = {
    "tool_diameter": "--tool-diameter",
    "cut": "--cut",
    "direction": "--direction",
    "lead_radius": "--lead-radius",
    "entry": "--ramp",
    "compensation": "--compensation",
    "tool_number": "--tool-number",
    "join": "--join",
}
#: The options of ``machining.tabs``, by their field.
TABS_OPTIONS = {"count": "--tabs", "width": "--tab-width", "height": "--tab-height"}
#: The options of one block only (but its lead option): ``--join`` is both blocks'.
_ONLY: dict[Block, tuple[str, ...]] = {
    "offset": ("--side", "--mitre-limit"),
    "machining": tuple(
        option
        for option in (*MACHINING_OPTIONS.values(), *TABS_OPTIONS.values())
        if option not in ("--tool-diameter", "--join")
    ),
}

_PANEL = "Offsets and machining (drawings, paths)"

OffsetOption = Annotated[
    float | None,
    typer.Option(
        "--offset",
        help="Move every contour this far (the tool radius), to --side: the tool-centre "
        "paths instead of the contours.",
        rich_help_panel=_PANEL,
        show_default=False,
    ),
]
SideOption = Annotated[
    Side | None,
    typer.Option(
        "--side",
        help="With --offset: left or right of the direction of travel, or inside or "
        "outside a closed contour.",
        rich_help_panel=_PANEL,
    ),
]
JoinOption = Annotated[
    Join | None,
    typer.Option(
        "--join",
        help="Outer corners of the offset: an arc about the corner (round) or a mitre.",
        rich_help_panel=_PANEL,
    ),
]
MitreLimit = Annotated[
    float | None,
    typer.Option(
        "--mitre-limit",
        help="With --join mitre: a mitre reaching farther than this many offsets from its "
        "corner is joined round (default 2).",
        rich_help_panel=_PANEL,
        show_default=False,
    ),
]
ToolDiameter = Annotated[
    float | None,
    typer.Option(
        "--tool-diameter",
        help="Machine the contours with a tool this wide: the tool-centre paths, lead-in "
        "and lead-out arcs, in cutting order (a program with --feed-rate).",
        rich_help_panel=_PANEL,
        show_default=False,
    ),
]
CutOption = Annotated[
    Cut | None,
    typer.Option(
        "--cut",
        help="Which side of the contour the tool runs: auto (outside a part, inside its "
        "holes; on an open contour), outside, inside, or on it.",
        rich_help_panel=_PANEL,
    ),
]
DirectionOption = Annotated[
    Direction | None,
    typer.Option(
        "--direction",
        help="Climb or conventional milling (spindle clockwise, M3).",
        rich_help_panel=_PANEL,
    ),
]
LeadRadius = Annotated[
    float | None,
    typer.Option(
        "--lead-radius",
        help="Radius of the lead-in and lead-out arcs (default the tool radius; 0: none).",
        rich_help_panel=_PANEL,
        show_default=False,
    ),
]
Ramp = Annotated[
    bool | None,
    typer.Option(
        "--ramp/--plunge",
        help="Enter the cut descending along the lead-in, or plunging (the default).",
        rich_help_panel=_PANEL,
        show_default=False,
    ),
]
TabsOption = Annotated[
    int | None,
    typer.Option(
        "--tabs",
        help="Leave this many tabs on each contour that encloses a part (with --tab-width, "
        "--tab-height).",
        rich_help_panel=_PANEL,
        show_default=False,
    ),
]
TabWidth = Annotated[
    float | None,
    typer.Option("--tab-width", help="A tab's length along the contour.", rich_help_panel=_PANEL),
]
TabHeight = Annotated[
    float | None,
    typer.Option(
        "--tab-height", help="A tab's height above the cutting depth.", rich_help_panel=_PANEL
    ),
]
CompensationOption = Annotated[
    Compensation | None,
    typer.Option(
        "--compensation",
        help="computed: the program follows the tool-centre paths; controller: the "
        "contours with cutter compensation (G41.1/G42.1), the controller offsets them.",
        rich_help_panel=_PANEL,
    ),
]
ToolNumber = Annotated[
    int | None,
    typer.Option(
        "--tool-number",
        help="With --compensation controller: G41/G42 D<n> (the tool table's radius) "
        "instead of the diameter in the program.",
        rich_help_panel=_PANEL,
        show_default=False,
    ),
]


@dataclass(frozen=True)
class Tooling:
    """The tool-radius options given (by their option name: ``{"--offset": 3.0}``)."""

    given: dict[str, Any] = field(default_factory=dict)

    @classmethod
    def of(
        cls,
        offset: float | None = None,
        side: str | None = None,
        join: str | None = None,
        mitre_limit: float | None = None,
        tool_diameter: float | None = None,
        cut: str | None = None,
        direction: str | None = None,
        lead_radius: float | None = None,
        ramp: bool | None = None,
        tabs: int | None = None,
        tab_width: float | None = None,
        tab_height: float | None = None,
        compensation: str | None = None,
        tool_number: int | None = None,
    ) -> Tooling:
        """From the commands' keyword arguments (``None``: not given)."""
        entry = None if ramp is None else ("ramp" if ramp else "plunge")
        values = {
            "--offset": offset, "--side": side, "--join": join, "--mitre-limit": mitre_limit,
            "--tool-diameter": tool_diameter, "--cut": cut, "--direction": direction,
            "--lead-radius": lead_radius, "--ramp": entry, "--tabs": tabs,
            "--tab-width": tab_width, "--tab-height": tab_height,
            "--compensation": compensation, "--tool-number": tool_number,
        }  # fmt: skip
        return cls({option: v for option, v in values.items() if v is not None})

    def apply(self, request: dict[str, Any], kind: Kind) -> dict[str, Any]:
        """``request`` with its ``offset`` or ``machining`` block set from these options (a
        new dict; raises :class:`UsageError` where an option has nothing to apply to)."""
        if not self.given:
            return request
        if kind == "spiral":
            raise UsageError(
                "a spiral is one curve, with no contour to offset or machine: only drawings "
                "and paths take these options",
                _names(self.given),
            )
        block = self._block(request)
        body = dict(request)
        if block == "offset":
            body["offset"] = {**(request.get("offset") or {}), **self._fields(OFFSET_OPTIONS)}
            _check_mitre(body["offset"], self.given)
            return body
        machining = {**(request.get("machining") or {}), **self._fields(MACHINING_OPTIONS)}
        tabs = self._fields(TABS_OPTIONS)
        if tabs:
            machining["tabs"] = {**(machining.get("tabs") or {}), **tabs}
            if "count" not in machining["tabs"]:
                sizes = [o for o in ("--tab-width", "--tab-height") if o in self.given]
                raise UsageError("only with --tabs N (how many tabs)", ", ".join(sizes))
        body["machining"] = machining
        return body

    def _block(self, request: dict[str, Any]) -> Block:
        """The block these options set: the one their lead option (``--offset``,
        ``--tool-diameter``) or the request asks for."""
        given = self.given
        if "--offset" in given and "--tool-diameter" in given:
            raise UsageError(
                "one or the other: --offset moves the contours by a distance, --tool-diameter "
                "machines them (offset by the tool radius)",
                "--offset, --tool-diameter",
            )
        asked: set[Block] = {b for b in BLOCKS if request.get(b) is not None}
        asked |= {b for b in BLOCKS if _LEAD[b] in given}
        if len(asked) == 2:
            mine: Block = "offset" if "--offset" in given else "machining"
            theirs = "machining" if mine == "offset" else "offset"
            raise UsageError(
                f"the request asks for {theirs} already: offset and machining are one or the other",
                _LEAD[mine],
            )
        block = next(iter(asked), None)
        for own, options in _ONLY.items():
            stray = [option for option in options if option in given]
            if stray and block != own:
                raise UsageError(f"only with {_LEAD[own]}", ", ".join(stray))
        if block is None:  # only --join is left
            raise UsageError("only with --offset or --tool-diameter", _names(given))
        return block

    def _fields(self, options: dict[str, str]) -> dict[str, Any]:
        return {name: self.given[o] for name, o in options.items() if o in self.given}


def _check_mitre(offset: dict[str, Any], given: dict[str, Any]) -> None:
    if "--mitre-limit" in given and offset.get("join") != "mitre":
        raise UsageError("only with --join mitre (a round join has no mitre)", "--mitre-limit")


def _names(given: dict[str, Any]) -> str:
    """The options of ``given``, as a usage error names them."""
    return ", ".join(given)


def option_of(path: str) -> str | None:
    """The option that sets the request field at ``path`` (``body.machining.tabs.width`` is
    ``--tab-width``; a whole block is its lead option), if there is one."""
    parts = path.split(".")
    if parts[:1] != ["body"] or len(parts) < 2 or parts[1] not in BLOCKS:
        return None
    block: Block = "offset" if parts[1] == "offset" else "machining"
    if len(parts) == 2:
        return _LEAD[block]
    if block == "offset":
        return OFFSET_OPTIONS.get(parts[2]) if len(parts) == 3 else None
    if parts[2] == "tabs":
        return TABS_OPTIONS.get(parts[3]) if len(parts) == 4 else "--tabs"
    return MACHINING_OPTIONS.get(parts[2]) if len(parts) == 3 else None
