"""Paths of random cubics: segment counts against the juicy-gcode baseline, throughput, and
what certifying costs beside fitting.

Prints, for a seeded corpus of random cubic Bézier curves in a 100 mm box (control points
uniform in [0, 100]²) at tolerances 0.1, 0.01 and 0.001 mm:

1. output segments per cubic of ``approximate_path`` with ``subdivide`` and ``fewest-arcs``
   beside a BASELINE written here in plain numpy/Python, independently of the service: the
   method of juicy-gcode — each cubic cut at its inflections only (roots of ``B'×B''``), each
   piece fitted by Sabin's incentre biarc (join point = incentre of the triangle of the two
   end points and the tangent intersection), a biarc whose deviation exceeds the tolerance
   split at the parameter of its largest deviation. The deviation is measured exactly: each
   arc answers for the curve up to where it crosses the normal line at the join point, and
   its largest distance to the arc is at an end or a root of ``(B − C)·B'`` (a quintic,
   ``numpy.roots``). A piece whose biarc is undefined (parallel tangents, a turn of 180° or
   more, no crossing of the join normal) is split in the middle; recursion is capped and
   pieces left over at the cap are counted as failures;
2. ``subdivide``'s throughput in output segments per second, all cubics as one path of
   one-segment subpaths and each cubic as its own call, and its ratio to the baseline (timed
   on a subset, per segment);
3. time to certify against time to fit: ``measure.circle_deviations`` (the root isolation of
   the certificate) over every output arc, against the whole ``approximate_path`` call.

Timings are best times, rivals in turn (``bench/timing.py``). Run with
``.venv/bin/python bench/paths.py``; the tests do not run it.
"""

from __future__ import annotations

import itertools
import math
import os
import platform
import sys
import time
from dataclasses import dataclass, field
from pathlib import Path as FilePath

import numpy as np
import numpy.polynomial.polynomial as npoly

sys.path.insert(0, str(FilePath(__file__).resolve().parent))

from timing import paired_best

from arcspline.geometry import COLUMN, GeometryError, Limits, PathSpline, approximate_path
from arcspline.geometry.curves.segments import Cubic, Path, Subpath
from arcspline.geometry.curves.split import split
from arcspline.geometry.fit import STRATEGIES
from arcspline.geometry.measure import circle_deviations, line_deviations
from arcspline.geometry.segment_table import segment_row
from arcspline.geometry.spline import Point

SEED = 20260601
CORPUS_SIZE = 1000
BOX_MM = 100.0
TOLERANCES = (0.1, 0.01, 0.001)
LIMITS = Limits(max_segments=2_000_000)
#: Cubics of the corpus the baseline is timed on (its rate extrapolated per segment).
BASELINE_SUBSET = 60
#: Seconds each paired timing runs for (at least three rounds).
BUDGET_S = 2.0

FEWEST_TARGET = 0.75  # fewest-arcs ÷ baseline segments
THROUGHPUT_TARGET = 500_000.0  # subdivide output segments/s, one core

#: Baseline: deepest recursion before a piece is given up (kept as it is, counted a failure).
MAX_DEPTH = 48
#: Baseline: a root of numpy.roots is taken as real below this imaginary part. Extra
#: candidates cannot raise the maximum (each is a point of the curve), so generous is safe.
IMAG_TOL = 1e-5
#: Baseline: inflections closer than this (in t) to an end or to each other are merged.
CUT_SEPARATION = 1e-9

Points = np.ndarray  # (4, 2) control points


# --- The baseline: juicy-gcode's method, plainly ------------------------------------------


@dataclass
class BaselineCount:
    segments: int = 0
    biarcs_evaluated: int = 0
    undefined: int = 0  # middle splits: biarc undefined or no join crossing
    failures: int = 0  # pieces given up at MAX_DEPTH
    arcs: list[tuple[float, float, np.ndarray, np.ndarray, float]] = field(default_factory=list)


def power_basis(cp: Points) -> np.ndarray:
    """``B(t) = c0 + c1·t + c2·t² + c3·t³``: rows c0..c3."""
    p0, p1, p2, p3 = cp
    return np.array(
        [p0, 3.0 * (p1 - p0), 3.0 * (p2 - 2.0 * p1 + p0), p3 - 3.0 * p2 + 3.0 * p1 - p0]
    )


def local_basis(c: np.ndarray, ta: float, tb: float) -> np.ndarray:
    """The power basis of ``B(ta + (tb − ta)·s)`` in ``s``."""
    h = tb - ta
    b0 = c[0] + ta * (c[1] + ta * (c[2] + ta * c[3]))
    b1 = h * (c[1] + ta * (2.0 * c[2] + 3.0 * ta * c[3]))
    b2 = h * h * (c[2] + 3.0 * ta * c[3])
    b3 = h * h * h * c[3]
    return np.array([b0, b1, b2, b3])


def derivative(b: np.ndarray) -> np.ndarray:
    return np.array([b[1], 2.0 * b[2], 3.0 * b[3]])


def real_roots(ascending: np.ndarray, lo: float, hi: float) -> np.ndarray:
    coeffs = np.trim_zeros(ascending[::-1], "f")
    if len(coeffs) < 2:
        return np.empty(0)
    r = np.roots(coeffs)
    r = r.real[np.abs(r.imag) <= IMAG_TOL]
    return r[(r > lo) & (r < hi)]


def inflections(c: np.ndarray) -> list[float]:
    """Roots in (0, 1) of ``B'×B'' = 2 c1×c2 + 6 c1×c3 t + 6 c2×c3 t²``."""

    def cross(u: np.ndarray, v: np.ndarray) -> float:
        return float(u[0] * v[1] - u[1] * v[0])

    q = np.array([2.0 * cross(c[1], c[2]), 6.0 * cross(c[1], c[3]), 6.0 * cross(c[2], c[3])])
    cuts, last = [], 0.0
    for t in sorted(real_roots(q, 0.0, 1.0).tolist()):
        if t - last > CUT_SEPARATION and 1.0 - t > CUT_SEPARATION:
            cuts.append(t)
            last = t
    return cuts


def _direction(b: np.ndarray, s: float, side: float) -> np.ndarray:
    """Unit tangent at ``s`` (from the side ``side``: +1 after, −1 before), through a cusp."""
    d = b[1] + s * (2.0 * b[2] + 3.0 * s * b[3])
    scale = np.abs(b[1:]).sum()
    if np.hypot(*d) <= 1e-12 * scale:
        d = side * (2.0 * b[2] + 6.0 * s * b[3])
    return d / np.hypot(*d)


def arc_deviation(
    b: np.ndarray, start: np.ndarray, normal: np.ndarray, kappa: float, lo: float, hi: float
) -> tuple[float, float]:
    """Largest ``|‖B − C‖ − r|`` over ``[lo, hi]`` for the circle through ``start`` with unit
    inward normal ``normal`` and curvature ``kappa`` (``C = start + normal/kappa``), and where.

    Extrema at the ends and at roots of ``(B − C)·B'``, times κ: ``κ(B − S)·B' − N·B'`` (a
    quintic, no division by κ); the distance as ``|κ‖P‖² − 2P·N| / (‖κP − N‖ + 1)``, ``P =
    B − S`` (no cancellation for large radii)."""
    p = b.copy()
    p[0] = p[0] - start
    d = derivative(b)
    h = kappa * (np.convolve(p[:, 0], d[:, 0]) + np.convolve(p[:, 1], d[:, 1]))
    h[:3] -= normal[0] * d[:, 0] + normal[1] * d[:, 1]
    s = np.concatenate(([lo, hi], real_roots(h, lo, hi)))
    x, y = npoly.polyval(s, p[:, 0]), npoly.polyval(s, p[:, 1])
    e = np.abs(kappa * (x * x + y * y) - 2.0 * (x * normal[0] + y * normal[1]))
    e /= np.hypot(kappa * x - normal[0], kappa * y - normal[1]) + 1.0
    k = int(np.argmax(e))
    return float(e[k]), float(s[k])


def incentre_biarc(
    b: np.ndarray,
) -> tuple[float, float, list[tuple[float, float, np.ndarray, np.ndarray, float]]] | None:
    """Sabin's incentre biarc of the piece ``b`` (local ``s`` over [0, 1]): its deviation,
    where (``s``) and its two arcs ``(s0, s1, start, normal, κ)``; ``None`` if undefined."""
    a, e = b[0], b.sum(axis=0)
    chord = e - a
    length = float(np.hypot(*chord))
    if length == 0.0:
        return None
    ec = chord / length
    t0, t1 = _direction(b, 0.0, 1.0), _direction(b, 1.0, -1.0)
    d, dd = b[1] + b[2] + 0.75 * b[3], 2.0 * b[2] + 3.0 * b[3]  # B', B'' at s = ½
    turn = d[0] * dd[1] - d[1] * dd[0]
    sigma = 1.0 if turn >= 0.0 else -1.0
    alpha = sigma * math.atan2(t0[0] * ec[1] - t0[1] * ec[0], t0 @ ec)
    beta = sigma * math.atan2(ec[0] * t1[1] - ec[1] * t1[0], ec @ t1)
    if not (alpha > 0.0 and beta > 0.0 and alpha + beta < math.pi):
        return None  # straight, turning the wrong way, or by 180° or more
    # Tangent intersection V = A + s·T0 with s·T0 + u·T1 = chord.
    v = a + t0 * ((chord[0] * t1[1] - chord[1] * t1[0]) / (t0[0] * t1[1] - t0[1] * t1[0]))
    side_a, side_v, side_e = np.hypot(*(v - e)), length, np.hypot(*(v - a))
    g = (side_a * a + side_v * v + side_e * e) / (side_a + side_v + side_e)
    n0 = sigma * np.array([-t0[1], t0[0]])
    ng = sigma * np.array([-ec[1], ec[0]])  # the biarc's tangent at G is the chord's
    ga, eg = g - a, e - g
    kappa0 = 2.0 * float(ga @ n0) / float(ga @ ga)
    kappa1 = 2.0 * float(eg @ ng) / float(eg @ eg)
    # The join: where the curve crosses the normal line at G, (B(s) − G)·ec = 0.
    q = b @ ec
    q[0] -= g @ ec
    crossings = real_roots(q, 0.0, 1.0)
    if len(crossings) == 0:
        return None
    pts = np.stack([npoly.polyval(crossings, b[:, 0]), npoly.polyval(crossings, b[:, 1])], 1)
    sj = float(crossings[np.argmin(np.hypot(*(pts - g).T))])
    dev0, at0 = arc_deviation(b, a, n0, kappa0, 0.0, sj)
    dev1, at1 = arc_deviation(b, g, ng, kappa1, sj, 1.0)
    arcs = [(0.0, sj, a, n0, kappa0), (sj, 1.0, g, ng, kappa1)]
    return (dev0, at0, arcs) if dev0 >= dev1 else (dev1, at1, arcs)


def baseline(cp: Points, tolerance: float, keep_arcs: bool = False) -> BaselineCount:
    """juicy-gcode's method on one cubic: cut at inflections, subdivide each piece."""
    c = power_basis(np.asarray(cp, dtype=np.float64))
    ts = [0.0, *inflections(c), 1.0]
    out = BaselineCount()
    for ta, tb in itertools.pairwise(ts):
        stack = [(ta, tb, 0)]
        while stack:
            lo, hi, depth = stack.pop()
            b = local_basis(c, lo, hi)
            fit = incentre_biarc(b)
            out.biarcs_evaluated += 1
            if fit is None:
                out.undefined += 1
                split, dev = 0.5, math.inf
            else:
                dev, split, arcs = fit
            if dev <= tolerance or depth >= MAX_DEPTH:
                out.failures += dev > tolerance
                out.segments += 2
                if keep_arcs and fit is not None:
                    out.arcs += [
                        (lo + (hi - lo) * s0, lo + (hi - lo) * s1, st, n, k)
                        for s0, s1, st, n, k in arcs
                    ]
                continue
            mid = lo + (hi - lo) * split
            stack += [(mid, hi, depth + 1), (lo, mid, depth + 1)]
    return out


def sampled_check(cp: Points, tolerance: float) -> float:
    """The baseline's worst sampled deviation ÷ tolerance over its own arcs (one-sided)."""
    result = baseline(cp, tolerance, keep_arcs=True)
    c = power_basis(np.asarray(cp, dtype=np.float64))
    worst = 0.0
    for t0, t1, start, normal, kappa in result.arcs:
        t = np.linspace(t0, t1, 64)
        x, y = npoly.polyval(t, c[:, 0]) - start[0], npoly.polyval(t, c[:, 1]) - start[1]
        e = np.abs(kappa * (x * x + y * y) - 2.0 * (x * normal[0] + y * normal[1]))
        e /= np.hypot(kappa * x - normal[0], kappa * y - normal[1]) + 1.0
        worst = max(worst, float(e.max()))
    return worst / tolerance


# --- The service ---------------------------------------------------------------------------


def cubic_of(cp: Points) -> Cubic:
    return Cubic(*(Point(float(x), float(y)) for x, y in cp))


def one_path(corpus: np.ndarray) -> Path:
    return Path(tuple(Subpath((cubic_of(cp),)) for cp in corpus))


def own_paths(corpus: np.ndarray) -> list[Path]:
    return [Path((Subpath((cubic_of(cp),)),)) for cp in corpus]


def per_cubic(
    paths: list[Path], tolerance: float, strategy: str
) -> tuple[np.ndarray, np.ndarray, list[int]]:
    """Segments and pieces per cubic (−1 where the call failed), and the cubics that failed."""
    counts, pieces, failed = [], [], []
    for i, path in enumerate(paths):
        try:
            result = approximate_path(path, tolerance, strategy, LIMITS)
        except GeometryError:
            counts.append(-1)
            pieces.append(-1)
            failed.append(i)
            continue
        counts.append(result.segment_count)
        pieces.append(len(result.subpaths[0].curve.frames))
    return np.array(counts), np.array(pieces), failed


@dataclass
class CertifyQueries:
    """Every output segment of a result as a query of ``measure``: arcs and lines apart."""

    frames: np.ndarray
    arc: tuple[np.ndarray, ...]
    line: tuple[np.ndarray, ...]
    reported: np.ndarray  # the kernel's max_deviation, arcs then lines


def certify_queries(result: PathSpline) -> CertifyQueries:
    frames, piece, lo, hi, rows = [], [], [], [], []
    offset = 0
    for sub in result.subpaths:
        table = sub.spline.table
        n = len(sub.curve.frames)
        g0, g1 = table[:, COLUMN["u_start"]], table[:, COLUMN["u_end"]]
        k = np.clip(np.floor(g0), 0, n - 1).astype(np.int64)
        assert np.all(g1 <= k + 1.0), "an output segment spans two pieces"
        frames.append(sub.curve.frames)
        piece.append(k + offset)
        lo.append(g0 - k)
        hi.append(np.minimum(g1 - k, 1.0))
        rows.append(table)
        offset += n
    table = np.concatenate(rows)
    k, a, b = np.concatenate(piece), np.concatenate(lo), np.concatenate(hi)
    is_arc = table[:, COLUMN["is_arc"]] != 0.0
    col = COLUMN
    centre = np.ascontiguousarray(table[:, [col["center_x"], col["center_y"]]])
    start = np.ascontiguousarray(table[:, [col["start_x"], col["start_y"]]])
    end = np.ascontiguousarray(table[:, [col["end_x"], col["end_y"]]])
    radius = np.ascontiguousarray(table[:, col["radius"]])
    arcs = (k[is_arc], a[is_arc], b[is_arc], centre[is_arc], radius[is_arc], radius[is_arc])
    lines = (k[~is_arc], a[~is_arc], b[~is_arc], start[~is_arc], end[~is_arc])
    dev = table[:, col["max_deviation"]]
    return CertifyQueries(
        np.ascontiguousarray(np.concatenate(frames)),
        tuple(np.ascontiguousarray(x) for x in arcs),
        tuple(np.ascontiguousarray(x) for x in lines),
        np.concatenate([dev[is_arc], dev[~is_arc]]),
    )


def certify(q: CertifyQueries) -> np.ndarray:
    return np.concatenate([circle_deviations(q.frames, *q.arc), line_deviations(q.frames, *q.line)])


# --- The report ----------------------------------------------------------------------------


def corpus_of(n: int, seed: int) -> np.ndarray:
    return np.random.default_rng(seed).uniform(0.0, BOX_MM, (n, 4, 2))


def fmt_cp(cp: Points) -> str:
    return "(" + ", ".join(f"({x:.6f}, {y:.6f})" for x, y in cp) + ")"


def verdict(met: bool) -> str:
    return "met" if met else "NOT met"


@dataclass
class Counts:
    """Per cubic at one tolerance: segments (−1: refused) and pieces of each method."""

    base: np.ndarray
    base_pieces: np.ndarray
    base_runs: list[BaselineCount]
    sub: np.ndarray
    few: np.ndarray
    pieces: np.ndarray
    refused: dict[str, list[int]]

    def ratio(self, ours: np.ndarray) -> float:
        ok = (self.sub >= 0) & (self.few >= 0)
        return float(ours[ok].sum() / self.base[ok].sum())


def counts_section(corpus: np.ndarray, paths: list[Path]) -> dict[float, Counts]:
    n = len(corpus)
    print(
        f"1. Output segments per cubic ({n} cubics; baseline = juicy-gcode's method in numpy, "
        f"recursion capped at depth {MAX_DEPTH})"
    )
    print(
        f"{'tol mm':>7} | {'baseline':>8} {'fail':>4} {'mid':>4} {'s':>5} | "
        f"{'subdiv':>7} {'fail':>4} | {'fewest':>7} {'fail':>4} | "
        f"{'fewest÷base':>11} {'subdiv÷base':>11} | {'fewest <':>8} {'=':>4} {'>':>4}"
    )
    out: dict[float, Counts] = {}
    base_pieces = np.array([len(inflections(power_basis(cp))) + 1 for cp in corpus])
    for tol in TOLERANCES:
        began = time.perf_counter()
        runs = [baseline(cp, tol) for cp in corpus]
        base_s = time.perf_counter() - began
        base = np.array([r.segments for r in runs])
        sub, pieces, sub_refused = per_cubic(paths, tol, "subdivide")
        few, _, few_refused = per_cubic(paths, tol, "fewest-arcs")
        c = out[tol] = Counts(
            base, base_pieces, runs, sub, few, pieces,
            {"subdivide": sub_refused, "fewest-arcs": few_refused},
        )  # fmt: skip
        ok = (sub >= 0) & (few >= 0)
        print(
            f"{tol:>7g} | {base.mean():>8.3f} {sum(r.failures for r in runs):>4d} "
            f"{sum(r.undefined for r in runs):>4d} {base_s:>5.1f} | "
            f"{sub[sub >= 0].mean():>7.3f} {len(sub_refused):>4d} | "
            f"{few[few >= 0].mean():>7.3f} {len(few_refused):>4d} | "
            f"{c.ratio(few):>11.3f} {c.ratio(sub):>11.3f} | "
            f"{int(((few < base) & ok).sum()):>8d} {int(((few == base) & ok).sum()):>4d} "
            f"{int(((few > base) & ok).sum()):>4d}"
        )
    print(
        "   fail: cubics the service refused (GeometryError), or baseline pieces still over the "
        "tolerance at the depth cap; mid: baseline middle splits where its biarc was undefined "
        "(a piece turning 180° or more, or parallel end tangents); s: baseline seconds (one run); "
        "ratios: total segments over the cubics both strategies handled; fewest <, =, >: "
        "cubics with fewer, as many, more segments than the baseline"
    )
    print(
        "   pieces per cubic before fitting: baseline (inflections only) "
        f"{base_pieces.mean():.3f}, subdivide (inflections, curvature extrema, quarter turns) "
        f"{out[TOLERANCES[0]].pieces.mean():.3f}; fewest-arcs cuts at inflections, cusps and "
        "quarter turns only (docs/fewest-arcs.md §4)"
    )
    rng = np.random.default_rng(SEED + 1)
    sample = rng.choice(n, 20, replace=False)
    worst = max(sampled_check(corpus[i], tol) for i in sample for tol in TOLERANCES)
    print(
        f"   baseline self-check: 20 cubics × {len(TOLERANCES)} tolerances, 64 samples per arc: "
        f"worst sampled deviation {worst:.4f} × tolerance"
    )
    targets = ", ".join(
        f"{tol:g}: {out[tol].ratio(out[tol].few):.3f} "
        f"{verdict(out[tol].ratio(out[tol].few) <= FEWEST_TARGET)}"
        for tol in TOLERANCES
    )
    print(f"   target fewest-arcs ÷ baseline ≤ {FEWEST_TARGET:g} — {targets}")
    return out


def oddities(corpus: np.ndarray, counts: dict[float, Counts]) -> None:
    """Cubics the service refuses, baseline give-ups, and the cubics where ours uses the most
    segments beside the baseline (ratio ≥ 1.5 and at least 4 more)."""
    print("\nOddities (per cubic; control points P0..P3 in mm)")
    for tol in TOLERANCES:
        c = counts[tol]
        for name, refused in c.refused.items():
            for i in refused:
                print(f"  tol {tol:g}: cubic {i} REFUSED by {name}: {fmt_cp(corpus[i])}")
        for i, run in enumerate(c.base_runs):
            if run.failures:
                print(
                    f"  tol {tol:g}: cubic {i}: baseline left {run.failures} piece(s) over the "
                    f"tolerance at the depth cap: {fmt_cp(corpus[i])}"
                )
        for name, ours in (("subdivide", c.sub), ("fewest-arcs", c.few)):
            bad = np.flatnonzero((ours >= 1.5 * c.base) & (ours - c.base >= 4))
            worst = bad[np.argsort(ours[bad] / c.base[bad])[::-1]]
            for i in worst[:3]:
                print(
                    f"  tol {tol:g}: cubic {i}: {name} {ours[i]} segments ({c.pieces[i]} pieces) "
                    f"vs baseline {c.base[i]} ({c.base_pieces[i]} pieces): {fmt_cp(corpus[i])}"
                )
            if len(bad) > 3:
                print(f"  tol {tol:g}: ... {len(bad)} cubics in all where {name} needs ≥ 1.5×")
        for name, ours in (("subdivide", c.sub), ("fewest-arcs", c.few)):
            i = int(np.argmax(np.where(ours >= 0, ours / c.base, 0.0)))
            print(
                f"  tol {tol:g}: largest {name} ÷ baseline on one cubic: cubic {i}, "
                f"{ours[i]} vs {c.base[i]} segments ({c.pieces[i]} vs {c.base_pieces[i]} pieces)"
            )


def speed_section(corpus: np.ndarray, paths: list[Path]) -> None:
    whole = one_path(corpus)
    subset = corpus[:BASELINE_SUBSET]
    table = np.array([segment_row(cubic_of(cp)) for cp in corpus])
    kernel_fit = STRATEGIES["subdivide"]

    def kernel(t: float) -> None:
        frames, _ = split(table, LIMITS.max_segments)
        tol = np.full(len(frames), t)
        kernel_fit(frames, tol, LIMITS.max_segments, LIMITS.min_relative_tolerance, True)

    print(
        f"\n2. subdivide throughput, one core (best of paired runs, {BUDGET_S:g} s a tolerance, "
        "≥ 3 rounds each)"
    )
    print(
        f"{'tol mm':>7} | {'segments':>8} {'pieces':>6} | {'path ms':>8} {'seg/s':>9} | "
        f"{'per-call ms':>11} {'seg/s':>9} | {'kernel ms':>9} {'seg/s':>9} | "
        f"{'base seg/s':>10} {'path÷base':>9}"
    )
    lowest = math.inf
    certify_rows = []
    for tol in TOLERANCES:
        result = approximate_path(whole, tol, "subdivide", LIMITS)
        segments = result.segment_count
        pieces = sum(len(s.curve.frames) for s in result.subpaths)
        queries = certify_queries(result)
        measured = certify(queries)
        assert np.all(measured <= tol), "a measured deviation exceeds the tolerance"
        i = int(np.argmax(np.abs(measured - queries.reported)))

        def whole_call(t: float = tol) -> None:
            approximate_path(whole, t, "subdivide", LIMITS)

        def each_call(t: float = tol) -> None:
            for p in paths:
                approximate_path(p, t, "subdivide", LIMITS)

        t_path, t_each, t_kernel, t_cert = paired_best(
            [whole_call, each_call, lambda t=tol: kernel(t), lambda q=queries: certify(q)],
            BUDGET_S,
        )
        base_segments = sum(baseline(cp, tol).segments for cp in subset)
        (t_base,) = paired_best([lambda t=tol: [baseline(cp, t) for cp in subset]], 0.0)
        rate, base_rate = segments / t_path, base_segments / t_base
        lowest = min(lowest, rate)
        print(
            f"{tol:>7g} | {segments:>8d} {pieces:>6d} | {t_path * 1e3:>8.2f} {rate:>9,.0f} | "
            f"{t_each * 1e3:>11.2f} {segments / t_each:>9,.0f} | {t_kernel * 1e3:>9.2f} "
            f"{segments / t_kernel:>9,.0f} | {base_rate:>10,.0f} {rate / base_rate:>8.0f}×"
        )
        certify_rows.append(
            (tol, segments, pieces, t_path, t_kernel, t_cert,
             abs(measured[i] - queries.reported[i]), measured[i])
        )  # fmt: skip
    print(
        "   path: all cubics in one approximate_path call (one-segment subpaths); per-call: "
        "one call per cubic; kernel: split + the compiled fit alone on the same segment table "
        "(what the Python around them in approximate_path costs is path − kernel)"
    )
    print(
        f"   base seg/s: the baseline on the first {BASELINE_SUBSET} cubics, best of 3, "
        "extrapolated per output segment (plain numpy/Python; numpy.roots dominates)"
    )
    print(
        f"   target ≥ {THROUGHPUT_TARGET:,.0f} seg/s (one path call) — lowest {lowest:,.0f} — "
        f"{verdict(lowest >= THROUGHPUT_TARGET)}"
    )

    print("\n3. Time to certify vs time to fit (same paired runs)")
    print(
        f"{'tol mm':>7} | {'certify ms':>10} {'÷path':>6} {'÷kernel':>7} | "
        f"{'certified arcs':>14} {'scaled ÷kernel':>14} | {'measure−kernel':>14}"
    )
    for tol, segments, pieces, t_path, t_kernel, t_cert, diff, at in certify_rows:
        # Every biarc the recursion evaluates is certified, kept or split: in a binary
        # recursion per piece, segments − pieces biarcs, two arcs each.
        candidates = 2 * (segments - pieces)
        share = t_cert * candidates / segments / t_kernel
        print(
            f"{tol:>7g} | {t_cert * 1e3:>10.2f} {t_cert / t_path:>6.1%} "
            f"{t_cert / t_kernel:>7.1%} | "
            f"{candidates:>14d} {share:>14.1%} | {diff:>9.1e} mm (of a {at:.2e} mm deviation)"
        )
    print(
        "   certify: measure.circle_deviations (line_deviations for the rows that are lines) "
        "over every output segment of the one-path result, in one call: the certificate's root "
        "isolation, without its polar-graph check; ÷path, ÷kernel: its time as a share of the "
        "whole call and of split + fit; certified arcs: every arc the recursion certifies, "
        "kept or split (2·(segments − pieces)); scaled ÷kernel: the certify time scaled to "
        "them; measure−kernel: largest difference from the kernel's reported deviation"
    )
    print(
        "   the scaled figure is an upper bound: measure costs more per arc than the certificate "
        "inside the fit (that divides out the root of (Q − C)·Q' at an arc's touching ends, "
        "leaving a quartic or cubic; measure keeps the quintic, maps each circle into its "
        "piece's frame and crosses the numpy boundary); the true share needs a profile of the "
        "kernel itself"
    )


def main() -> None:
    began = time.perf_counter()
    print(
        "arcspline paths benchmark: random cubics against juicy-gcode's method (one process, "
        "one core; best times, rivals in turn)"
    )
    print(
        f"seed {SEED}; {CORPUS_SIZE} cubics, control points uniform in [0, {BOX_MM:g}]² mm; "
        f"Python {platform.python_version()}, numpy {np.__version__}, {platform.machine()}, "
        f"{os.cpu_count()} CPUs"
    )
    print()
    corpus = corpus_of(CORPUS_SIZE, SEED)
    paths = own_paths(corpus)
    counts = counts_section(corpus, paths)
    oddities(corpus, counts)
    speed_section(corpus, paths)
    print(f"\n(total {time.perf_counter() - began:.0f} s)")


if __name__ == "__main__":
    main()
