"""The summary tables on stderr: for each input, what its answer says about itself (its
``stats``: segments, the largest deviation and the tolerance it was fitted to), the time
the work took, and where the output went — or why it failed. Nothing here is computed
again: every number is the service's own, or the command's clock."""

from __future__ import annotations

from collections import Counter
from collections.abc import Sequence
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING, NamedTuple

from rich import box
from rich.table import Table
from rich.text import Text

from .options import Kind

if TYPE_CHECKING:
    from arcspline.api.offset_schemas import MachiningResponse, OffsetResponse
    from arcspline.api.path_schemas import PathStatsResponse
    from arcspline.api.schemas import StatsResponse
    from arcspline.client import ApproximateResponse, DrawingResponse, PathResponse


class OffsetFacts(NamedTuple):
    """An answer's ``offset`` block: the offset asked for, the contours in and the
    tool-centre paths out, how many notes, and the bound on their distance from the exact
    offset of the input (its fit's deviation: offsets are 1-Lipschitz)."""

    distance: float
    side: str
    contours_in: int
    paths_out: int
    notes: int
    source_max_deviation: float


class MachiningFacts(NamedTuple):
    """An answer's ``machining`` block: the tool, how many contours are cut on each side
    (``(("outside", 1), ("inside", 1))``), how many warnings, the rapids' length."""

    tool_diameter: float
    cuts: tuple[tuple[str, int], ...]
    warnings: int
    rapid_length: float


@dataclass(frozen=True)
class Summary:
    """An answer's statistics. ``fitted_to`` is the tolerance the segments were fitted to;
    a drawing spends part of its ``tolerance`` before the fit (joining gaps, snapped cusps:
    docs/drawings.md §6), a curve none. ``offset``/``machining``: the answer's own block,
    when the request asked for one; their notes and warnings are among ``warnings``."""

    kind: Kind
    parts: int
    segments: int
    arcs: int
    lines: int
    max_deviation: float
    fitted_to: float
    tolerance: float
    units: str | None
    warnings: tuple[str, ...] = ()
    offset: OffsetFacts | None = None
    machining: MachiningFacts | None = None


@dataclass(frozen=True)
class Outcome:
    """One input's row: its summary (``None`` when not asked for, or failed), the time its
    work took, where its output went, or its ``error``."""

    name: str
    output: str
    summary: Summary | None = None
    seconds: float | None = None
    error: str | None = None


def summarize(answer: ApproximateResponse | PathResponse | DrawingResponse) -> Summary:
    """The statistics an answer carries (a spiral's, a path's or a drawing's)."""
    from arcspline.client import DrawingResponse, PathResponse

    if isinstance(answer, DrawingResponse):
        warnings = tuple(
            f"{w.element}: {w.reason}" + (f" ({w.occurrences}×)" if w.occurrences > 1 else "")
            for w in answer.document.warnings
        )
        parts = answer.stats.toolpath_count
        summary = _of(
            "drawing", parts, answer.stats, answer.budget.tolerance, answer.units, warnings
        )
    elif isinstance(answer, PathResponse):
        summary = _of("path", answer.stats.subpath_count, answer.stats, answer.stats.tolerance)
    else:
        return _of("spiral", 1, answer.stats, answer.stats.tolerance)
    return _with_tooling(summary, answer.offset, answer.machining)


def _with_tooling(
    summary: Summary, offset: OffsetResponse | None, machining: MachiningResponse | None
) -> Summary:
    """``summary`` with the facts of the answer's offset or machining block, and its notes or
    warnings (each names its contour) after the document's."""
    if offset is not None:
        facts = OffsetFacts(
            offset.distance, offset.side, offset.contours_in, offset.paths_out,
            len(offset.notes), offset.source_max_deviation,
        )  # fmt: skip
        notes = tuple(note.message for note in offset.notes)
        return replace(summary, offset=facts, warnings=summary.warnings + notes)
    if machining is not None:
        cuts = tuple(Counter(contour.cut for contour in machining.contours).items())
        plan = MachiningFacts(
            machining.tool_diameter, cuts, len(machining.warnings), machining.rapid_length
        )
        said = tuple(warning.message for warning in machining.warnings)
        return replace(summary, machining=plan, warnings=summary.warnings + said)
    return summary


def _of(
    kind: Kind,
    parts: int,
    stats: StatsResponse | PathStatsResponse,
    tolerance: float,
    units: str | None = None,
    warnings: tuple[str, ...] = (),
) -> Summary:
    return Summary(
        kind, parts, stats.segment_count, stats.arc_count, stats.line_count,
        stats.max_deviation, stats.tolerance, tolerance, units, warnings,
    )  # fmt: skip


#: One input's lines (``approx``), and the columns of a batch's rows.
DETAILS = (
    "input",
    "kind",
    "segments",
    "arcs / lines",
    "max deviation",
    "tolerance",
    "offset",
    "machining",
    "time",
    "output",
)
COLUMNS = ("input", "segments", "max deviation", "tolerance", "time", "output")
_NUMBERS = frozenset({"segments", "arcs / lines", "max deviation", "tolerance", "time"})
_PARTS = {"drawing": "toolpath", "path": "subpath"}
_CAPTION = (
    "a drawing's deviation is from its joined toolpaths, fitted within what joining and "
    "snapping left of the tolerance (fit), so the drawing as given is within the tolerance"
)


def table(outcomes: Sequence[Outcome], title: str) -> Table:
    """One row per input, in order (``batch``)."""
    grid = Table(title=title, box=box.SIMPLE_HEAD, title_justify="left")
    for heading in COLUMNS:
        if heading in _NUMBERS:
            grid.add_column(heading, justify="right", no_wrap=True)
        else:
            grid.add_column(heading, overflow="fold", min_width=12)
    for outcome in outcomes:
        cells = _cells(outcome)
        grid.add_row(*(cells.get(heading, "") for heading in COLUMNS))
    if any(_spent(o.summary) for o in outcomes):
        grid.caption = _CAPTION
    return grid


def details(outcome: Outcome, title: str) -> Table:
    """One input's lines (``approx``)."""
    grid = Table(title=title, box=box.SIMPLE, show_header=False, title_justify="left")
    grid.add_column(style="bold", no_wrap=True)
    grid.add_column(overflow="fold")
    cells = _cells(outcome)
    for heading in DETAILS:
        if cells.get(heading):
            grid.add_row(heading, cells[heading])
    if _spent(outcome.summary):
        grid.caption = _CAPTION
    return grid


def _cells(outcome: Outcome) -> dict[str, str | Text]:
    """An outcome's cells by heading; only what is known."""
    cells: dict[str, str | Text] = {"input": outcome.name, "output": outcome.output}
    if outcome.seconds is not None:
        cells["time"] = f"{outcome.seconds:.2f} s"
    if outcome.error is not None:
        cells["output"] = Text.assemble(("failed: ", "bold red"), outcome.error)
    summary = outcome.summary
    if summary is None:
        return cells
    kind: str = summary.kind
    if kind in _PARTS:
        kind += f", {summary.parts} {_PARTS[kind]}{'' if summary.parts == 1 else 's'}"
    ratio = summary.max_deviation / summary.fitted_to
    tolerance = f"{summary.tolerance:.4g}" + (f" {summary.units}" if summary.units else "")
    if _spent(summary):
        tolerance += f" (fit {summary.fitted_to:.4g})"
    cells.update(
        {
            "kind": kind,
            "segments": str(summary.segments),
            "arcs / lines": f"{summary.arcs} / {summary.lines}",
            "max deviation": f"{summary.max_deviation:.4g} ({ratio:.1%})",
            "tolerance": tolerance,
        }
    )
    unit = f" {summary.units}" if summary.units else ""
    if summary.offset is not None:
        cells["offset"] = _offset(summary.offset, unit)
    if summary.machining is not None:
        cells["machining"] = _machining(summary.machining, unit)
    return cells


def _offset(facts: OffsetFacts, unit: str) -> str:
    """``3 mm outside: 2 contours → 3 paths, 1 note (within 0.0099 of the exact offset)``."""
    return (
        f"{facts.distance:.4g}{unit} {facts.side}: {_count(facts.contours_in, 'contour')} → "
        f"{_count(facts.paths_out, 'path')}, {_count(facts.notes, 'note')} "
        f"(within {facts.source_max_deviation:.4g} of the exact offset)"
    )


def _machining(facts: MachiningFacts, unit: str) -> str:
    """``tool 6 mm: 2 contours (1 outside, 1 inside), 0 warnings, rapids 35.2 mm``."""
    contours = sum(n for _, n in facts.cuts)
    sides = ", ".join(f"{n} {cut}" for cut, n in facts.cuts)
    return (
        f"tool {facts.tool_diameter:.4g}{unit}: {_count(contours, 'contour')}"
        + (f" ({sides})" if sides else "")
        + f", {_count(facts.warnings, 'warning')}, rapids {facts.rapid_length:.4g}{unit}"
    )


def _count(n: int, noun: str) -> str:
    return f"{n} {noun}{'' if n == 1 else 's'}"


def _spent(summary: Summary | None) -> bool:
    return summary is not None and summary.fitted_to != summary.tolerance


def warnings(summary: Summary) -> list[Text]:
    """A drawing's warnings: what it held but did not draw, and notes (docs/drawings.md);
    then an offset's notes or a machining plan's warnings."""
    return [Text.assemble(("warning: ", "yellow"), line) for line in summary.warnings]
