"""Timing for the benchmarks: best wall times, with rivals timed in turn.

This build machine is shared: its speed drifts by tens of percent over seconds. Calls that
are compared (the core and the plain baseline, two strategies) are therefore timed in turn,
a short block of calls of one, then of the other, round after round, so that both see the
same drift; each keeps its best single-call time. Blocks rather than single calls keep each
rival's code and data as warm in the caches as it would be timed alone (one call after
another's evicts them: 30 % slower for the core).
"""

from __future__ import annotations

import math
import os
import sys
import time
from collections.abc import Callable, Sequence
from pathlib import Path

#: Seconds of back-to-back calls of one rival before the next one's turn.
BLOCK_S = 0.05


def paired_best(runs: Sequence[Callable[[], object]], budget_s: float) -> list[float]:
    """Best wall time of each of ``runs`` in seconds, timed in turn in blocks of about
    ``BLOCK_S`` (at least three calls each) until about ``budget_s`` has passed (at least
    three rounds)."""
    best = [math.inf] * len(runs)
    began = time.perf_counter()
    rounds = 0
    while rounds < 3 or time.perf_counter() - began < budget_s:
        for j, run in enumerate(runs):
            block_began = time.perf_counter()
            calls = 0
            while calls < 3 or time.perf_counter() - block_began < BLOCK_S:
                start = time.perf_counter()
                run()
                best[j] = min(best[j], time.perf_counter() - start)
                calls += 1
        rounds += 1
    return best


def corpus_dir() -> Path:
    """The shared corpus: ``$SHARED_CORPUS``, ``../shared/corpus`` or ``/work/shared/corpus``
    (exits saying so when none is there)."""
    for candidate in (os.environ.get("SHARED_CORPUS"), "../shared/corpus", "/work/shared/corpus"):
        if candidate and (Path(candidate) / "svg").is_dir():
            return Path(candidate)
    sys.exit("the shared corpus is not here: set SHARED_CORPUS")
