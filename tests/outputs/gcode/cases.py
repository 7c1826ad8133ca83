"""The spirals and options the G-code tests write programs for: real approximations only.

Each case is a spiral, a tolerance and a strategy, chosen to reach one kind of difficulty;
``program()`` writes (and reads back) one case at one set of options, cached per process.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cache
from typing import Any

from arcspline.geometry import ArcSpline, Spiral, approximate
from arcspline.outputs.gcode import GcodeOptions, write_program
from tests.support import gcode_reader


@dataclass(frozen=True)
class Case:
    spiral: dict[str, Any]
    tolerance: float
    strategy: str = "subdivide"


PAPER = {"start": (1.5, 3.0), "start_tangent": (1.0, 0.0), "turn_angle_deg": 51.34}
CASES: dict[str, Case] = {
    # The paper's example, both turning directions and both strategies.
    "paper": Case({**PAPER, "end_curvature": 0.41574}, 1e-3),
    "paper-cw": Case({**PAPER, "end_curvature": -0.41574}, 1e-4),
    "paper-fewest": Case({**PAPER, "end_curvature": 0.41574}, 1e-4, "fewest-arcs"),
    # About 20 µm across: a handful of units in the last place per arc at 3 decimals.
    "tiny": Case(
        {
            "start": (0.01, -0.02),
            "start_tangent": (0.3, 1.0),
            "turn_angle_deg": 30.0,
            "end_curvature": 40.0,
        },
        1e-5,
    ),
    # Pieces shorter than one unit in the last place at 3 decimals: rounded ends coincide.
    "micro": Case(
        {
            "start": (0.3, 0.2),
            "start_tangent": (1.0, -1.0),
            "turn_angle_deg": 60.0,
            "end_curvature": -200.0,
        },
        1e-6,
    ),
    # Some 15,000 units across, clockwise, with centres hundreds of thousands away.
    "large": Case(
        {
            "start": (-250.0, 400.0),
            "start_tangent": (-1.0, 2.0),
            "turn_angle_deg": 80.0,
            "end_curvature": -0.002,
        },
        1e-2,
    ),
    # Turning by 0.01°: radii near a million, sweeps near 1e-4 rad.
    "straight": Case(
        {
            "start": (10.0, 20.0),
            "start_tangent": (1.0, 1.0),
            "turn_angle_deg": 0.01,
            "end_curvature": -2e-6,
        },
        1e-4,
    ),
    # Turning by 1e-9°: the core itself writes two lines.
    "flat": Case(
        {
            "start": (1.0, 2.0),
            "start_tangent": (1.0, 1.0),
            "turn_angle_deg": 1e-9,
            "end_curvature": 1e-12,
        },
        1e-3,
    ),
    # Turning by 89°, from a straight start into a 5 mm radius.
    "sharp": Case(
        {
            "start": (-3.0, -4.0),
            "start_tangent": (0.0, -1.0),
            "turn_angle_deg": 89.0,
            "end_curvature": 200.0,
        },
        1e-4,
    ),
}
PRECISIONS: list[tuple[str, int]] = [("mm", 3), ("mm", 4), ("inch", 4), ("inch", 5)]
ARC_FORMATS = ["ij", "r"]
MATRIX = [
    (name, units, decimals, fmt)
    for name in CASES
    for units, decimals in PRECISIONS
    for fmt in ARC_FORMATS
]


def matrix_id(entry: tuple[str, str, int, str]) -> str:
    name, units, decimals, fmt = entry
    return f"{name}-{units}{decimals}-{fmt}"


@cache
def spiral(name: str) -> Spiral:
    return Spiral.from_parameters(**CASES[name].spiral)


@cache
def spline(name: str) -> ArcSpline:
    case = CASES[name]
    return approximate(spiral(name), case.tolerance, strategy=case.strategy)  # type: ignore[arg-type]


@dataclass(frozen=True)
class Written:
    """One program, with what it was written from and what the reader made of it."""

    name: str
    spiral: Spiral
    spline: ArcSpline
    options: GcodeOptions
    text: str
    program: gcode_reader.Program

    @property
    def decimals(self) -> int:
        return self.options.resolved_decimals

    @property
    def ulp(self) -> float:
        return 10.0**-self.decimals


@cache
def program(name: str, **options: Any) -> Written:
    opts = GcodeOptions(**{"feed_rate": 1200.0, **options})
    text = write_program(spline(name), spiral(name), opts)
    return Written(name, spiral(name), spline(name), opts, text, gcode_reader.read(text))


def matrix_program(entry: tuple[str, str, int, str]) -> Written:
    name, units, decimals, fmt = entry
    return program(name, units=units, decimals=decimals, arc_format=fmt)
