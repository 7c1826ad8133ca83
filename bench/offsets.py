"""Tool-radius offsets and machining programs over the shared corpus: what they cost on top
of the fit, and what they make.

For every SVG and DXF file of the corpus (``$SHARED_CORPUS`` or ``../shared/corpus``), at
0.01 mm with ``subdivide``, prints:

* the BASELINE measured in the same run: the time to fit the drawing (``approximate_drawing``)
  and its segments;
* the time to offset the fitted drawing 1 mm outside (``offset_path``, fitted again) and the
  segments of the tool-centre paths, or the refusal (an open or crossing contour);
* the time to plan the cut of a 2 mm tool (``machine``, ``cut: auto``) and to write its
  program (``write_machining``: safe_z 5, cut_z −1, step_down 0.5, feed 600), the segments of
  the tool-centre paths with their leads, the rapid length, the program's lines; or the
  refusal.

Times are the best of a few runs (one run when a call takes longer than a second). Run with
``.venv/bin/python bench/offsets.py``; the tests do not run it.
"""

from __future__ import annotations

import platform
import time
from collections.abc import Callable
from functools import partial
from typing import TypeVar

from timing import corpus_dir

from arcspline.drawings import DocumentError
from arcspline.drawings.approximate import CURVE_FRACTION, DrawingOptions, approximate_drawing
from arcspline.drawings.document import DocumentSpec
from arcspline.geometry import GeometryError, Limits
from arcspline.geometry.offset import OffsetOptions, offset_path
from arcspline.machining import MachiningOptions, machine, write_machining
from arcspline.outputs.gcode import GcodeError, GcodeOptions

LIMITS = Limits(max_segments=2_000_000)
TOLERANCE_MM = 0.01
RADIUS_MM = 1.0
GCODE = GcodeOptions(600.0, safe_z=5.0, cut_z=-1.0, step_down=0.5)
#: As in the corpus tests: CadQuery's rational spline says metres but means millimetres.
SOURCE_UNITS = {"CadQuery__cadquery__rational_spline.dxf": "mm"}
REPEATS = 3
#: A call slower than this is timed once.
ONCE_S = 1.0
T = TypeVar("T")


def _best(f: Callable[[], T]) -> tuple[T, float]:
    best = float("inf")
    for _ in range(REPEATS):
        t0 = time.perf_counter()
        result = f()
        best = min(best, time.perf_counter() - t0)
        if best > ONCE_S:
            break
    return result, best


def _refusal(error: Exception) -> str:
    return " ".join(str(error).split())[:70]


def main() -> None:
    corpus = corpus_dir()
    print(
        f"# offsets (outside {RADIUS_MM:g} mm) and machining (tool {2 * RADIUS_MM:g} mm) of the "
        f"corpus at {TOLERANCE_MM} mm ({platform.processor() or platform.machine()}, "
        f"python {platform.python_version()})"
    )
    files = sorted(p for kind in ("svg", "dxf") for p in (corpus / kind).iterdir()
                   if p.suffix.lower() == f".{kind}")  # fmt: skip
    print(
        f"{'file':44} {'paths':>5} {'fit seg':>8} {'fit ms':>8} | {'off seg':>8} {'off ms':>8} | "
        f"{'mach seg':>8} {'plan ms':>8} {'write ms':>8} {'rapid mm':>9} {'lines':>7}"
    )
    totals = [0.0, 0.0, 0.0, 0.0]
    for file in files:
        name = file.name[:44]
        fmt = file.suffix.lower().lstrip(".")
        spec = DocumentSpec(
            file.read_bytes(),
            fmt,  # type: ignore[arg-type]
            source_units=SOURCE_UNITS.get(file.name),
            curve_tolerance_mm=TOLERANCE_MM * CURVE_FRACTION,
        )
        try:
            drawing = spec.read()
            options = DrawingOptions(TOLERANCE_MM)
            fitted, fit_s = _best(partial(approximate_drawing, drawing, options, LIMITS))
        except (DocumentError, GeometryError) as error:
            print(f"{name:44} refused: {_refusal(error)}")
            continue
        spline = fitted.spline
        totals[0] += fit_s
        line = (
            f"{name:44} {len(spline.subpaths):5d} {spline.segment_count:8d} {fit_s * 1e3:8.1f} | "
        )
        try:
            outside = OffsetOptions(RADIUS_MM, "outside")
            offset, off_s = _best(partial(offset_path, spline, outside, LIMITS))
            out = 0 if offset.spline is None else offset.spline.segment_count
            line += f"{out:8d} {off_s * 1e3:8.1f} | "
            totals[1] += off_s
        except GeometryError as error:
            line += f"{'refused: ' + _refusal(error)[:16]:>17} | "
        try:
            tool = MachiningOptions(2 * RADIUS_MM)
            machined, plan_s = _best(partial(machine, spline, tool, LIMITS))
            program, write_s = _best(partial(write_machining, machined, GCODE))
            totals[2] += plan_s
            totals[3] += write_s
            line += (
                f"{machined.spline.segment_count:8d} {plan_s * 1e3:8.1f} {write_s * 1e3:8.1f} "
                f"{machined.rapid_length:9.1f} {program.count(chr(10)):7d}"
            )
        except (GeometryError, GcodeError) as error:
            line += f"refused: {_refusal(error)}"
        print(line, flush=True)
    print(
        f"\n# totals: fit {totals[0]:.2f} s; offset {totals[1]:.2f} s; machining plan "
        f"{totals[2]:.2f} s, program {totals[3]:.2f} s (over the files each accepts)"
    )


if __name__ == "__main__":
    main()
