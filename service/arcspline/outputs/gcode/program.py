"""The program text: preamble; per part (a spiral, or each subpath of a path) a rapid to its
start (with the 2.5-D retract and plunge) and one block per planned move; ``M2``; optional
header comments and line numbers."""

from __future__ import annotations

from collections.abc import Iterator, Sequence

from arcspline.geometry import ArcSpline, Curve

from ..part import Part
from .lattice import feed_word, fixed_point
from .options import GcodeError, GcodeOptions
from .plan import Plan, plan_program

#: RS-274/NGC line numbers have at most five digits.
MAX_LINE_NUMBER = 99_999


def _header(plans: Sequence[Plan], parts: Sequence[Part], options: GcodeOptions) -> Iterator[str]:
    d = options.resolved_decimals
    units = options.units
    first = parts[0][0]
    arc_count = sum(spline.stats.arc_count for spline, _ in parts)
    line_count = sum(spline.stats.line_count for spline, _ in parts)
    worst = max(spline.stats.max_deviation for spline, _ in parts)
    arcs = sum(w is not None for plan in plans for w in plan.arcs)
    moves = sum(len(plan.arcs) for plan in plans)
    measured = max(float(plan.deviation.max()) for plan in plans)
    yield "(arcspline: curves as circular arcs, after Walton and Meek 1996)"
    yield f"(tolerance {first.tolerance:.6g} {units}, strategy {first.strategy})"
    yield (
        f"(arc spline: {arc_count} arcs, {line_count} lines, max deviation {worst:.6g} {units}"
        + (f", {len(parts)} paths)" if len(parts) > 1 else ")")
    )
    yield f"(program: {moves} moves, {arcs} arcs G2 G3, {moves - arcs} lines G1)"
    yield (
        f"(measured max deviation of the program from the curve {measured:.6g} {units}, "
        f"{d} decimals)"
    )
    levels = options.pass_levels
    if len(levels) > 1:
        step = fixed_point(-levels[0], d)  # the first pass is one step below Z0
        yield (
            f"(depth: {len(levels)} passes of at most {step} {units} down to "
            f"Z{fixed_point(levels[-1], d)}, every pass of a path before the next path)"
        )


def _text(plans: Sequence[Plan], parts: Sequence[Part], options: GcodeOptions) -> Iterator[str]:
    """The program's lines, without line numbers."""
    d = options.resolved_decimals
    units = options.units
    feed = feed_word(options.feed_rate, d)
    if options.comments:
        yield from _header(plans, parts, options)
    yield f"G17 {'G21' if units == 'mm' else 'G20'} G90 G91.1 G94 {feed}"
    two_and_a_half = options.safe_z is not None and options.cut_z is not None
    safe = plunge = ""
    if options.safe_z is not None:
        safe = fixed_point(round(options.safe_z * 10**d), d)
    levels = [fixed_point(z, d) for z in options.pass_levels]
    if two_and_a_half:
        plunge = feed_word(options.resolved_plunge_feed_rate, d)
    for plan in plans:
        x0, y0 = fixed_point(plan.start[0], d), fixed_point(plan.start[1], d)
        restore = ""
        if not two_and_a_half:
            yield f"G0 X{x0} Y{y0}"
            yield from _cuts(plan, d, restore)
            continue
        # A closed part ends where it starts: the next pass plunges there; an open one
        # retracts and goes back to its start.
        closed = plan.ends[-1] == plan.start
        for k, cut in enumerate(levels):
            if k == 0 or not closed:
                yield f"G0 Z{safe}"
                yield f"G0 X{x0} Y{y0}"
            if plunge == feed:
                yield f"G1 Z{cut}"
            else:
                yield f"G1 Z{cut} {plunge}"
                restore = f" {feed}"
            yield from _cuts(plan, d, restore)
    if options.safe_z is not None:
        yield f"G0 Z{safe}"
    yield "M2"


def _cuts(plan: Plan, d: int, restore: str) -> Iterator[str]:
    """One block per planned move; the first restores the feed after a slower plunge."""
    for k, (end, arc) in enumerate(zip(plan.ends, plan.arcs, strict=True)):
        words = f"X{fixed_point(end[0], d)} Y{fixed_point(end[1], d)}"
        if arc is not None:
            if arc.radius is not None:
                words += f" R{fixed_point(arc.radius, d)}"
            else:
                assert arc.offset is not None
                words += f" I{fixed_point(arc.offset[0], d)} J{fixed_point(arc.offset[1], d)}"
        code = "G1" if arc is None else "G3" if arc.ccw else "G2"
        yield f"{code} {words}{restore if k == 0 else ''}"


def write_program(spline: ArcSpline, curve: Curve, options: GcodeOptions) -> str:
    """The G-code program cutting ``spline``, an approximation of ``curve``
    (:func:`write_parts` of one part)."""
    return write_parts([(spline, curve)], options)


def write_parts(parts: Sequence[Part], options: GcodeOptions) -> str:
    """One G-code program cutting every part in order, with a rapid (at ``safe_z``, if
    given) between them.

    Raises :class:`GcodeError` when a curve's coordinates are too large to write
    (``spiral``), or when ``options.decimals`` are too coarse for the spline's tolerance: the
    path read back from the program would leave ``tolerance + 10^-decimals`` of the curve.
    """
    if not parts or any(len(spline) == 0 for spline, _ in parts):
        raise GcodeError("spiral", "the arc spline has no segments")
    plans = [plan_program(spline, curve, options) for spline, curve in parts]
    return numbered(list(_text(plans, parts, options)), options)


def numbered(lines: list[str], options: GcodeOptions) -> str:
    """The program's text: with ``line_numbers``, ``N10``, ``N20``, … (``N1``, ``N2``, … when
    tens would pass :data:`MAX_LINE_NUMBER`) on every line but comments."""
    if options.line_numbers:
        coded = [k for k, text in enumerate(lines) if not text.startswith("(")]
        step = 10 if 10 * len(coded) <= MAX_LINE_NUMBER else 1
        if step * len(coded) > MAX_LINE_NUMBER:
            raise GcodeError(
                "line_numbers", f"a program of {len(coded)} blocks exceeds N{MAX_LINE_NUMBER}"
            )
        for n, k in enumerate(coded, start=1):
            lines[k] = f"N{n * step} {lines[k]}"
    return "\n".join(lines) + "\n"


class GcodeWriter:
    """The program as an output writer; its options are :class:`GcodeOptions`."""

    name = "gcode"
    media_type = "text/x-gcode"

    def write(self, parts: Sequence[Part], options: GcodeOptions) -> str:
        return write_parts(parts, options)


WRITER = GcodeWriter()
