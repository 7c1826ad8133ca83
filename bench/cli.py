"""The command line, end to end (issue 18): figures printed, never asserted.

Each figure is the median of 5 runs of a whole process (interpreter start, imports, work,
output written), measured in one run beside its baselines:

1. ``python -c pass`` (the interpreter alone) and ``arcspline --version`` (the command's own
   start: no app, no numpy);
2. ``arcspline approx`` in local mode on the paper's spiral at 1e-5 (54 arcs, JSON and G-code),
   beside the same work through the Python API in one process (``arcspline.approximate``,
   the work alone);
3. ``arcspline approx`` on a drawing of the corpus (zebra.svg, Illustrator, 0.01 mm, G-code),
   in local mode and with ``--server`` against a running service (pool of 2).

Run with ``make bench`` or ``.venv/bin/python bench/cli.py``.
"""

from __future__ import annotations

import json
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from serve import service

ROOT = Path(__file__).resolve().parents[1]
COMMAND = str(Path(sys.executable).with_name("arcspline"))
RUNS = 5
PAPER = json.dumps(
    {
        "spiral": {
            "start": [1.5, 3.0],
            "start_tangent": [1.0, 0.0],
            "turn_angle_deg": 51.34,
            "end_curvature": 0.41574,
        }
    }
)
DRAWING = "svg/domoszlai__juicy-gcode__zebra.svg"


def corpus() -> Path:
    for candidate in (os.environ.get("SHARED_CORPUS"), "../shared/corpus", "/work/shared/corpus"):
        if candidate and (ROOT / candidate / "svg").is_dir():
            return ROOT / candidate
    sys.exit("the shared corpus is not here: set SHARED_CORPUS")


def seconds(argv: list[str]) -> float:
    """The median wall time of ``argv`` over :data:`RUNS` runs (each must succeed)."""
    times = []
    for _ in range(RUNS):
        began = time.perf_counter()
        subprocess.run(argv, check=True, capture_output=True, cwd=ROOT)
        times.append(time.perf_counter() - began)
    return statistics.median(times)


def in_process_s() -> float:
    code = (
        "import time, arcspline\n"
        "s = arcspline.Spiral.from_parameters((1.5, 3.0), (1.0, 0.0), 51.34, 0.41574)\n"
        "arcspline.approximate(s, 1e-5)\n"
        "t = time.perf_counter(); n = len(arcspline.approximate(s, 1e-5))\n"
        "print(time.perf_counter() - t, n)"
    )
    out = subprocess.run([sys.executable, "-c", code], check=True, capture_output=True, text=True)
    took, arcs = out.stdout.split()
    assert arcs == "54", arcs
    return float(took)


def row(label: str, value_s: float, note: str = "") -> None:
    print(f"  {label:<58} {value_s * 1000:8.1f} ms {note}")


def main() -> None:
    drawing = str(corpus() / DRAWING)
    with tempfile.TemporaryDirectory() as scratch:
        out = Path(scratch)
        print(f"whole processes, median of {RUNS} ({COMMAND}):")
        row("python -c pass", seconds([sys.executable, "-c", "pass"]))
        row("arcspline --version", seconds([COMMAND, "--version"]))
        row("arcspline.approximate(paper spiral, 1e-5), in process", in_process_s(), "(work only)")
        paper = [COMMAND, "approx", PAPER, "-t", "1e-5"]
        row(
            "arcspline approx <paper spiral> -t 1e-5 -o .json",
            seconds([*paper, "-o", str(out / "p.json")]),
        )
        row("arcspline approx <paper spiral> -t 1e-5 --feed-rate 600 -o .ngc",
            seconds([*paper, "--feed-rate", "600", "-o", str(out / "p.ngc")]))  # fmt: skip
        zebra = [
            COMMAND,
            "approx",
            drawing,
            "-t",
            "0.01",
            "--feed-rate",
            "600",
            "-o",
            str(out / "z.ngc"),
        ]
        row("arcspline approx zebra.svg -t 0.01 -o .ngc (local)", seconds(zebra))
        with service(2) as running:
            row("arcspline approx zebra.svg ... --server (pool of 2)",
                seconds([*zebra, "--server", running.url]))  # fmt: skip


if __name__ == "__main__":
    main()
