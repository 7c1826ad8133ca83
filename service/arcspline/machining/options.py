"""The options of a machining program (docs/machining.md §1), and their validation."""

from __future__ import annotations

import math
import numbers
from typing import Literal, NamedTuple, get_args

from arcspline.geometry import GeometryError

Cut = Literal["auto", "outside", "inside", "on"]
Direction = Literal["climb", "conventional"]
Entry = Literal["plunge", "ramp"]
Compensation = Literal["computed", "controller"]
Join = Literal["round", "mitre"]

CUTS: tuple[str, ...] = get_args(Cut)
DIRECTIONS: tuple[str, ...] = get_args(Direction)
ENTRIES: tuple[str, ...] = get_args(Entry)
COMPENSATIONS: tuple[str, ...] = get_args(Compensation)
JOINS: tuple[str, ...] = get_args(Join)

#: Most tabs on one contour: more is surely a mistake (a tab every few micrometres).
MAX_TABS = 100
#: Largest tool number a controller's tool table holds (LinuxCNC's pocket numbers are
#: 16-bit; Fanuc offsets stop far below).
MAX_TOOL_NUMBER = 99_999
#: Largest length accepted (tool diameter, lead radius, tab sizes): the G-code writer's
#: coordinate bound, a kilometre in millimetres.
MAX_LENGTH = 1e6


class Tabs(NamedTuple):
    """Holding tabs on each outside contour: ``count`` of them, evenly spaced, each leaving
    ``width`` of material (along the contour) standing ``height`` above the cut depth."""

    # ``count`` shadows ``tuple.count``: the name is the request field's (docs/machining.md).
    count: int  # type: ignore[assignment]
    width: float
    height: float


class MachiningOptions(NamedTuple):
    """How to machine a drawing's contours with an end mill of ``tool_diameter``
    (docs/machining.md §1). Validate with :func:`check`."""

    tool_diameter: float
    cut: Cut = "auto"
    direction: Direction = "climb"
    lead_radius: float | None = None
    entry: Entry = "plunge"
    tabs: Tabs | None = None
    compensation: Compensation = "computed"
    tool_number: int | None = None
    join: Join = "round"

    @property
    def tool_radius(self) -> float:
        return 0.5 * float(self.tool_diameter)

    @property
    def resolved_lead_radius(self) -> float:
        """``lead_radius``, or the tool radius when it is not given (0: no leads)."""
        return self.tool_radius if self.lead_radius is None else float(self.lead_radius)


def _length(value: object, *, zero: bool = False) -> bool:
    """A finite real number in (0, MAX_LENGTH), or 0 when ``zero`` allows it."""
    if not isinstance(value, numbers.Real) or isinstance(value, bool):
        return False
    number = float(value)
    low_ok = number >= 0.0 if zero else number > 0.0
    return math.isfinite(number) and low_ok and number < MAX_LENGTH


def _choice(name: str, value: object, allowed: tuple[str, ...]) -> None:
    if value not in allowed:
        raise GeometryError(
            f"machining.{name}", f"must be one of {', '.join(allowed)}, got {value!r}"
        )


def check(options: MachiningOptions) -> MachiningOptions:
    """``options`` if every field is valid; otherwise :class:`GeometryError` naming
    ``machining.<field>``."""
    if not _length(options.tool_diameter):
        raise GeometryError(
            "machining.tool_diameter",
            f"must be a finite number > 0 and below {MAX_LENGTH:g}, got {options.tool_diameter!r}",
        )
    _choice("cut", options.cut, CUTS)
    _choice("direction", options.direction, DIRECTIONS)
    _choice("entry", options.entry, ENTRIES)
    _choice("compensation", options.compensation, COMPENSATIONS)
    _choice("join", options.join, JOINS)
    if options.lead_radius is not None and not _length(options.lead_radius, zero=True):
        raise GeometryError(
            "machining.lead_radius",
            f"must be a finite number ≥ 0 (0: no lead arcs), got {options.lead_radius!r}",
        )
    _check_tabs(options.tabs)
    number = options.tool_number
    if number is not None:
        if options.compensation != "controller":
            raise GeometryError(
                "machining.tool_number", "applies only with compensation 'controller'"
            )
        if isinstance(number, bool) or not isinstance(number, int):
            raise GeometryError("machining.tool_number", f"must be an integer, got {number!r}")
        if not 1 <= number <= MAX_TOOL_NUMBER:
            raise GeometryError(
                "machining.tool_number",
                f"must lie between 1 and {MAX_TOOL_NUMBER}, got {number}",
            )
    return options


def _check_tabs(tabs: Tabs | None) -> None:
    if tabs is None:
        return
    count = tabs.count
    if isinstance(count, bool) or not isinstance(count, int) or not 1 <= count <= MAX_TABS:
        raise GeometryError(
            "machining.tabs.count", f"must be an integer from 1 to {MAX_TABS}, got {count!r}"
        )
    for name in ("width", "height"):
        value = getattr(tabs, name)
        if not _length(value):
            raise GeometryError(
                f"machining.tabs.{name}",
                f"must be a finite number > 0 and below {MAX_LENGTH:g}, got {value!r}",
            )
