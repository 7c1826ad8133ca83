"""A raw document's offset or machining options, from the query string (docs/http-api.md,
"Offsets and machining"): ``?offset=3&side=outside`` is ``"offset": {"distance": 3, "side":
"outside"}``, ``?tool_diameter=6&cut=inside&tabs=4&tab_width=5&tab_height=1.5`` is
``"machining": {...}`` — the names the command line uses too."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

from pydantic import BaseModel

from .offset_schemas import MachiningRequest, OffsetRequest, TabsRequest

#: Each query parameter and the request field it gives (``join``: of whichever is asked).
TOOL_PARAMETERS: dict[str, tuple[str, ...]] = {
    "offset": ("offset", "distance"),
    "side": ("offset", "side"),
    "mitre_limit": ("offset", "mitre_limit"),
    "tool_diameter": ("machining", "tool_diameter"),
    "cut": ("machining", "cut"),
    "direction": ("machining", "direction"),
    "lead_radius": ("machining", "lead_radius"),
    "entry": ("machining", "entry"),
    "compensation": ("machining", "compensation"),
    "tool_number": ("machining", "tool_number"),
    "tabs": ("machining", "tabs", "count"),
    "tab_width": ("machining", "tabs", "width"),
    "tab_height": ("machining", "tabs", "height"),
    "join": ("offset", "join"),
}
_MODELS: dict[str, type[BaseModel]] = {
    "offset": OffsetRequest,
    "machining": MachiningRequest,
    "tabs": TabsRequest,
}
_BY_FIELD = {path: name for name, path in TOOL_PARAMETERS.items()} | {
    ("machining", "join"): "join",
}


def _path(name: str, machining: bool) -> tuple[str, ...]:
    if name == "join" and machining:
        return ("machining", "join")
    return TOOL_PARAMETERS[name]


def tool_fields(query: Mapping[str, str]) -> dict[str, Any]:
    """The ``offset`` and ``machining`` objects the query's parameters give (none if it
    names none of them); ``join`` goes to ``machining`` when a machining parameter is given."""
    names = [name for name in query if name in TOOL_PARAMETERS]
    machining = any(TOOL_PARAMETERS[name][0] == "machining" for name in names)
    fields: dict[str, Any] = {}
    for name in names:
        *parents, leaf = _path(name, machining)
        where = fields
        for parent in parents:
            where = where.setdefault(parent, {})
        where[leaf] = query[name]
    return fields


def query_loc(loc: Sequence[str | int]) -> tuple[str | int, ...]:
    """The query parameter a validation error of the ``offset`` or ``machining`` objects
    names (the object's path as is, when no single parameter gives it)."""
    for length in range(len(loc), 0, -1):
        name = _BY_FIELD.get(tuple(str(part) for part in loc[:length]))
        if name is not None:
            return ("query", name)
    return ("query", *loc)


def tool_field(name: str) -> tuple[type[BaseModel], str, str]:
    """Query parameter ``name``'s model, its field there, and its dotted path in the JSON
    body (for the contract's declaration)."""
    path = TOOL_PARAMETERS[name]
    return _MODELS[path[-2]], path[-1], ".".join(path)
