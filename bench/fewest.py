"""Benchmark: ``fewest-arcs`` against ``subdivide`` — segment counts, deviations and times.

Prints (1) the paper's Table 1 spiral at its five tolerances, with the deviation measured
independently by the test oracle (dense two-sided sampling) and the time ratio to
``subdivide`` (issue 15's target: ≤ 5× at 1e-5); (2) 200 random spirals at random relative
tolerances: mean counts, their ratio and the time ratio, in one batch and one per call; (3)
the 2000-spiral benchmark: the same generator, 2000 spirals, fewest-arcs' mean count beside
the one before issue 15 (the numpy core at commit 9cdb49b, measured with this generator).
Run: ``.venv/bin/python bench/fewest.py``.
"""

from __future__ import annotations

import math
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from timing import paired_best

from arcspline.geometry import ArcSpline, Spiral, approximate, approximate_many
from tests.support import oracle

PAPER = Spiral.from_parameters(
    start=(1.5, 3.0), start_tangent=(1.0, 0.0), turn_angle_deg=51.34, end_curvature=0.41574
)
TOLERANCES = (0.1, 0.01, 1e-3, 1e-4, 1e-5)
RATIO_TARGET = 5.0  # fewest-arcs ÷ subdivide, paper spiral at 1e-5
#: fewest-arcs' total over the 2000-spiral benchmark before issue 15 (numpy core, 9cdb49b).
BEFORE_2000_TOTAL = 10452


def table1() -> None:
    print("Table 1 spiral (start (1.5, 3), tangent (1, 0), θ 51.34°, c 0.41574)")
    print(
        f"{'tolerance':>9} | {'subdivide':>9} {'measured dev':>12} {'ms':>6} | "
        f"{'fewest':>6} {'measured dev':>12} {'ms':>6} | {'time ratio':>10}"
    )
    cp = np.asarray(PAPER.control_points)
    for tol in TOLERANCES:
        row = []
        for strategy in ("subdivide", "fewest-arcs"):
            spline = approximate(PAPER, tol, strategy)  # type: ignore[arg-type]
            verdict = oracle.check(cp, spline, tol)
            assert not verdict.violations, verdict.describe()
            row.append((len(spline), verdict.deviation.max))
        t0, t1 = paired_best(
            [
                lambda t=tol: approximate(PAPER, t),  # type: ignore[misc]
                lambda t=tol: approximate(PAPER, t, "fewest-arcs"),  # type: ignore[misc]
            ],
            1.0,
        )
        (n0, d0), (n1, d1) = row
        print(
            f"{tol:>9g} | {n0:>9d} {d0:>12.6g} {t0 * 1e3:>6.3f} | {n1:>6d} {d1:>12.6g} "
            f"{t1 * 1e3:>6.3f} | {t1 / t0:>9.1f}x"
        )
    verdict = "met" if t1 / t0 <= RATIO_TARGET else "NOT met"
    print(f"target at 1e-5: ≤ {RATIO_TARGET:g}× subdivide — {t1 / t0:.1f}× — {verdict}")


def random_spirals(n: int = 200, seed: int = 2026) -> tuple[list[Spiral], list[float]]:
    rng = np.random.default_rng(seed)
    spirals, tolerances = [], []
    for _ in range(n):
        direction = rng.uniform(0.0, 2.0 * math.pi)
        spiral = Spiral.from_parameters(
            start=(float(rng.uniform(-50, 50)), float(rng.uniform(-50, 50))),
            start_tangent=(math.cos(direction), math.sin(direction)),
            turn_angle_deg=float(rng.uniform(1.0, 89.0)),
            end_curvature=float(rng.choice([-1.0, 1.0]) * 10 ** rng.uniform(-2, 1)),
        )
        spirals.append(spiral)
        tolerances.append(float(spiral.chord * 10 ** rng.uniform(-5, -1)))
    return spirals, tolerances


def random_table() -> None:
    spirals, tolerances = random_spirals()
    counts = {}
    seconds = {}
    for strategy in ("subdivide", "fewest-arcs"):
        results = approximate_many(spirals, tolerances, strategy)  # type: ignore[arg-type]
        assert all(isinstance(r, ArcSpline) for r in results)
        counts[strategy] = np.array([len(r) for r in results])  # type: ignore[arg-type]
    seconds["subdivide"], seconds["fewest-arcs"] = paired_best(
        [
            lambda: approximate_many(spirals, tolerances),
            lambda: approximate_many(spirals, tolerances, "fewest-arcs"),
        ],
        3.0,
    )
    sub, few = counts["subdivide"], counts["fewest-arcs"]
    print(f"\n{len(spirals)} random spirals (θ 1–89°, relative tolerance 1e-5–1e-1), one batch")
    print(f"mean segments: subdivide {sub.mean():.2f}, fewest-arcs {few.mean():.2f}")
    print(
        f"fewest/subdivide: {few.sum() / sub.sum():.3f} overall, "
        f"fewer on {(few < sub).sum()}, equal on {(few == sub).sum()}, more on {(few > sub).sum()}"
    )
    ratio = seconds["fewest-arcs"] / seconds["subdivide"]
    print(
        f"time: subdivide {seconds['subdivide'] * 1e3:.1f} ms, fewest-arcs "
        f"{seconds['fewest-arcs'] * 1e3:.1f} ms, ratio {ratio:.0f}x"
    )
    pairs = [
        paired_best(
            [
                lambda s=s, t=t: approximate(s, t),  # type: ignore[misc]
                lambda s=s, t=t: approximate(s, t, "fewest-arcs"),  # type: ignore[misc]
            ],
            0.0,
        )
        for s, t in zip(spirals[:40], tolerances, strict=False)
    ]
    singles, fewest = [p[0] for p in pairs], [p[1] for p in pairs]
    print(
        f"one spiral per call (first 40): subdivide {np.mean(singles) * 1e3:.2f} ms, fewest-arcs "
        f"{np.mean(fewest) * 1e3:.2f} ms, ratio {np.sum(fewest) / np.sum(singles):.0f}x"
    )


def benchmark_2000() -> None:
    spirals, tolerances = random_spirals(2000)
    results = approximate_many(spirals, tolerances, "fewest-arcs")
    counts = np.array([len(r) for r in results])  # type: ignore[arg-type]
    before = BEFORE_2000_TOTAL / len(spirals)
    verdict = "no higher" if counts.sum() <= BEFORE_2000_TOTAL else "HIGHER"
    print(
        f"\n2000-spiral benchmark (this generator, seed 2026): fewest-arcs mean "
        f"{counts.mean():.4f} ({counts.sum()} segments); before issue 15 {before:.4f} "
        f"({BEFORE_2000_TOTAL}) — {verdict}"
    )


if __name__ == "__main__":
    table1()
    random_table()
    benchmark_2000()
