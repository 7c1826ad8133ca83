"""The options the commands share, as ``Annotated`` aliases, and what they change in a
request (:class:`Overrides`): an option given on the command line replaces the request's
field; one not given leaves it as the request has it.

The request's fields are checked by the service (the same messages in local and server
mode); here only what the command line itself decides: that a tolerance is given somewhere,
and that an option applies to the kind of input at hand.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import Annotated, Any, Literal

import typer

from .errors import UsageError
from .tooling import Tooling

Kind = Literal["spiral", "path", "drawing"]
Format = Literal["json", "gcode", "dxf", "svg"]
StrategyName = Literal["subdivide", "fewest-arcs"]
Units = Literal["mm", "inch"]
SourceUnits = Literal["mm", "cm", "m", "in", "ft", "pt", "pc", "px"]

#: The G-code options (``GcodeRequest`` but ``units``, which ``--units`` sets).
GCODE_FIELDS = (
    "feed_rate",
    "decimals",
    "arc_format",
    "line_numbers",
    "comments",
    "safe_z",
    "cut_z",
    "plunge_feed_rate",
    "step_down",
    "min_arc_length",
    "max_radius",
)
#: The options only a drawing has (``DrawingRequest``).
DRAWING_FIELDS = ("source_units", "layers", "join_tolerance", "order", "choose_start")

_WORK = "Approximation"
_GCODE = "G-code"
_DRAWING = "Drawings (SVG, DXF)"
_RUN = "Where and how"

Tolerance = Annotated[
    float | None,
    typer.Option(
        "--tolerance",
        "-t",
        help="Largest distance from the curve or drawing (in its units). "
        "Required unless a JSON request gives one; overrides it if both do.",
        rich_help_panel=_WORK,
        show_default=False,
    ),
]
Strategy = Annotated[
    StrategyName | None,
    typer.Option(help="subdivide (Walton & Meek) or fewest-arcs.", rich_help_panel=_WORK),
]
UnitsOption = Annotated[
    Units | None,
    typer.Option(
        help="Drawings: the unit of the output and of every length given. A path or "
        "spiral: the G-code's unit (G21/G20).",
        rich_help_panel=_WORK,
    ),
]
FeedRate = Annotated[
    float | None,
    typer.Option(help="Cutting feed, units/min: asks for a program.", rich_help_panel=_GCODE),
]
Decimals = Annotated[
    int | None,
    typer.Option(
        help="Digits after the point, 3-6 (default 4 mm, 5 inch).", rich_help_panel=_GCODE
    ),
]
ArcFormat = Annotated[
    Literal["ij", "r"] | None,
    typer.Option(help="Arc centres as I/J offsets or R words.", rich_help_panel=_GCODE),
]
LineNumbers = Annotated[
    bool | None, typer.Option(help="N10, N20, ... on every block.", rich_help_panel=_GCODE)
]
Comments = Annotated[
    bool | None,
    typer.Option(help="A header: tolerance, counts, measured deviation.", rich_help_panel=_GCODE),
]
SafeZ = Annotated[
    float | None, typer.Option(help="Retract height (with --cut-z).", rich_help_panel=_GCODE)
]
CutZ = Annotated[
    float | None, typer.Option(help="Cutting depth (with --safe-z).", rich_help_panel=_GCODE)
]
PlungeFeedRate = Annotated[
    float | None, typer.Option(help="Feed of the plunge.", rich_help_panel=_GCODE)
]
StepDown = Annotated[
    float | None,
    typer.Option(help="Cut in passes at most this deep (cut_z < 0).", rich_help_panel=_GCODE),
]
MinArcLength = Annotated[
    float | None,
    typer.Option(
        help="Shorter arcs become lines where the tolerance allows.", rich_help_panel=_GCODE
    ),
]
MaxRadius = Annotated[
    float | None,
    typer.Option(
        help="Flatter arcs become lines where the tolerance allows.", rich_help_panel=_GCODE
    ),
]
Layers = Annotated[
    list[str] | None,
    typer.Option(
        help="DXF: read only these layers (repeat, or separate with commas).",
        rich_help_panel=_DRAWING,
        show_default=False,
    ),
]
SourceUnitsOption = Annotated[
    SourceUnits | None,
    typer.Option(
        help="The unit of the document's numbers, overriding its own.", rich_help_panel=_DRAWING
    ),
]
JoinTolerance = Annotated[
    float | None,
    typer.Option(
        help="Join ends closer than this (default tolerance/10).", rich_help_panel=_DRAWING
    ),
]
Order = Annotated[
    bool | None,
    typer.Option(
        help="Order toolpaths to shorten the rapids (default on).", rich_help_panel=_DRAWING
    ),
]
ChooseStart = Annotated[
    bool | None,
    typer.Option(help="Start each closed contour nearest the tool.", rich_help_panel=_DRAWING),
]
Server = Annotated[
    str | None,
    typer.Option(
        help="Send the work to the service at this URL instead of computing it here.",
        rich_help_panel=_RUN,
        show_default=False,
    ),
]
FormatOption = Annotated[
    Format | None,
    typer.Option(
        "--format",
        "-f",
        help="Output format (default: by the suffix of -o, else json).",
        rich_help_panel=_RUN,
        show_default=False,
    ),
]
OutputFile = Annotated[
    Path | None,
    typer.Option(
        "--output",
        "-o",
        help="Write here (.ngc .gcode .nc .dxf .svg .json); - or none: stdout.",
        rich_help_panel=_RUN,
        show_default=False,
        dir_okay=False,
    ),
]
Quiet = Annotated[
    bool, typer.Option("--quiet", "-q", help="No summary table.", rich_help_panel=_RUN)
]


@dataclass(frozen=True)
class Overrides:
    """The request fields the command line sets (only those given)."""

    tolerance: float | None = None
    strategy: str | None = None
    units: str | None = None
    gcode: dict[str, Any] = field(default_factory=dict)
    drawing: dict[str, Any] = field(default_factory=dict)
    tooling: Tooling = field(default_factory=Tooling)

    @classmethod
    def of(
        cls,
        tolerance: float | None,
        strategy: str | None,
        units: str | None,
        tooling: Tooling | None = None,
        **given: Any,
    ) -> Overrides:
        """From the commands' keyword arguments (``None``: not given); ``tooling``: the
        offset and machining options (:mod:`~arcspline.cli.tooling`)."""
        unknown = set(given) - set(GCODE_FIELDS) - set(DRAWING_FIELDS)
        assert not unknown, f"not request fields: {unknown}"
        if given.get("layers") is not None:
            given["layers"] = [name for item in given["layers"] for name in item.split(",") if name]
        gcode = {k: v for k, v in given.items() if k in GCODE_FIELDS and v is not None}
        drawing = {k: v for k, v in given.items() if k in DRAWING_FIELDS and v is not None}
        return cls(tolerance, strategy, units, gcode, drawing, tooling or Tooling())

    @property
    def asks_for_program(self) -> bool:
        return bool(self.gcode)

    def apply(self, request: dict[str, Any], kind: Kind) -> dict[str, Any]:
        """``request`` with these fields set (a new dict; raises :class:`UsageError` where an
        option cannot apply)."""
        body = dict(request)
        if self.tolerance is not None:
            body["tolerance"] = self.tolerance
        if "tolerance" not in body:
            raise UsageError("required, as the request gives no tolerance", "--tolerance")
        if self.strategy is not None:
            body["strategy"] = self.strategy
        gcode = {**(body.get("gcode") or {}), **self.gcode}
        if kind == "drawing":
            body.update(self.drawing)
            if self.units is not None:
                body["units"] = self.units
                if "units" in gcode:  # a drawing's program is in its units; said once
                    gcode["units"] = self.units
        else:
            if self.drawing:
                names = ", ".join("--" + name.replace("_", "-") for name in self.drawing)
                raise UsageError(f"only for drawings (SVG or DXF), not for a {kind}", names)
            if self.units is not None:
                if not gcode:
                    raise UsageError(
                        f"a {kind} has no unit of its own: --units is its G-code's (and its "
                        "DXF's or SVG's), which needs --feed-rate",
                        "--units",
                    )
                gcode["units"] = self.units
        if gcode:
            body["gcode"] = gcode
        return self.tooling.apply(body, kind)
