"""Reading the command line's outputs back without its code: a DXF through ezdxf, an SVG's
path data through a few regular expressions, the JSON answer as plain JSON; each as the
end points of its segments, to compare."""

from __future__ import annotations

import math
import re
import xml.etree.ElementTree as ET
from pathlib import Path
from typing import Any

import ezdxf

Point = tuple[float, float]
_SVG = "{http://www.w3.org/2000/svg}"
_TOKEN = re.compile(r"[MLAZmlaz]|[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?")


def json_segments(answer: dict[str, Any]) -> list[dict[str, Any]]:
    """Every segment of a spiral's, a path's or a drawing's JSON answer, in order."""
    if "segments" in answer:
        return list(answer["segments"])
    parts = answer.get("subpaths") or answer["toolpaths"]
    return [segment for part in parts for segment in part["segments"]]


def json_ends(answer: dict[str, Any]) -> list[tuple[Point, Point]]:
    return [(tuple(s["start"]), tuple(s["end"])) for s in json_segments(answer)]  # type: ignore[misc]


def dxf_ends(path: Path) -> list[tuple[Point, Point]]:
    """The end points of every LINE and ARC of a DXF's modelspace (an ARC's from its centre,
    radius and angles, anticlockwise as DXF draws them)."""
    ends = []
    for entity in ezdxf.readfile(path).modelspace():
        if entity.dxftype() == "LINE":
            start, end = entity.dxf.start, entity.dxf.end
            ends.append(((start.x, start.y), (end.x, end.y)))
        elif entity.dxftype() == "ARC":
            c, r = entity.dxf.center, entity.dxf.radius
            a0, a1 = math.radians(entity.dxf.start_angle), math.radians(entity.dxf.end_angle)
            ends.append(
                ((c.x + r * math.cos(a0), c.y + r * math.sin(a0)),
                 (c.x + r * math.cos(a1), c.y + r * math.sin(a1)))
            )  # fmt: skip
        else:
            raise AssertionError(f"unexpected {entity.dxftype()} in the DXF")
    return ends


def svg_points(text: str) -> list[Point]:
    """Every end point of the absolute M, L and A commands of an SVG's paths, y turned up."""
    points = []
    for element in ET.fromstring(text).iter(f"{_SVG}path"):
        tokens = _TOKEN.findall(element.get("d", ""))
        i = 0
        while i < len(tokens):
            command = tokens[i]
            assert command in "MLAZ", f"not an absolute M, L, A or Z: {command}"
            skip = {"M": 2, "L": 2, "A": 7, "Z": 0}[command]
            if skip:
                x, y = float(tokens[i + skip - 1]), float(tokens[i + skip])
                points.append((x, -y))
            i += skip + 1
    return points


def same_ends(
    got: list[tuple[Point, Point]], expected: list[tuple[Point, Point]], within: float
) -> bool:
    """The same segments by their end points, whichever way each is drawn."""

    def rounded(point: Point) -> Point:  # an order that rounding cannot upset
        return round(point[0], 6), round(point[1], 6)

    def key(ends: tuple[Point, Point]) -> tuple[Point, Point]:
        a, b = sorted(ends, key=rounded)
        return a, b

    def order(pair: tuple[Point, Point]) -> tuple[Point, Point]:
        return rounded(pair[0]), rounded(pair[1])

    if len(got) != len(expected):
        return False
    return all(
        math.dist(p, q) <= within
        for g, e in zip(
            sorted(map(key, got), key=order), sorted(map(key, expected), key=order), strict=True
        )
        for p, q in zip(g, e, strict=True)
    )
