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

from arcspline.geometry import DEFAULT_LIMITS, STRATEGIES, SpiralFromParameters
from arcspline.outputs.gcode import GcodeOptions

from .jobs import Job, approximate_chunk, approximate_one, render

#: The paper's example (Walton & Meek 1996, Table 1).
_SPIRAL = SpiralFromParameters((1.5, 3.0), (1.0, 0.0), 51.34, 0.41574)


def warm() -> None:
    """Run a job of each kind: every strategy, alone and in a chunk, with a G-code program,
    a refused one, and the preview's picture."""
    jobs = [
        *(Job(_SPIRAL, 1e-3, strategy) for strategy in STRATEGIES),
        Job(_SPIRAL, 1e-3, outputs=(("gcode", GcodeOptions(feed_rate=1000.0)),)),
        Job(_SPIRAL, 1e-300),
    ]
    for job in jobs:
        approximate_one(job, DEFAULT_LIMITS)
    approximate_chunk(jobs, DEFAULT_LIMITS)
    render(Job(_SPIRAL, 1e-3, outputs=(("svg", None),)), DEFAULT_LIMITS)


warm()
