"""Request and response models of tool-radius offsets and machining, on the path and drawing
requests (docs/http-api.md, "Offsets and machining"): ``offset`` moves every contour by a
distance to one side; ``machining`` plans the cut of a tool of a diameter (its side chosen
per contour, leads, tabs, order) and writes the program. Either turns the answer's toolpaths
into the tool-centre paths; a request takes at most one of them."""

from __future__ import annotations

from typing import TYPE_CHECKING, Literal

from pydantic import Field

from .schemas import RequestModel, ResponseModel

if TYPE_CHECKING:
    # The core's values are built where the job is made; naming the models loads neither.
    from arcspline.geometry.offset import OffsetOptions
    from arcspline.machining import MachiningOptions

Side = Literal["left", "right", "inside", "outside"]
Join = Literal["round", "mitre"]
Cut = Literal["auto", "outside", "inside", "on"]
#: Largest tool number (LinuxCNC's tool table takes 1..99999; 0 is "no tool").
MAX_TOOL_NUMBER = 99999
#: Most holding tabs per contour.
MAX_TABS = 64
#: Longest length a request may give (offset, tool, lead, tab): the G-code writer's
#: coordinate bound, a kilometre in millimetres (``arcspline.machining.options.MAX_LENGTH``);
#: far beyond any tool, and well within what the offset's arithmetic holds.
MAX_LENGTH = 1e6


class OffsetRequest(RequestModel):
    """Every contour offset by ``distance`` (the tool radius) to ``side``."""

    distance: float = Field(
        gt=0, lt=MAX_LENGTH, description="The offset (the tool radius), in the request's units."
    )
    side: Side = Field(
        description="`left`/`right` of the direction of travel; `inside`/`outside` of a closed "
        "contour (refused for an open one)."
    )
    join: Join = Field(
        default="round",
        description="Convex corners: an arc of radius `distance` about the corner, or a mitre.",
    )
    mitre_limit: float = Field(
        default=2.0,
        ge=1,
        description="A mitre reaching farther than `mitre_limit × distance` from its corner is "
        "joined round instead.",
    )

    def options(self) -> OffsetOptions:
        from arcspline.geometry.offset import OffsetOptions

        return OffsetOptions(
            distance=self.distance, side=self.side, join=self.join, mitre_limit=self.mitre_limit
        )


class TabsRequest(RequestModel):
    """Holding tabs: where the tool rises by ``height`` over ``width`` of the path, spread
    evenly along each closed contour cut outside or inside."""

    count: int = Field(ge=1, le=MAX_TABS, description="Tabs per contour.")
    width: float = Field(gt=0, lt=MAX_LENGTH, description="Length of each tab along the path.")
    height: float = Field(gt=0, lt=MAX_LENGTH, description="How far above `cut_z` it stands.")


class MachiningRequest(RequestModel):
    """The cut of a tool of ``tool_diameter``: each contour's side (``cut``), the direction,
    leads, entry, tabs and cutter compensation."""

    tool_diameter: float = Field(gt=0, lt=MAX_LENGTH, description="The tool's diameter.")
    cut: Cut = Field(
        default="auto",
        description="`auto`: a closed contour at even nesting depth outside, at odd depth "
        "inside, an open one on the line; or the same side for every contour.",
    )
    direction: Literal["climb", "conventional"] = Field(
        default="climb", description="Milling direction of a clockwise (M3) spindle."
    )
    lead_radius: float | None = Field(
        default=None,
        ge=0,
        lt=MAX_LENGTH,
        description="Radius of the lead-in and lead-out arcs (null: the tool radius; 0: none).",
    )
    entry: Literal["plunge", "ramp"] = Field(
        default="plunge", description="`ramp`: a helical descent along the lead-in."
    )
    tabs: TabsRequest | None = Field(default=None, description="Holding tabs (none if null).")
    compensation: Literal["computed", "controller"] = Field(
        default="computed",
        description="`computed`: the program follows the tool centre; `controller`: it follows "
        "the contour with G41.1/G42.1 (G41/G42 with `tool_number`).",
    )
    tool_number: int | None = Field(
        default=None,
        ge=1,
        le=MAX_TOOL_NUMBER,
        description="Controller compensation by the tool table's diameter (`D<n>`).",
    )
    join: Join = Field(
        default="round", description="Convex corners of the tool path, as for offsets."
    )

    def options(self) -> MachiningOptions:
        from arcspline.machining import MachiningOptions, Tabs

        tabs = (
            None if self.tabs is None else Tabs(self.tabs.count, self.tabs.width, self.tabs.height)
        )
        return MachiningOptions(
            tool_diameter=self.tool_diameter, cut=self.cut, direction=self.direction,
            lead_radius=self.lead_radius, entry=self.entry, tabs=tabs,
            compensation=self.compensation, tool_number=self.tool_number, join=self.join,
        )  # fmt: skip


OFFSET_DESCRIPTION = (
    "Offset every contour by a distance (the tool radius): the answer's toolpaths are the "
    "tool-centre paths (not with `machining`)."
)
MACHINING_DESCRIPTION = (
    "Plan the cut of a tool: the answer's toolpaths are the tool-centre paths, and the `gcode` "
    "output is the machining program (needs `gcode.safe_z` and `gcode.cut_z`; not with "
    "`offset`)."
)
BOTH_MESSAGE = "offset and machining exclude each other: give one of them"


# -- responses ---------------------------------------------------------------------------


class OffsetNoteResponse(ResponseModel):
    """What became of a contour: ``split`` into several paths, ``vanished`` (narrower than
    the tool), ``narrow`` (a part too narrow was dropped), ``collapsed``."""

    toolpath: int = Field(description="The contour's index (its toolpath or subpath).")
    kind: Literal["split", "vanished", "narrow", "collapsed", "loop", "open"]
    message: str = Field(description="Names the contour (and for a drawing its elements).")


class OffsetResponse(ResponseModel):
    """The offset asked for and what it gave; every tool-centre path is within
    ``source_max_deviation`` of the exact offset of the drawing (offsets are 1-Lipschitz)."""

    distance: float
    side: Side
    contours_in: int
    paths_out: int
    origin: list[int] = Field(description="Per tool-centre path: the contour it offsets.")
    source_max_deviation: float
    notes: list[OffsetNoteResponse]


class MachinedContourResponse(ResponseModel):
    """Per tool-centre path, in cutting order: the contour it cuts, the side, the milling
    direction and the contour's nesting depth."""

    toolpath: int = Field(description="The contour's index (its toolpath or subpath).")
    cut: Literal["outside", "inside", "on"]
    direction: Literal["climb", "conventional"]
    depth: int


class MachiningWarningResponse(ResponseModel):
    toolpath: int = Field(description="The contour's index (its toolpath or subpath).")
    message: str


class MachiningResponse(ResponseModel):
    """The cut planned: its contours in cutting order, warnings, the rapids' length."""

    tool_diameter: float
    contours: list[MachinedContourResponse]
    warnings: list[MachiningWarningResponse]
    rapid_length: float
    source_max_deviation: float
