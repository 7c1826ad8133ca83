"""The tool's step of a path or drawing job (docs/http-api.md, "Offsets and machining"):
after the approximation, the contours offset (``arcspline.geometry.offset``) or machined
(``arcspline.machining``) into the tool-centre paths that the answer, its outputs and its
preview are made of.

Runs in the worker, as the rest of a job: only the core, the outputs and the machining
package, never the web stack.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import Any, NamedTuple

from arcspline.geometry import ArcSpline, GeometryError, Limits
from arcspline.geometry.offset import OffsetOptions, offset_path
from arcspline.geometry.path_spline import PathSpline
from arcspline.machining import Machined, MachiningOptions, machine, write_machining
from arcspline.outputs import WRITERS, Part
from arcspline.outputs.drawing_preview import PreviewOptions, ToolView

#: What turns a job's contours into tool-centre paths.
Tooling = OffsetOptions | MachiningOptions

#: How a job names contour ``i`` in its notes and warnings (``toolpaths[i] (drawn by …)``
#: for a drawing, ``path.subpaths[i]`` for a path).
Namer = Callable[[int], str]

#: What a machining refusal of the offset underneath it names, as the machining request's
#: own fields (its ``offset`` is the tool radius the request gave as a diameter).
_MACHINING_FIELDS = {"offset.distance": "machining.tool_diameter", "offset.side": "machining.cut"}


class Tooled(NamedTuple):
    """The tool-centre paths of a job, and what its answer says of them.

    ``origin[k]`` is the contour (the source subpath) of tool-centre path ``k``; ``block`` the
    answer's ``offset`` or ``machining`` object; ``machined`` the plan the program is written
    from (machining only); ``contours`` the part's contours, ``width`` the swept width (the
    tool's diameter) and ``label`` what the legend says of the tool, for the preview.
    """

    spline: PathSpline
    origin: tuple[int, ...]
    block: dict[str, Any]
    machined: Machined | None
    contours: tuple[ArcSpline, ...]
    width: float
    label: str

    def parts(self) -> list[Part]:
        return [(s.spline, s.curve) for s in self.spline.subpaths]


def _offset(spline: PathSpline, options: OffsetOptions, limits: Limits, name: Namer) -> Tooled:
    result = offset_path(spline, options, limits)
    assert result.spline is not None, "offset_path refuses a path whose every contour vanishes"
    notes = [
        {"toolpath": i, "kind": note.kind, "message": f"{name(i)}: {note.message}"}
        for i, note in result.notes
    ]
    block = {
        "offset": {
            "distance": options.distance,
            "side": options.side,
            "contours_in": len(spline.subpaths),
            "paths_out": len(result.spline.subpaths),
            "origin": list(result.origin),
            "source_max_deviation": result.source_max_deviation,
            "notes": notes,
        }
    }
    label = f"offset {options.distance:g} {options.side}"
    return Tooled(
        result.spline, tuple(result.origin), block, None, _contours(spline),
        2.0 * options.distance, label,
    )  # fmt: skip


def _machine(spline: PathSpline, options: MachiningOptions, limits: Limits, name: Namer) -> Tooled:
    try:
        machined = machine(spline, options, limits)
    except GeometryError as error:
        raise _as_machining(error) from None
    contours = [
        {"toolpath": c.source, "cut": c.cut, "direction": c.direction, "depth": c.depth}
        for c in machined.contours
    ]
    warnings = [{"toolpath": i, "message": f"{name(i)}: {words}"} for i, words in machined.warnings]
    block = {
        "machining": {
            "tool_diameter": options.tool_diameter,
            "contours": contours,
            "warnings": warnings,
            "rapid_length": machined.rapid_length,
            "source_max_deviation": machined.source_max_deviation,
        }
    }
    origin = tuple(c.source for c in machined.contours)
    label = f"tool ⌀{options.tool_diameter:g}, cut {options.cut}, {options.direction}"
    return Tooled(
        machined.spline, origin, block, machined, _contours(spline), options.tool_diameter,
        label,
    )  # fmt: skip


def _as_machining(error: GeometryError) -> GeometryError:
    """A refusal of the offset underneath a machining job, in the machining request's
    fields."""
    field = _MACHINING_FIELDS.get(error.field)
    if field is None:
        return error
    return GeometryError(field, error.message, kind=error.kind, limit=error.limit)


def _contours(spline: PathSpline) -> tuple[ArcSpline, ...]:
    return tuple(s.spline for s in spline.subpaths)


def tool(spline: PathSpline, tooling: Tooling, limits: Limits, name: Namer) -> Tooled:
    """The tool-centre paths of ``spline`` (the approximated contours) for ``tooling``: an
    offset, or a machining plan. Raises the core's :class:`GeometryError` (a machining
    refusal of the offset underneath named by the machining request's fields)."""
    if isinstance(tooling, OffsetOptions):
        return _offset(spline, tooling, limits, name)
    return _machine(spline, tooling, limits, name)


def write(name: str, options: Any, parts: Sequence[Part], tooled: Tooled | None) -> str:
    """Output ``name`` of ``parts`` (the tool-centre paths if ``tooled``): with machining, the
    program is the machining plan's (``write_machining``), and a drawing preview shows the
    contours and the swept width too."""
    if tooled is not None and name == "gcode" and tooled.machined is not None:
        return write_machining(tooled.machined, options)
    if tooled is not None and name == "drawing-preview":
        units = options if isinstance(options, str) else "mm"
        view = ToolView(tooled.contours, tooled.width, tooled.label)
        options = PreviewOptions(units, view)
    return WRITERS[name].write(parts, options)
