"""Whole drawings of the shared corpus: time and output segments per file, joined and
ordered, against each element approximated alone, and the rapids before and after ordering.

For every SVG and DXF file of the corpus (``$SHARED_CORPUS`` or ``../shared/corpus``), at
0.01 mm and 0.001 mm with ``subdivide`` and ``fewest-arcs``, prints:

* input: elements read (skipped), input segments, toolpaths after joining;
* the time to read the document, and of the pipeline after it (tidy, join, order,
  approximate: ``approximate_drawing``), best of a few runs;
* output segments, and the BASELINE measured in the same run: the paths issue's pipeline,
  every element read (and tidied) approximated as a path of its own (no joining, no
  ordering) — segments and time;
* rapid length from the origin through every toolpath, in the document's order and as cut.

Files the pipeline refuses are listed with the refusal. Run with
``.venv/bin/python bench/drawings.py``; the tests do not run it.
"""

from __future__ import annotations

import platform
import time
from collections.abc import Callable, Sequence
from functools import partial
from typing import TypeVar

from timing import corpus_dir

from arcspline.drawings import DocumentError, Element
from arcspline.drawings.approximate import (
    CURVE_FRACTION,
    SNAP_FRACTION,
    DrawingOptions,
    approximate_drawing,
)
from arcspline.drawings.document import DocumentSpec
from arcspline.drawings.tidy import tidy
from arcspline.geometry import GeometryError, Limits, PathSpline, StrategyName, approximate_path
from arcspline.geometry.curves.segments import Path

LIMITS = Limits(max_segments=2_000_000)
TOLERANCES_MM = (0.01, 0.001)
STRATEGIES = ("subdivide", "fewest-arcs")
REPEATS = 3
T = TypeVar("T")


def _best(f: Callable[[], T]) -> tuple[T, float]:
    best, result = float("inf"), None
    for _ in range(REPEATS):
        t0 = time.perf_counter()
        result = f()
        best = min(best, time.perf_counter() - t0)
    assert result is not None
    return result, best


def _each_alone(
    elements: Sequence[Element], tolerance: float, strategy: StrategyName
) -> list[PathSpline]:
    """The baseline: every element (tidied) approximated as a path of its own."""
    return [approximate_path(Path((e.subpath,)), tolerance, strategy, LIMITS) for e in elements]


def main() -> None:
    corpus = corpus_dir()
    print(
        f"# drawings of the corpus ({platform.processor() or platform.machine()}, "
        f"python {platform.python_version()})"
    )
    files = sorted(p for kind in ("svg", "dxf") for p in (corpus / kind).iterdir()
                   if p.suffix.lower() == f".{kind}")  # fmt: skip
    header = (
        f"{'file':48} {'tol':>6} {'strategy':>11} {'read':>6} {'skip':>5} {'in seg':>7} "
        f"{'paths':>6} {'out seg':>8} {'ms':>8} {'base seg':>8} {'base ms':>8} "
        f"{'rapid before':>12} {'after':>10}"
    )
    print(header)
    totals = {key: [0, 0.0, 0, 0.0] for key in ((t, s) for t in TOLERANCES_MM for s in STRATEGIES)}
    for file in files:
        fmt = file.suffix.lower().lstrip(".")
        curve_mm = min(TOLERANCES_MM) * CURVE_FRACTION  # read once, for the finest tolerance
        spec = DocumentSpec(file.read_bytes(), fmt, curve_tolerance_mm=curve_mm)  # type: ignore[arg-type]
        name = file.name[:48]
        try:
            drawing, read_s = _best(spec.read)
        except DocumentError as error:
            print(f"{name:48} refused: {error}")
            continue
        segments_in = sum(len(e.subpath.segments) for e in drawing.elements)
        print(f"{name:48} read in {read_s * 1e3:.1f} ms ({spec.content.__len__()} bytes)")
        for tolerance in TOLERANCES_MM:
            for strategy in STRATEGIES:
                options = DrawingOptions(tolerance, strategy)  # type: ignore[arg-type]
                try:
                    result, seconds = _best(partial(approximate_drawing, drawing, options, LIMITS))
                    alone = tidy(drawing.elements, tolerance * SNAP_FRACTION).elements
                    base, base_s = _best(partial(_each_alone, alone, tolerance, strategy))
                except (DocumentError, GeometryError) as error:
                    print(f"{name:48} {tolerance:6g} {strategy:>11} refused: {error}")
                    continue
                out = result.spline.segment_count
                base_out = sum(b.segment_count for b in base)
                total = totals[(tolerance, strategy)]
                total[0] += out
                total[1] += seconds
                total[2] += base_out
                total[3] += base_s
                print(
                    f"{name:48} {tolerance:6g} {strategy:>11} {len(drawing.elements):6d} "
                    f"{drawing.skipped:5d} {segments_in:7d} {len(result.toolpaths):6d} "
                    f"{out:8d} {seconds * 1e3:8.1f} {base_out:8d} {base_s * 1e3:8.1f} "
                    f"{result.rapid_before:12.1f} {result.rapid_after:10.1f}"
                )
    print("\n# totals over the corpus")
    for (tolerance, strategy), (out, seconds, base_out, base_s) in totals.items():
        print(
            f"{tolerance:6g} {strategy:>11}: {out} segments in {seconds:.2f} s "
            f"(each element alone: {base_out} segments in {base_s:.2f} s)"
        )


if __name__ == "__main__":
    main()
