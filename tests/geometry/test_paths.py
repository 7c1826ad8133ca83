"""``approximate_path`` end to end, checked independently of the core.

The output is read as the service answers it (``arcspline.worker.jobs.path_segments``) and
judged by our own means: the paper's Table 1 through the general path; certified deviations
(python-flint, ``tests/support/path_oracle.py``) of every output segment of seeded random
Béziers; the dense two-way oracle (``check_path``) on representative paths; structural
invariants recomputed here (an exact chain, exact ``u`` tiling, lines and circular arcs kept
as they are, G1 where the input is smooth and its corners where it has them); hypothesis
properties over random paths with corners, cusps, loops and closed subpaths; exact scale
invariance; degenerate input handled exactly or refused with a GeometryError that says where.
"""

from __future__ import annotations

import itertools
import json
import math
from collections.abc import Iterable, Mapping, Sequence
from pathlib import Path as FilePath
from typing import Any

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

from arcspline.geometry import GeometryError, PathSpline, Spiral, approximate_path
from arcspline.geometry.curves.segments import (
    CircularArc,
    Cubic,
    EllipticalArc,
    Line,
    Path,
    Quadratic,
    Segment,
    Subpath,
)
from arcspline.geometry.spline import Point
from arcspline.paths.svg_data import parse_path_data
from arcspline.worker.jobs import path_segments
from tests.support import path_oracle as po

EPS = float(np.finfo(np.float64).eps)
STRATEGIES = ("subdivide", "fewest-arcs")
TABLE = json.loads((FilePath(__file__).parent / "data" / "table1.json").read_text())

PROPERTY = settings(
    max_examples=40,
    deadline=None,
    derandomize=True,
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.filter_too_much],
)

Outputs = list[dict[str, Any]]


def pt(x: float, y: float) -> Point:
    return Point(float(x), float(y))


def run(path: Path, tolerance: float, strategy: str) -> tuple[PathSpline, list[Outputs]]:
    result = approximate_path(path, tolerance, strategy)  # type: ignore[arg-type]
    return result, [path_segments(sub) for sub in result.subpaths]


def one(*segments: Segment, closed: bool = False) -> Path:
    return Path((Subpath(tuple(segments), closed),))


def bezier_points(segment: Segment) -> list[Point] | None:
    """A Bézier's (or a line's) control points; ``None`` for an arc."""
    if isinstance(segment, Line):
        return [segment.start, segment.end]
    if isinstance(segment, Quadratic):
        return [segment.start, segment.control, segment.end]
    if isinstance(segment, Cubic):
        return [segment.start, segment.control1, segment.control2, segment.end]
    return None


def spiral_path(end_curvature: float = TABLE["spiral"]["end_curvature"]) -> tuple[Path, Any]:
    """The Table 1 spiral as a plain cubic (its four control points) in a general path."""
    spiral = Spiral.from_parameters(**{**TABLE["spiral"], "end_curvature": end_curvature})
    cp = [pt(*p) for p in spiral.control_points]
    return one(Cubic(*cp)), cp


# -- certified deviations --------------------------------------------------------------


def certified(cp: Sequence[Point], out: Mapping[str, Any]) -> float:
    """The exact (flint) largest distance from the Bézier ``cp`` over the output's ``u``
    range to its circle or its line."""
    u0, u1 = float(out["u_start"]), float(out["u_end"])
    if out["type"] == "arc":
        return po.certified_arc_deviation(cp, u0, u1, out["center"], out["radius"])
    return po.certified_line_deviation(cp, u0, u1, out["start"], out["end"])


def rounding(out: Mapping[str, Any], scale: float) -> float:
    """What rounding the emitted numbers can move a distance by: 16 ulps of the coordinate
    scale plus, for an arc, of ``|C| + r`` (a huge radius rounds to ulps of its size)."""
    size = scale
    if out["type"] == "arc":
        size += max(abs(c) for c in out["center"]) + out["radius"]
    return 16 * EPS * size


def check_certified(path: Path, result: PathSpline, outs: list[Outputs], tolerance: float) -> int:
    """Every output of a Bézier source: its certified deviation is within the tolerance (no
    slack) and is the reported one (1e-12 relative plus rounding); the subpath's reported
    maximum is the certified maximum. Returns how many segments were certified."""
    count = 0
    for sub, spline, mine in zip(path.subpaths, result.subpaths, outs, strict=True):
        sources = [bezier_points(s) for s in sub.segments]
        scale = max(
            (abs(v) for s in sub.segments for p in (bezier_points(s) or []) for v in p),
            default=0.0,
        )
        worst, worst_slack = 0.0, 0.0
        for i, out in enumerate(mine):
            cp = sources[out["source_segment"]]
            if cp is None or len(cp) < 3:
                continue
            exact = certified(cp, out)
            slack = rounding(out, scale)
            where = f"output {i} ({out['type']}, u {out['u_start']!r}..{out['u_end']!r})"
            assert exact <= tolerance, f"{where}: certified {exact!r} > tolerance {tolerance!r}"
            assert abs(exact - out["max_deviation"]) <= 1e-12 * exact + slack, (
                f"{where}: reported {out['max_deviation']!r}, certified {exact!r}"
            )
            if exact > worst:
                worst, worst_slack = exact, slack
            count += 1
        if all(cp is not None and len(cp) >= 3 for cp in sources):
            reported = spline.spline.stats.max_deviation
            assert abs(reported - worst) <= 1e-12 * worst + worst_slack, (reported, worst)
    return count


# -- structure -------------------------------------------------------------------------


def out_tangent(out: Mapping[str, Any], *, end: bool) -> np.ndarray:
    """Unit direction of travel at an output segment's start or end."""
    p = np.array(out["end" if end else "start"], dtype=float)
    if out["type"] == "line":
        d = np.array(out["end"], dtype=float) - np.array(out["start"], dtype=float)
    else:
        v = p - np.array(out["center"], dtype=float)
        d = np.array([-v[1], v[0]]) * (1.0 if out["direction"] == "ccw" else -1.0)
    return d / math.hypot(*d)


def src_tangent(segment: Segment, t: float) -> np.ndarray:
    """Unit direction of travel of a source segment at ``t`` (at a Bézier's end whose leg
    vanishes, the next control point that differs: the limit of ``B'/‖B'‖``)."""
    cp = bezier_points(segment)
    if cp is not None:
        c = np.array(cp, dtype=float)
        n = len(c) - 1
        if t in (0.0, 1.0):
            for k in range(1, n + 1):
                v = c[k] - c[0] if t == 0.0 else c[n] - c[n - k]
                if np.any(v != 0):
                    return v / math.hypot(*v)
            raise AssertionError("a single point has no tangent")
        d = n * np.diff(c, axis=0)
        v = sum(math.comb(n - 1, i) * t**i * (1 - t) ** (n - 1 - i) * d[i] for i in range(n))
        return v / math.hypot(*v)
    assert isinstance(segment, CircularArc | EllipticalArc)
    if isinstance(segment, CircularArc):
        rx = ry = segment.radius
        rot = 0.0
    else:
        rx, ry, rot = segment.rx, segment.ry, segment.rotation_rad
    phi = segment.start_angle_rad + t * segment.sweep_rad
    x, y = -rx * math.sin(phi), ry * math.cos(phi)
    c, s = math.cos(rot), math.sin(rot)
    v = np.array([c * x - s * y, s * x + c * y]) * math.copysign(1.0, segment.sweep_rad)
    return v / math.hypot(*v)


def smooth_inside(segment: Segment, t: float) -> bool:
    """Whether a source segment has a tangent at interior ``t`` (not a cusp or a turning
    point of a straight Bézier: speed below 1e-9 of its control polygon's)."""
    cp = bezier_points(segment)
    if cp is None:
        return True
    c = np.array(cp, dtype=float)
    n = len(c) - 1
    d = n * np.diff(c, axis=0)
    v = sum(math.comb(n - 1, i) * t**i * (1 - t) ** (n - 1 - i) * d[i] for i in range(n))
    return bool(math.hypot(*v) > 1e-9 * float(np.max(np.abs(d))))


def size_of(out: Mapping[str, Any]) -> float:
    """The length over which an output's direction is rounded: radius, or line length."""
    return float(out["radius"] if out["type"] == "arc" else out["length"])


def angle(a: np.ndarray, b: np.ndarray) -> float:
    return math.atan2(abs(a[0] * b[1] - a[1] * b[0]), float(a @ b))


def is_point(segment: Segment) -> bool:
    cp = bezier_points(segment)
    return cp is not None and all(p == cp[0] for p in cp)


def structure_violations(
    sub: Subpath, outs: Outputs, tolerance: float, *, tangents: bool = True
) -> list[str]:
    """What a subpath's output must be, recomputed here.

    Numbers finite; reported deviations in ``[0, tolerance]``; the chain starts at the
    subpath's start, each segment where the previous one ends and the last at the subpath's
    end, all bit for bit; each source segment's outputs are consecutive and tile its
    ``[0, 1]`` exactly; a source with no output is
    a single point; a line is one line, a circular arc one arc, both exactly as given. With
    ``tangents``: each source segment's outputs leave along its start tangent and arrive along
    its end tangent (so the output has the input's corners and is G1 across its smooth joints
    and seam), and are G1 among themselves except at a cusp of the source.
    """
    bad: list[str] = []
    segs = sub.segments
    numbers = [
        v
        for o in outs
        for v in (*o["start"], *o["end"], o["max_deviation"], o["u_start"], o["u_end"])
    ]
    numbers += [v for o in outs if o["type"] == "arc" for v in (*o["center"], o["radius"])]
    if not all(math.isfinite(v) for v in numbers):
        return ["a number is not finite"]
    empty = [i for i, o in enumerate(outs) if o["type"] == "line" and o["start"] == o["end"]]
    empty += [i for i, o in enumerate(outs) if o["type"] == "arc" and not o["radius"] > 0]
    if empty:
        return [f"outputs {empty} have no length or no radius (no direction)"]
    bad += [
        f"output {i}: reported deviation {o['max_deviation']!r} outside [0, {tolerance!r}]"
        for i, o in enumerate(outs)
        if not 0.0 <= o["max_deviation"] <= tolerance
    ]
    if tuple(outs[0]["start"]) != tuple(segs[0].start):
        bad.append(f"the chain starts at {outs[0]['start']}, not at {segs[0].start}")
    if tuple(outs[-1]["end"]) != tuple(segs[-1].end):
        bad.append(f"the chain ends at {outs[-1]['end']}, not at {segs[-1].end}")
    bad += [
        f"joint {i}: {outs[i]['end']} != {outs[i + 1]['start']}"
        for i in range(len(outs) - 1)
        if outs[i]["end"] != outs[i + 1]["start"]
    ]
    runs: dict[int, list[int]] = {}
    for i, o in enumerate(outs):
        runs.setdefault(o["source_segment"], []).append(i)
    order = [o["source_segment"] for o in outs]
    if order != sorted(order):
        bad.append(f"outputs answer for source segments out of order: {order}")
    for j, seg in enumerate(segs):
        mine = runs.get(j, [])
        if not mine:
            if not (is_point(seg) or (seg.start == seg.end and isinstance(seg, Line))):
                bad.append(f"source segment {j} has no output")
            continue
        us = [outs[i]["u_start"] for i in mine]
        ue = [outs[i]["u_end"] for i in mine]
        tiles = (
            us[0] == 0.0
            and ue[-1] == 1.0
            and ue[:-1] == us[1:]
            and all(a < b for a, b in zip(us, ue, strict=True))
        )
        if not tiles:
            bad.append(f"source segment {j}: u ranges {list(zip(us, ue, strict=True))}")
        first, last = outs[mine[0]], outs[mine[-1]]
        if isinstance(seg, Line) and (
            len(mine) != 1
            or first["type"] != "line"
            or (tuple(first["start"]), tuple(first["end"])) != (seg.start, seg.end)
        ):
            bad.append(f"line {j} is not one line from its start to its end")
        if isinstance(seg, CircularArc) and (
            len(mine) != 1
            or first["type"] != "arc"
            or tuple(first["center"]) != seg.center
            or first["radius"] != seg.radius
            or first["sweep_rad"] != seg.sweep_rad
            or (tuple(first["start"]), tuple(first["end"])) != (seg.start, seg.end)
        ):
            bad.append(f"circular arc {j} is not one arc with its own centre, radius and sweep")
        if not tangents:
            continue
        for o, t, at_end in ((first, 0.0, False), (last, 1.0, True)):
            off = angle(out_tangent(o, end=at_end), src_tangent(seg, t))
            at = max(abs(v) for v in o["end" if at_end else "start"])
            allowed = 1e-9 + 64 * EPS * at / size_of(o)
            if not off <= allowed:
                bad.append(
                    f"source segment {j}: output {'end' if at_end else 'start'} tangent off "
                    f"the source's by {off:.3g} rad (allowed {allowed:.3g})"
                )
        for a, b in itertools.pairwise(mine):
            if not smooth_inside(seg, outs[a]["u_end"]):
                continue
            off = angle(out_tangent(outs[a], end=True), out_tangent(outs[b], end=False))
            # A direction rounds by up to 64 ulps of the coordinates over the segment's size
            # (an arc's radius, a line's length), as the oracle allows.
            at = max(abs(v) for v in outs[a]["end"])
            allowed = 1e-9 + sum(64 * EPS * at / size_of(outs[i]) for i in (a, b))
            if not off <= allowed:
                bad.append(
                    f"outputs {a}/{b} inside smooth source segment {j}: corner {off:.3g} "
                    f"(allowed {allowed:.3g})"
                )
    return bad


def check_oracle(path: Path, outs: list[Outputs], tolerance: float, samples: int) -> po.Verdict:
    verdict = po.check_path(path, outs, tolerance, samples=samples)
    assert verdict.ok, verdict.describe()
    return verdict


def check_structure(path: Path, outs: list[Outputs], tolerance: float, **kw: Any) -> None:
    assert len(outs) == len(path.subpaths)
    for k, (sub, mine) in enumerate(zip(path.subpaths, outs, strict=True)):
        bad = structure_violations(sub, mine, tolerance, **kw)
        assert not bad, f"subpath {k}:\n" + "\n".join(bad)


# -- the paper's Table 1 ---------------------------------------------------------------


@pytest.mark.parametrize("row", TABLE["rows"], ids=lambda row: f"tol={row['tolerance']:g}")
def test_table1_through_the_general_path(row: Mapping[str, float]) -> None:
    path, _ = spiral_path()
    result, outs = run(path, row["tolerance"], "subdivide")
    stats = result.subpaths[0].spline.stats
    assert stats.arc_count == row["arcs"]
    assert stats.line_count == 0
    assert stats.max_deviation == pytest.approx(row["max_deviation"], rel=TABLE["deviation_rtol"])
    assert result.stats.arc_count == row["arcs"]
    assert check_certified(path, result, outs, row["tolerance"]) == row["arcs"]
    check_structure(path, outs, row["tolerance"])


def test_table1_mirrored_through_the_general_path() -> None:
    path, _ = spiral_path(-TABLE["spiral"]["end_curvature"])
    for row in TABLE["rows"]:
        result, outs = run(path, row["tolerance"], "subdivide")
        assert result.stats.arc_count == row["arcs"]
        assert all(o["direction"] == "cw" for o in outs[0])
        assert result.stats.max_deviation == pytest.approx(
            row["max_deviation"], rel=TABLE["deviation_rtol"]
        )


def test_table1_spiral_with_fewest_arcs() -> None:
    path, _ = spiral_path()
    for row in TABLE["rows"]:
        result, outs = run(path, row["tolerance"], "fewest-arcs")
        assert 0 < result.stats.arc_count < row["arcs"]
        check_certified(path, result, outs, row["tolerance"])
        check_structure(path, outs, row["tolerance"])


# -- certified deviations of seeded random Béziers -------------------------------------


def random_beziers(rng: np.random.Generator) -> Iterable[tuple[Path, float]]:
    """Two cubics and a quadratic of size ~20 with tolerances from 1e-4 to 1e-1, and a chain
    of three cubics meeting at corners."""
    for n in (4, 4, 3):
        cp = [pt(*p) for p in rng.uniform(-10, 10, (n, 2))]
        segment = Cubic(*cp) if n == 4 else Quadratic(*cp)
        yield one(segment), float(10 ** rng.uniform(-4, -1))
    knots = rng.uniform(-10, 10, (4, 2))
    chain = tuple(
        Cubic(pt(*knots[i]), *(pt(*p) for p in rng.uniform(-10, 10, (2, 2))), pt(*knots[i + 1]))
        for i in range(3)
    )
    yield Path((Subpath(chain),)), float(10 ** rng.uniform(-3, -1))


@pytest.mark.parametrize("seed", range(16))
def test_certified_deviations_of_random_beziers(seed: int) -> None:
    rng = np.random.default_rng(seed)
    for path, tolerance in random_beziers(rng):
        for strategy in STRATEGIES:
            result, outs = run(path, tolerance, strategy)
            assert check_certified(path, result, outs, tolerance) == result.segment_count
            check_structure(path, outs, tolerance)


# -- the dense two-way oracle on representative paths ----------------------------------

ORACLE_CASES = {
    "corners and curves": ("M 0 0 L 10 0 C 15 0 15 5 10 10 L 0 10 Q -5 5 0 0 Z", 0.01),
    "cusp": ("M 0 0 C 10 10 0 10 10 0", 0.01),
    "loop": ("M 0 0 C 10 10 -3 10 7 0", 0.01),
    "one closed cubic (corner at the seam)": ("M 10 10 C 15 10 5 15 10 10 Z", 0.002),
    "smooth closed blob": ("M 0 0 C 10 0 10 10 0 10 C -10 10 -10 0 0 0 Z", 0.01),
    "figure eight (smooth seam)": ("M 0 0 C 20 20 20 -20 0 0 C -20 20 -20 -20 0 0 Z", 0.02),
    "smooth quadratic chain": ("M 0 0 Q 5 10 10 0 T 20 0 T 30 0", 0.01),
    "a line that doubles back": ("M 0 0 C 10 0 -5 0 5 0", 0.001),
    "two subpaths, a circle": (
        "M 0 0 C 3 3 7 3 10 0 M 20 0 L 30 0 A 5 5 0 0 1 40 0 A 5 5 0 0 1 30 0",
        0.01,
    ),
    "tiny": ("M 1e-6 1e-6 C 2e-6 1e-6 2e-6 2e-6 1e-6 2e-6", 1e-9),
    "far from the origin": ("M 1e5 1e5 C 100010 1e5 100010 100010 1e5 100010", 0.01),
}


@pytest.mark.parametrize("strategy", STRATEGIES)
@pytest.mark.parametrize(("d", "tolerance"), ORACLE_CASES.values(), ids=ORACLE_CASES.keys())
def test_dense_oracle_on_representative_paths(d: str, tolerance: float, strategy: str) -> None:
    path = parse_path_data(d)
    result, outs = run(path, tolerance, strategy)
    verdict = check_oracle(path, outs, tolerance, samples=513)
    check_structure(path, outs, tolerance)
    # The reported maximum is the measured one (to the oracle's relative accuracy of its
    # sampled maxima, and to rounding at the coordinates).
    measured = max(max(v) for v in verdict.segment_deviation)
    scale = max(abs(v) for o in outs for s in o for v in (*s["start"], *s["end"]))
    assert result.stats.max_deviation == pytest.approx(
        measured, rel=1e-6, abs=po.rounding_slack(scale)
    )


@pytest.mark.parametrize("strategy", STRATEGIES)
def test_dense_oracle_on_elliptical_arcs(strategy: str) -> None:
    # Once refused by the oracle: the last output's u_end was 1.0000000000000002.
    path = parse_path_data("M 0 0 A 10 5 30 0 1 10 0 L 10 5 A 6 4 90 1 0 0 -2 z")
    _, outs = run(path, 0.01, strategy)
    check_oracle(path, outs, 0.01, samples=513)
    check_structure(path, outs, 0.01)


@pytest.mark.parametrize("strategy", STRATEGIES)
@pytest.mark.parametrize(
    "d", ["M 0 0 A 10 5 30 0 1 10 0", "M 0 0 A 6 4 90 1 0 0 -2", "M 0 0 A 8 3 -20 1 1 5 5"]
)
def test_elliptical_arc_deviations_by_the_oracle(d: str, strategy: str) -> None:
    """Each output of an elliptical arc measured against its piece of the ellipse."""
    path = parse_path_data(d)
    tolerance = 0.01
    _, outs = run(path, tolerance, strategy)
    arc = path.subpaths[0].segments[0]
    for o in outs[0]:
        measured = po.measure_piece(arc, o["u_start"], o["u_end"], o, samples=513)
        assert measured <= tolerance, o
        assert measured == pytest.approx(o["max_deviation"], rel=1e-3, abs=1e-12)
    check_structure(path, outs, tolerance)


# -- properties --------------------------------------------------------------------------

#: Coordinates on a dyadic grid (multiples of 2⁻¹⁰ in [−20, 20]): sums and differences of a
#: few are exact, so a cusp built below is exact and a reflected control point exactly
#: collinear, while coincidences stay as rare as with any floats.
wide = st.integers(-20 * 1024, 20 * 1024).map(lambda k: k / 1024)


@st.composite
def arc_data(draw: st.DrawFn, start: Point) -> CircularArc | EllipticalArc | None:
    """An arc from ``start`` in SVG's endpoint form (radii, rotation, flags, end point),
    converted by the path data parser; ``None`` if it gives no arc (the end is the start, or
    radii too small for the chord are scaled up onto its midpoint: degenerate)."""
    rx = draw(st.integers(2, 25))
    ry = draw(st.one_of(st.just(rx), st.integers(2, 25)))
    rot = draw(st.sampled_from([0, 17, 30, 45, 90]))
    large, sweep = draw(st.integers(0, 1)), draw(st.integers(0, 1))
    end = pt(draw(wide), draw(wide))
    d = f"M {start.x!r} {start.y!r} A {rx} {ry} {rot} {large} {sweep} {end.x!r} {end.y!r}"
    path = parse_path_data(d)
    if not path.subpaths:
        return None
    (segment,) = path.subpaths[0].segments
    if not isinstance(segment, CircularArc | EllipticalArc):
        return None
    if max(math.dist(segment.start, segment.end), 1.0) >= 2 * min(rx, ry) - 1e-6:
        return None  # radii scaled up to the chord (or nearly): a half-turn at most
    return segment


@st.composite
def generic_paths(draw: st.DrawFn) -> Path:
    """Random subpaths of lines, quadratics, cubics and circular and elliptical arcs (as SVG
    gives them) with corners, smooth joints (the previous control point reflected), exact
    cusps (a scaled copy of (0,0) (1,1) (0,1) (1,0) by a power of two: B'(1/2) = 0 exactly),
    loops, and closed subpaths (closed by a line where the end is not the start, as Z)."""
    subpaths = []
    for _ in range(draw(st.integers(1, 2))):
        start = cur = pt(draw(wide), draw(wide))
        prev_control: Point | None = None
        segments: list[Segment] = []
        for _ in range(draw(st.integers(1, 3))):
            kind = draw(
                st.sampled_from(["line", "quadratic", "cubic", "smooth", "cusp", "loop", "arc"])
            )
            arc = draw(arc_data(cur)) if kind == "arc" else None
            if arc is not None:
                segment: Segment = arc
            elif kind == "smooth" and prev_control is not None:
                c1 = pt(2 * cur.x - prev_control.x, 2 * cur.y - prev_control.y)
                c2, end = pt(draw(wide), draw(wide)), pt(draw(wide), draw(wide))
                segment = Cubic(cur, c1, c2, end)
            elif kind == "cusp":
                s = 2.0 ** draw(st.integers(0, 4))
                sx, sy = draw(st.sampled_from([1, -1])) * s, draw(st.sampled_from([1, -1])) * s
                x, y = cur
                segment = Cubic(cur, pt(x + sx, y + sy), pt(x, y + sy), pt(x + sx, y))
            elif kind == "loop":
                a, b = draw(wide) / 4, draw(wide) / 4
                x, y = cur
                # (0,0) (10,1) (−3,10) (7,0) rotated and scaled by (a, b): a loop.
                segment = Cubic(
                    cur,
                    pt(x + 10 * a - b, y + 10 * b + a),
                    pt(x - 3 * a - 10 * b, y + 10 * a - 3 * b),
                    pt(x + 7 * a, y + 7 * b),
                )
            elif kind == "line":
                segment = Line(cur, pt(draw(wide), draw(wide)))
            elif kind == "quadratic":
                segment = Quadratic(cur, pt(draw(wide), draw(wide)), pt(draw(wide), draw(wide)))
            else:
                segment = Cubic(cur, *(pt(draw(wide), draw(wide)) for _ in range(3)))
            segments.append(segment)
            cur = segment.end
            cp = bezier_points(segment)
            prev_control = cp[-2] if cp is not None else None
        closed = draw(st.booleans())
        if closed and cur != start:
            segments.append(Line(cur, start))
        subpaths.append(Subpath(tuple(segments), closed))
    return Path(tuple(subpaths))


def _generic(path: Path) -> bool:
    """No coincident points or (nearly) collinear control points by chance: those are the
    degenerate cases, tested on their own below; and no segment tiny beside the tolerance."""
    for sub in path.subpaths:
        for seg in sub.segments:
            points = bezier_points(seg)
            if points is None:
                continue  # an arc as SVG gives it (see arc_data)
            cp = np.array(points, dtype=float)
            legs = np.hypot(*np.diff(cp, axis=0).T)
            if np.min(legs) < 1e-3 or np.max(legs) < 0.1:
                return False
            if len(cp) > 2:
                d = np.diff(cp, axis=0)
                cross = np.abs(d[:-1, 0] * d[1:, 1] - d[:-1, 1] * d[1:, 0])
                if np.max(cross) < 1e-3 * np.max(legs) ** 2:
                    return False
    return True


@PROPERTY
@given(generic_paths(), st.sampled_from([0.1, 0.01, 0.001]), st.sampled_from(STRATEGIES))
def test_random_paths_keep_every_guarantee(path: Path, tolerance: float, strategy: str) -> None:
    assume(_generic(path))
    result, outs = run(path, tolerance, strategy)
    check_structure(path, outs, tolerance)
    check_certified(path, result, outs, tolerance)


@settings(PROPERTY, max_examples=4)
@given(generic_paths(), st.sampled_from(STRATEGIES))
def test_random_paths_pass_the_dense_oracle(path: Path, strategy: str) -> None:
    assume(_generic(path))
    assume(sum(len(s.segments) for s in path.subpaths) <= 4)
    _, outs = run(path, 0.05, strategy)
    check_oracle(path, outs, 0.05, samples=513)


grid = st.integers(-6, 6)


@st.composite
def grid_path_data(draw: st.DrawFn) -> str:
    """SVG path data on a small integer grid: coincident and collinear control points,
    zero-length segments, exact cusps, loops, arcs and ``Z`` come up all the time."""
    parts = []
    for _ in range(draw(st.integers(1, 2))):
        parts.append(f"M {draw(grid)} {draw(grid)}")
        for _ in range(draw(st.integers(1, 4))):
            command = draw(st.sampled_from("LQTCCSA"))
            n = {"L": 2, "Q": 4, "T": 2, "C": 6, "S": 4}.get(command, 0)
            if command == "A":
                rx, ry = draw(st.integers(1, 6)), draw(st.integers(1, 6))
                rot = draw(st.sampled_from([0, 30, 90]))
                flags = f"{draw(st.integers(0, 1))} {draw(st.integers(0, 1))}"
                parts.append(f"A {rx} {ry} {rot} {flags} {draw(grid)} {draw(grid)}")
            else:
                parts.append(command + " " + " ".join(str(draw(grid)) for _ in range(n)))
        if draw(st.booleans()):
            parts.append("Z")
    return " ".join(parts)


@PROPERTY
@given(grid_path_data(), st.sampled_from([0.1, 0.01]), st.sampled_from(STRATEGIES))
def test_degenerate_paths_are_handled_or_refused_with_where(
    d: str, tolerance: float, strategy: str
) -> None:
    """Never NaN, never another exception, never beyond the tolerance; a refusal names
    the subpath (and segment) it is about."""
    try:
        path = parse_path_data(d)
    except GeometryError:
        assume(False)
    assume(len(path.subpaths) > 0)
    try:
        result, outs = run(path, tolerance, strategy)
    except GeometryError as error:
        refusal: GeometryError | None = error
    else:
        refusal = None
    if refusal is not None:
        assert "path.subpaths[" in str(refusal), str(refusal)
        return
    # Tangents at degenerate ends: see the examples below.
    check_structure(path, outs, tolerance, tangents=False)
    check_certified(path, result, outs, tolerance)


@PROPERTY
@given(generic_paths(), st.integers(-200, 200), st.sampled_from(STRATEGIES))
def test_scaling_by_a_power_of_two_scales_the_output_exactly(
    path: Path, k: int, strategy: str
) -> None:
    assume(_generic(path))
    f = 2.0**k

    def scaled(segment: Segment) -> Segment:
        """The segment scaled by ``f`` about the origin: points and radii, not angles."""
        fields = {
            name: pt(value[0] * f, value[1] * f)
            if isinstance(value, tuple)
            else value * f
            if name in ("radius", "rx", "ry")
            else value
            for name, value in segment._asdict().items()
        }
        return type(segment)(**fields)

    big = Path(
        tuple(Subpath(tuple(scaled(s) for s in sub.segments), sub.closed) for sub in path.subpaths)
    )
    _, outs = run(path, 0.01, strategy)
    _, big_outs = run(big, 0.01 * f, strategy)
    lengths = ("start", "end", "center", "radius", "length", "max_deviation")
    for mine, theirs in zip(outs, big_outs, strict=True):
        assert len(mine) == len(theirs)
        for a, b in zip(mine, theirs, strict=True):
            for key, value in a.items():
                if key in lengths:
                    expect = [v * f for v in value] if isinstance(value, list) else value * f
                    assert b[key] == expect, key
                else:
                    assert b[key] == value, key


# -- degenerate input, one by one ------------------------------------------------------


def lines_only(path: Path, tolerance: float) -> None:
    """The output is lines, lying on the source to rounding both ways (the oracle's union
    Hausdorff distance), for both strategies."""
    for strategy in STRATEGIES:
        _, outs = run(path, tolerance, strategy)
        assert all(o["type"] == "line" for o in outs[0]), [o["type"] for o in outs[0]]
        check_structure(path, outs, tolerance)
        verdict = po.check_path(path, outs, tolerance, samples=257)
        assert verdict.ok, verdict.describe()
        assert max(verdict.subpath_union) < 1e-12


STRAIGHT = {
    "coincident pairs": "M 0 0 C 0 0 10 0 10 0",
    "first three coincide": "M 0 0 C 0 0 0 0 10 5",
    "evenly spaced": "M 0 0 C 1 2 2 4 3 6",
    "doubles back twice": "M 0 0 C 10 0 -5 0 5 0",
    "quadratic doubles back": "M 0 0 Q 10 0 5 0",
    "quadratic out and back": "M 0 0 Q 10 0 0 0",
    "out and back, diagonal": "M 0 0 C 3 4 3 4 0 0",
    "straight among curves": "M -5 0 Q 0 5 0 0 C 2 0 4 0 6 0 L 6 6",
}


@pytest.mark.parametrize("d", STRAIGHT.values(), ids=STRAIGHT.keys())
def test_straight_beziers_become_lines_on_the_source(d: str) -> None:
    path = parse_path_data(d)
    if len(path.subpaths[0].segments) == 1:
        lines_only(path, 0.001)
    else:
        for strategy in STRATEGIES:
            _, outs = run(path, 0.001, strategy)
            check_structure(path, outs, 0.001)
            assert po.check_path(path, outs, 0.001, samples=257).ok


@pytest.mark.parametrize(
    "d",
    [
        "M 0 0 Q 4 0 3 0",
        "M 0 0 Q 4 4 3 3",
        "M 0 0 C 1 0 -1 0 0 0",
        "M 0 0 C 10 5 10 5 10 5",
    ],
)
def test_straight_beziers_that_are_refused(d: str) -> None:
    lines_only(parse_path_data(d), 0.01)


def test_a_straight_cubic_has_no_micro_arc_at_its_turning_point() -> None:
    lines_only(parse_path_data("M -3 -4 C 9 12 3 4 0 0"), 0.01)


def test_zero_length_segments_are_left_out() -> None:
    for d in ("M 0 0 L 10 0 L 10 0 L 10 10", "M 0 0 L 10 0 C 10 0 10 0 10 0 Q 10 0 10 0 L 10 10"):
        path = parse_path_data(d)
        segs = path.subpaths[0].segments
        for strategy in STRATEGIES:
            _, outs = run(path, 0.01, strategy)
            assert [(o["type"], o["source_segment"]) for o in outs[0]] == [
                ("line", 0),
                ("line", len(segs) - 1),
            ]
            check_structure(path, outs, 0.01)


@pytest.mark.parametrize("strategy", STRATEGIES)
def test_a_cusp_is_a_corner_exactly_where_it_is(strategy: str) -> None:
    # B'(1/2) = 0 and B(1/2) = (5, 7.5): the output turns back there, and only there.
    path = parse_path_data("M 0 0 C 10 10 0 10 10 0")
    _, outs = run(path, 0.01, strategy)
    check_structure(path, outs, 0.01)
    joints = [i for i in range(len(outs[0]) - 1) if outs[0][i]["u_end"] == 0.5]
    assert len(joints) == 1
    a, b = outs[0][joints[0]], outs[0][joints[0] + 1]
    assert a["end"] == [5.0, 7.5]
    assert angle(out_tangent(a, end=True), out_tangent(b, end=False)) > math.pi - 1e-6


@pytest.mark.parametrize("strategy", STRATEGIES)
def test_input_corners_are_kept_and_lines_and_arcs_are_kept(strategy: str) -> None:
    d = "M 0 0 L 10 0 A 5 5 0 0 1 20 0 L 20 -10 C 20 -20 0 -20 0 -10 Z"
    path = parse_path_data(d)
    _, outs = run(path, 0.01, strategy)
    check_structure(path, outs, 0.01)
    segs = path.subpaths[0].segments
    first = [next(o for o in outs[0] if o["source_segment"] == j) for j in range(len(segs))]
    last = [[o for o in outs[0] if o["source_segment"] == j][-1] for j in range(len(segs))]
    # The corners' angles are the input's, to rounding: at (10, 0) the arc leaves upwards.
    corners = [
        angle(out_tangent(last[j - 1], end=True), out_tangent(first[j], end=False))
        for j in range(len(segs))
    ]
    expected = [
        angle(src_tangent(segs[j - 1], 1.0), src_tangent(segs[j], 0.0)) for j in range(len(segs))
    ]
    assert corners == pytest.approx(expected, abs=1e-9)
    assert corners[1] == pytest.approx(math.pi / 2, abs=1e-12)


@pytest.mark.parametrize("strategy", STRATEGIES)
def test_a_smooth_closed_subpath_is_g1_at_its_seam(strategy: str) -> None:
    path = parse_path_data("M 0 0 C 10 0 10 10 0 10 C -10 10 -10 0 0 0 Z")
    _, outs = run(path, 0.001, strategy)
    check_structure(path, outs, 0.001)
    chain = outs[0]
    assert chain[-1]["end"] == chain[0]["start"]
    assert angle(out_tangent(chain[-1], end=True), out_tangent(chain[0], end=False)) <= 1e-9


@pytest.mark.parametrize(
    ("d", "breaks"),
    [
        ("M 0 0 C 10 0 10 10 10 10", "refused as a near-cusp"),
        ("M 0 0 C 2 -12 0 -4 0 -4 L -2 4", "the last arc's end tangent is 0.675 rad off"),
    ],
)
def test_coincident_last_control_points(d: str, breaks: str) -> None:
    path = parse_path_data(d)
    for strategy in STRATEGIES:
        _, outs = run(path, 0.01, strategy)
        check_structure(path, outs, 0.01)


@pytest.mark.parametrize("d", ["M 10 10 C 10 10 10 0 0 0", "M -2 4 L 0 -4 C 0 -4 2 -12 0 0"])
def test_coincident_first_control_points(d: str) -> None:
    """The mirror images of the cases above are handled."""
    path = parse_path_data(d)
    for strategy in STRATEGIES:
        result, outs = run(path, 0.01, strategy)
        check_structure(path, outs, 0.01)
        check_certified(path, result, outs, 0.01)


@pytest.mark.parametrize(
    ("d", "tolerance"),
    [
        # Regressions: the u of outputs once missed by 1 ulp at pieces' boundaries (rows
        # mapped t0 + (t1 − t0)·1 for one and t0 of the next piece for the other), and an
        # arc's last u_end was (a0 + sweep − a0)/sweep.
        ("M 0 0 C -2 -3 4 -5 7 -3", 0.1),  # 0.6647670508799826 != 0.6647670508799827
        ("M 0 0 C -9 4 1 3 5 3", 0.1),
        ("M 0 0 Q 5 10 10 0 T 20 0", 0.01),
        ("M 0 0 A 10 5 30 0 1 10 0", 0.01),  # last u_end 1.0000000000000002
        ("M 0 0 A 3 3 45 0 0 0 1", 0.01),  # last u_end 0.9999999999999999
        ("M 0 0 A 5 5 0 1 1 -5 -8", 0.01),
        ("M 0 0 A 6 4 90 0 0 0 -2", 0.01),
    ],
)
@pytest.mark.parametrize("strategy", STRATEGIES)
def test_u_ranges_tile_exactly(d: str, tolerance: float, strategy: str) -> None:
    path = parse_path_data(d)
    _, outs = run(path, tolerance, strategy)
    for j in range(len(path.subpaths[0].segments)):
        mine = [o for o in outs[0] if o["source_segment"] == j]
        us, ue = [o["u_start"] for o in mine], [o["u_end"] for o in mine]
        assert us[0] == 0.0
        assert ue[-1] == 1.0
        assert ue[:-1] == us[1:]


@pytest.mark.parametrize("strategy", STRATEGIES)
def test_an_elliptical_arc_starting_at_a_vertex(strategy: str) -> None:
    d = "M 2.121320343559643 2.1213203435596424 A 3 7 45 0 1 -3.018914603595431 5.311223149815971"
    path = parse_path_data(d)
    _, outs = run(path, 0.01, strategy)
    check_structure(path, outs, 0.01)


@pytest.mark.parametrize("strategy", STRATEGIES)
def test_a_near_cusp_gives_no_empty_output(strategy: str) -> None:
    d = (
        "M 6.260372607526325 -6.28045255389363 C -1.7396273924736754 -14.28045255389363 "
        "6.260372607526325 -14.28045255389363 -1.7396273924736754 -6.28045255389363"
    )
    path = parse_path_data(d)
    try:
        _, outs = run(path, 0.1, strategy)
    except GeometryError as error:  # a refusal as a near-cusp is fine too
        field: str | None = error.field
    else:
        field = None
    if field is not None:
        assert field == "path.subpaths[0].segments[0]"
        return
    check_structure(path, outs, 0.1)
    check_oracle(path, outs, 0.1, samples=257)


# -- refusals --------------------------------------------------------------------------


def refusal(path: Path, tolerance: float = 0.01, strategy: str = "subdivide") -> GeometryError:
    with pytest.raises(GeometryError) as info:
        approximate_path(path, tolerance, strategy)  # type: ignore[arg-type]
    return info.value


def test_a_subpath_of_one_point_is_refused_by_name() -> None:
    err = refusal(parse_path_data("M 0 0 L 1 0 M 1 1 C 1 1 1 1 1 1"))
    assert err.field == "path.subpaths[1]"
    assert "no length" in err.message


@pytest.mark.parametrize(
    ("segment", "says"),
    [
        (Cubic(pt(0, 0), pt(1e150, 0), pt(1, 1), pt(2, 0)), "not finite or beyond"),
        (Cubic(pt(0, 0), pt(math.nan, 0), pt(1, 1), pt(2, 0)), "not finite"),
        (Quadratic(pt(0, 0), pt(math.inf, 1), pt(2, 0)), "not finite"),
        (Line(pt(-1e151, 0), pt(0, 0)), "not finite or beyond"),
        (CircularArc(pt(1, 0), pt(0, 1), pt(0, 0), 0.0, 0.0, 1.0), "radii must be > 0"),
        (CircularArc(pt(1, 0), pt(1, 0), pt(0, 0), 1.0, 0.0, 2 * math.pi), "less than a full"),
        (
            EllipticalArc(pt(1, 0), pt(0, 1), pt(0, 0), 1.0, -1.0, 0.0, 0.0, 1.0),
            "radii must be > 0",
        ),
    ],
    ids=["huge", "nan", "inf", "huge line", "zero radius", "full turn", "negative ry"],
)
def test_numbers_the_core_cannot_take_are_refused_naming_the_segment(
    segment: Segment, says: str
) -> None:
    path = Path((Subpath((Line(pt(-1, 0), pt(0, 0)),)), Subpath((segment,))))
    err = refusal(path)
    assert err.field == "path.subpaths[1].segments[0]"
    assert says in err.message


@pytest.mark.parametrize("tolerance", [0.0, -1.0, math.nan, math.inf])
def test_a_bad_tolerance_is_refused(tolerance: float) -> None:
    assert refusal(parse_path_data("M 0 0 L 1 0"), tolerance).field == "tolerance"


def test_a_bad_strategy_and_empty_paths_are_refused() -> None:
    assert refusal(parse_path_data("M 0 0 L 1 0"), strategy="best").field == "strategy"
    assert refusal(Path(())).field == "path"
    assert refusal(Path((Subpath(()),))).field == "path.subpaths[0]"


def test_a_tolerance_below_the_floor_is_refused_naming_the_segment() -> None:
    err = refusal(parse_path_data("M 0 0 L 1 0 M 1e12 1e12 C 1e12 0 0 1e12 0 0"), 1e-9)
    assert err.kind == "tolerance_floor"
    assert "path.subpaths[1].segments[0]" in err.message
    assert err.limit is not None
    assert err.limit > 1e-9


def test_tiny_curves_are_handled_or_refused_with_the_true_reason() -> None:
    path = parse_path_data("M 0 0 C 1e-199 0 1e-199 1e-199 0 1e-199")
    try:
        result, outs = run(path, 1e-202, "subdivide")
    except GeometryError as error:
        refusal: GeometryError | None = error
    else:
        refusal = None
    if refusal is not None:
        assert "coincide" not in refusal.message
        assert "segments[0]" in str(refusal)
    else:
        check_structure(path, outs, 1e-202)
        check_certified(path, result, outs, 1e-202)
