"""The program text: preamble, rapid to the start (with the 2.5-D retract and plunge), one
block per planned move, ``M2``; optional header comments and line numbers."""

from __future__ import annotations

from collections.abc import Iterator

from arcspline.geometry import ArcSpline, Curve

from .lattice import feed_word, fixed_point
from .options import GcodeError, GcodeOptions
from .plan import Plan, plan_program

#: RS-274/NGC line numbers have at most five digits.
MAX_LINE_NUMBER = 99_999


def _text(plan: Plan, spline: ArcSpline, options: GcodeOptions) -> Iterator[str]:
    """The program's lines, without line numbers."""
    d = options.resolved_decimals
    units = options.units
    feed = feed_word(options.feed_rate, d)
    if options.comments:
        stats = spline.stats
        arcs = sum(w is not None for w in plan.arcs)
        moves = len(plan.arcs)
        yield "(arcspline: cubic Bezier spiral as circular arcs, Walton and Meek 1996)"
        yield f"(tolerance {spline.tolerance:.6g} {units}, strategy {spline.strategy})"
        yield (
            f"(arc spline: {stats.arc_count} arcs, {stats.line_count} lines, "
            f"max deviation {stats.max_deviation:.6g} {units})"
        )
        yield f"(program: {moves} moves, {arcs} arcs G2 G3, {moves - arcs} lines G1)"
        yield (
            f"(measured max deviation of the program from the spiral "
            f"{float(plan.deviation.max()):.6g} {units}, {d} decimals)"
        )
    yield f"G17 {'G21' if units == 'mm' else 'G20'} G90 G91.1 G94 {feed}"
    x0, y0 = fixed_point(plan.start[0], d), fixed_point(plan.start[1], d)
    restore = ""
    if options.safe_z is not None and options.cut_z is not None:
        safe = fixed_point(round(options.safe_z * 10**d), d)
        cut = fixed_point(round(options.cut_z * 10**d), d)
        plunge = feed_word(options.resolved_plunge_feed_rate, d)
        yield f"G0 Z{safe}"
        yield f"G0 X{x0} Y{y0}"
        if plunge == feed:
            yield f"G1 Z{cut}"
        else:
            yield f"G1 Z{cut} {plunge}"
            restore = f" {feed}"
    else:
        yield f"G0 X{x0} Y{y0}"
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
    if options.safe_z is not None:
        yield f"G0 Z{fixed_point(round(options.safe_z * 10**d), d)}"
    yield "M2"


def write_program(spline: ArcSpline, curve: Curve, options: GcodeOptions) -> str:
    """The G-code program cutting ``spline``, an approximation of ``curve``.

    Raises :class:`GcodeError` when the spiral's coordinates are too large to write
    (``spiral``), or when ``options.decimals`` are too coarse for the spline's tolerance: the
    path read back from the program would leave ``tolerance + 10^-decimals`` of the spiral.
    """
    if len(spline) == 0:
        raise GcodeError("spiral", "the arc spline has no segments")
    lines = list(_text(plan_program(spline, curve, options), spline, options))
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

    def write(self, spline: ArcSpline, curve: Curve, options: GcodeOptions) -> str:
        return write_program(spline, curve, options)


WRITER = GcodeWriter()
