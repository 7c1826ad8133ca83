"""Speed of the geometry core beside the plain one-spiral-at-a-time baseline (issue 15).

Prints, for the paper's spiral at each Table 1 tolerance, µs per call of
``arcspline.approximate`` (strategy ``subdivide``) beside ``bench/plain.py`` (the paper's
algorithm written plainly in Python) in the same run, with the arc counts of both (which must
agree); then arcs/s over a batch of 10 000 random spirals at mixed tolerances (each
``10^U(-6, -4)`` of its chord) through ``approximate_many`` beside the plain version on a
subset, the share of that time spent in the compiled loop, and how far the rate is from what a
biarc's arithmetic allows. Timings are best times, the rivals timed in turn
(``bench/timing.py``) so that both see the same machine load.

Run with ``make bench`` (or ``.venv/bin/python bench/core.py``); the tests do not run it.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

from plain import plain_approximate
from timing import paired_best

from arcspline import Spiral, approximate, approximate_many
from arcspline.geometry.fit import STRATEGIES
from arcspline.geometry.fit.batch import frame_table

PAPER = {"start": (1.5, 3.0), "start_tangent": (1.0, 0.0), "turn_angle_deg": 51.34}
PAPER_CURVATURE = 0.41574
TABLE1_TOLERANCES = (0.1, 0.01, 0.001, 1e-4, 1e-5)
BATCH_SIZE = 10_000
PLAIN_SUBSET = 500
#: Mixed tolerances: each spiral's is 10**U(LOW, HIGH) of its chord.
RELATIVE_TOLERANCE_EXPONENTS = (-6.0, -4.0)
SEED = 20260522
#: Seconds each comparison runs for (the rivals in turn, as many rounds as fit).
BUDGET_S = 2.0

SINGLE_TARGET_US = 40.0  # one paper spiral at 1e-5
SINGLE_TARGET = 80.0  # × plain
BATCH_TARGET_ARCS_PER_S = 2_500_000.0
#: What a core could do if it did nothing but a biarc's arithmetic: ~200 floating-point
#: operations (with its square roots, divisions and root iterations) at ~2 Gflop/s.
ARITHMETIC_BOUND_ARCS_PER_S = 10_000_000.0

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
    core = ratio = 0.0
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
        f"targets at 1e-5: ≤ {SINGLE_TARGET_US:g} µs — {core * 1e6:.1f} µs — "
        f"{verdict(core * 1e6 <= SINGLE_TARGET_US)}; ≥ {SINGLE_TARGET:g}× plain — "
        f"{ratio:.0f}× — {verdict(ratio >= SINGLE_TARGET)}"
    )


def batch() -> None:
    params = random_spirals(BATCH_SIZE, SEED)
    spirals = [Spiral.from_parameters(*p) for p in params]
    rng = np.random.default_rng(SEED + 1)
    relative = 10.0 ** rng.uniform(*RELATIVE_TOLERANCE_EXPONENTS, BATCH_SIZE)
    tolerances = [float(r) * s.chord for r, s in zip(relative, spirals, strict=True)]
    results = approximate_many(spirals, tolerances)
    failures = [r for r in results if isinstance(r, Exception)]
    assert not failures, f"{len(failures)} spirals failed: {failures[0]}"
    arcs = sum(len(r) for r in results if not isinstance(r, Exception))

    subset, sub_tol = params[:PLAIN_SUBSET], tolerances[:PLAIN_SUBSET]
    plain_arcs = sum(
        len(plain_approximate(*p, tol)) for p, tol in zip(subset, sub_tol, strict=True)
    )
    core_sub_arcs = sum(len(r) for r in results[:PLAIN_SUBSET] if not isinstance(r, Exception))
    same = "the same count" if plain_arcs == core_sub_arcs else f"the core: {core_sub_arcs}"

    def run_plain() -> None:
        for p, tol in zip(subset, sub_tol, strict=True):
            plain_approximate(*p, tol)

    # The compiled loop alone, on the same spirals: what the Python around it costs.
    frames = frame_table([s.frame for s in spirals])
    tol_array = np.array(tolerances)
    kernel = STRATEGIES["subdivide"]
    core, plain, loop = paired_best(
        [
            lambda: approximate_many(spirals, tolerances),
            run_plain,
            lambda: kernel(frames, tol_array, 10_000, 1e-10),
        ],
        6.0,
    )
    core_rate, plain_rate = arcs / core, plain_arcs / plain
    low, high = RELATIVE_TOLERANCE_EXPONENTS
    print()
    print(
        f"Batch: {BATCH_SIZE} random spirals (seed {SEED}; θ 1..89°, |c| 1e-2..1e2), "
        f"tolerance 10^U({low:g}, {high:g}) × chord: {arcs} arcs ({arcs / BATCH_SIZE:.1f} a spiral)"
    )
    print(f"core  approximate_many: {core * 1e3:.1f} ms = {core_rate:,.0f} arcs/s")
    print(
        f"      of which the compiled loop {loop * 1e3:.1f} ms ({loop / core:.0%}; "
        f"{arcs / loop:,.0f} arcs/s), Python around it {(core - loop) * 1e3:.1f} ms"
    )
    print(
        f"plain looped over the first {PLAIN_SUBSET} spirals ({plain_arcs} arcs, {same}; "
        f"arcs/s extrapolated): {plain_rate:,.0f} arcs/s; ratio {core_rate / plain_rate:.0f}×"
    )
    print(
        f"target: ≥ {BATCH_TARGET_ARCS_PER_S:,.0f} arcs/s — "
        f"{verdict(core_rate >= BATCH_TARGET_ARCS_PER_S)}; "
        f"{core_rate / ARITHMETIC_BOUND_ARCS_PER_S:.0%} of the ~10 M arcs/s that a biarc's ~200 "
        "flops allow a core (each kept biarc also costs the evaluations of the pieces split "
        "on the way, about one more)"
    )


def main() -> None:
    print("arcspline core benchmark (one process, one core; best times, rivals in turn)")
    print()
    single()
    batch()


if __name__ == "__main__":
    main()
