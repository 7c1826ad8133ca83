"""Speed of the geometry core beside the plain one-spiral-at-a-time baseline (issue 2, point 6).

Prints, for the paper's spiral at each Table 1 tolerance, µs per spiral for the core
(``arcspline.geometry.approximate``) and for ``bench/plain.py`` in the same run, with the arc
counts of both (which must agree); then arcs/s over 10 000 random spirals at 1e-5 of their
chord through ``approximate_many``, beside the plain version. Timings are best times, the core and
the plain version timed in turn (``bench/timing.py``) so that both see the same machine load.
Run with ``make bench`` (or ``.venv/bin/python bench/core.py``); the tests do not run it.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from plain import plain_approximate
from timing import paired_best

from arcspline.geometry import Spiral, approximate, approximate_many

PAPER = {"start": (1.5, 3.0), "start_tangent": (1.0, 0.0), "turn_angle_deg": 51.34}
PAPER_CURVATURE = 0.41574
TABLE1_TOLERANCES = (0.1, 0.01, 0.001, 1e-4, 1e-5)
BATCH_SIZE = 10_000
PLAIN_SUBSET = 500
RELATIVE_TOLERANCE = 1e-5
SEED = 20260522
#: Seconds each comparison runs for (core and plain in turn, as many rounds as fit).
BUDGET_S = 2.0

SINGLE_TARGET = 10.0  # × plain, one spiral at 1e-5
BATCH_TARGET_ARCS_PER_S = 1_000_000.0
BATCH_TARGET = 50.0  # × plain


Params = tuple[tuple[float, float], tuple[float, float], float, float]


def random_spirals(n: int, seed: int) -> list[Params]:
    """Start uniform in ±100, tangent normal, θ uniform 1..89°, |c| log-uniform 1e-2..1e2."""
    rng = np.random.default_rng(seed)
    start = rng.uniform(-100.0, 100.0, (n, 2))
    tangent = rng.normal(size=(n, 2))
    theta = rng.uniform(1.0, 89.0, n)
    curvature = 10.0 ** rng.uniform(-2.0, 2.0, n) * rng.choice([-1.0, 1.0], n)
    return [
        (
            (float(start[i, 0]), float(start[i, 1])),
            (float(tangent[i, 0]), float(tangent[i, 1])),
            float(theta[i]),
            float(curvature[i]),
        )
        for i in range(n)
    ]


def verdict(met: bool) -> str:
    return "met" if met else "NOT met"


def single() -> None:
    paper = Spiral.from_parameters(**PAPER, end_curvature=PAPER_CURVATURE)
    print("One spiral: the paper's example (start (1.5, 3), tangent (1, 0), 51.34°, c 0.41574)")
    print(f"{'tolerance':>10} {'arcs':>5} {'core µs':>9} {'plain µs':>9} {'ratio':>7}")
    ratio = 0.0
    for tol in TABLE1_TOLERANCES:
        core_arcs = len(approximate(paper, tol))
        plain_arcs = len(
            plain_approximate(PAPER["start"], PAPER["start_tangent"], 51.34, PAPER_CURVATURE, tol)
        )
        assert core_arcs == plain_arcs, f"arc counts differ at {tol}: {core_arcs} vs {plain_arcs}"
        core, plain = paired_best(
            [
                lambda tol=tol: approximate(paper, tol),
                lambda tol=tol: plain_approximate(
                    PAPER["start"], PAPER["start_tangent"], 51.34, PAPER_CURVATURE, tol
                ),
            ],
            BUDGET_S,
        )
        ratio = plain / core
        print(f"{tol:>10g} {core_arcs:>5} {core * 1e6:>9.1f} {plain * 1e6:>9.1f} {ratio:>6.1f}×")
    print("arc counts: core == plain at every tolerance (checked)")
    print(
        f"target: ≥ {SINGLE_TARGET:g}× plain at 1e-5 — got {ratio:.1f}× — "
        f"{verdict(ratio >= SINGLE_TARGET)}"
    )


def batch() -> None:
    params = random_spirals(BATCH_SIZE, SEED)
    spirals = [
        Spiral.from_parameters(start, tangent, theta, curvature)
        for start, tangent, theta, curvature in params
    ]
    tolerances = [RELATIVE_TOLERANCE * s.chord for s in spirals]
    results = approximate_many(spirals, tolerances)
    failures = [r for r in results if isinstance(r, Exception)]
    assert not failures, f"{len(failures)} spirals failed: {failures[0]}"
    arcs = sum(len(r) for r in results if not isinstance(r, Exception))

    subset = params[:PLAIN_SUBSET]
    sub_tol = tolerances[:PLAIN_SUBSET]
    plain_arcs = sum(
        len(plain_approximate(start, tangent, theta, curvature, tol))
        for (start, tangent, theta, curvature), tol in zip(subset, sub_tol, strict=True)
    )
    core_sub_arcs = sum(len(r) for r in results[:PLAIN_SUBSET] if not isinstance(r, Exception))
    same = (
        "the same count as the core's"
        if plain_arcs == core_sub_arcs
        else (f"the core has {core_sub_arcs}")
    )

    def run_plain() -> None:
        for (start, tangent, theta, curvature), tol in zip(subset, sub_tol, strict=True):
            plain_approximate(start, tangent, theta, curvature, tol)

    core, plain = paired_best([lambda: approximate_many(spirals, tolerances), run_plain], 6.0)
    core_rate = arcs / core
    plain_rate = plain_arcs / plain
    ratio = core_rate / plain_rate
    print()
    print(
        f"Batch: {BATCH_SIZE} random spirals (seed {SEED}; θ 1..89°, |c| 1e-2..1e2), "
        f"tolerance {RELATIVE_TOLERANCE:g} × chord"
    )
    print(f"core  approximate_many: {arcs} arcs in {core:.3f} s = {core_rate:,.0f} arcs/s")
    print(
        f"plain looped over the first {PLAIN_SUBSET} spirals only ({plain_arcs} arcs, {same}; "
        f"arcs/s extrapolated from this subset): {plain:.3f} s = {plain_rate:,.0f} arcs/s"
    )
    print(f"ratio: {ratio:.1f}×")
    print(
        f"target: ≥ {BATCH_TARGET_ARCS_PER_S:,.0f} arcs/s — "
        f"{verdict(core_rate >= BATCH_TARGET_ARCS_PER_S)}; "
        f"≥ {BATCH_TARGET:g}× plain — {verdict(ratio >= BATCH_TARGET)}"
    )


def main() -> None:
    print("arcspline core benchmark (one process, one core; best times, core and plain in turn)")
    print()
    single()
    batch()


if __name__ == "__main__":
    main()
