"""Warm-up: every kind of job run once, so that the first request a worker serves costs what
the next one does.

The kernels are compiled ahead of time (nothing is compiled at request time), but a first
call still pays one-time costs: lazy imports inside numpy and the writers, first-use
allocations, cold caches (measured: the first subdivide job in a new process 0.4 ms, later
ones 0.1 ms). The worker pool's forkserver imports this module (``pool.PRELOAD``) before it
forks any worker, so every worker, and every replacement of one, starts warm; with the
``spawn`` start method each worker imports it before it says it is ready.
"""

from __future__ import annotations

from arcspline.drawings.approximate import DrawingOptions
from arcspline.drawings.document import DocumentSpec
from arcspline.geometry import DEFAULT_LIMITS, STRATEGIES, SpiralFromParameters
from arcspline.outputs.dxf import DxfOptions
from arcspline.outputs.gcode import GcodeOptions
from arcspline.outputs.svg_document import SvgDocumentOptions
from arcspline.paths import PathFromData

from .drawing_jobs import DrawingJob, approximate_drawing_one, render_drawing
from .jobs import Job, PathJob, approximate_chunk, approximate_one, approximate_path_one, render

#: The paper's example (Walton & Meek 1996, Table 1).
_SPIRAL = SpiralFromParameters((1.5, 3.0), (1.0, 0.0), 51.34, 0.41574)
#: A path with every kind of segment and two subpaths.
_PATH = PathFromData(
    "M 0 0 C 10 0 20 10 30 30 L 40 30 A 5 5 0 0 1 50 30 A 8 4 30 0 1 60 20 Z m 5 5 q 5 5 10 0"
)

_CUT = DrawingOptions(tolerance=1e-2)
#: A drawing of each format: an SVG with a transformed group and a DXF (R12) of a line and
#: an arc that join.
_SVG = DocumentSpec(
    b'<svg xmlns="http://www.w3.org/2000/svg" width="40mm" height="30mm" viewBox="0 0 40 30">'
    b'<g transform="rotate(10 20 15)"><path d="M 5 5 C 15 0 25 30 35 5"/>'
    b'<ellipse cx="20" cy="15" rx="8" ry="4"/><rect x="2" y="2" width="10" height="6" rx="1"/>'
    b"</g></svg>",
    "svg",
)
_DXF = DocumentSpec(
    b"0\nSECTION\n2\nENTITIES\n0\nLINE\n8\n0\n10\n0\n20\n0\n11\n10\n21\n0\n"
    b"0\nARC\n8\n0\n10\n10\n20\n5\n40\n5\n50\n270\n51\n90\n0\nENDSEC\n0\nEOF\n",
    "dxf",
)


def warm() -> None:
    """Run a job of each kind: every strategy, alone and in a chunk, with a G-code program,
    a refused one, the preview's picture, and a path of each strategy and its picture."""
    jobs = [
        *(Job(_SPIRAL, 1e-3, strategy) for strategy in STRATEGIES),
        Job(_SPIRAL, 1e-3, outputs=(("gcode", GcodeOptions(feed_rate=1000.0)),)),
        Job(_SPIRAL, 1e-300),
    ]
    for job in jobs:
        approximate_one(job, DEFAULT_LIMITS)
    approximate_chunk(jobs, DEFAULT_LIMITS)
    render(Job(_SPIRAL, 1e-3, outputs=(("svg", None),)), DEFAULT_LIMITS)
    gcode = (("gcode", GcodeOptions(feed_rate=1000.0)),)
    for strategy in STRATEGIES:
        approximate_path_one(PathJob(_PATH, 1e-2, strategy, gcode), DEFAULT_LIMITS)
    render(PathJob(_PATH, 1e-2, outputs=(("svg", None),)), DEFAULT_LIMITS)
    _warm_drawings(gcode)


def _warm_drawings(gcode: tuple[tuple[str, GcodeOptions], ...]) -> None:
    """A drawing of each format, with the program, and each document output."""
    for document in (_SVG, _DXF):
        approximate_drawing_one(DrawingJob(document, _CUT, gcode), DEFAULT_LIMITS)
    for output in (
        ("dxf", DxfOptions()),
        ("svg-document", SvgDocumentOptions()),
        ("drawing-preview", "mm"),
    ):
        render_drawing(DrawingJob(_SVG, _CUT, (output,)), DEFAULT_LIMITS)


warm()
