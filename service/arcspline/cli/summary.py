"""The summary tables on stderr: for each input, what its answer says about itself (its
``stats``: segments, the largest deviation and the tolerance it was fitted to), the time
the work took, and where the output went — or why it failed. Nothing here is computed
again: every number is the service's own, or the command's clock."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING

from rich import box
from rich.table import Table
from rich.text import Text

from .options import Kind

if TYPE_CHECKING:
    from arcspline.api.path_schemas import PathStatsResponse
    from arcspline.api.schemas import StatsResponse
    from arcspline.client import ApproximateResponse, DrawingResponse, PathResponse


@dataclass(frozen=True)
class Summary:
    """An answer's statistics. ``fitted_to`` is the tolerance the segments were fitted to;
    a drawing spends part of its ``tolerance`` before the fit (joining gaps, snapped cusps:
    docs/drawings.md §6), a curve none."""

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
        return _of("drawing", parts, answer.stats, answer.budget.tolerance, answer.units, warnings)
    if isinstance(answer, PathResponse):
        return _of("path", answer.stats.subpath_count, answer.stats, answer.stats.tolerance)
    return _of("spiral", 1, answer.stats, answer.stats.tolerance)


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
    return cells


def _spent(summary: Summary | None) -> bool:
    return summary is not None and summary.fitted_to != summary.tolerance


def warnings(summary: Summary) -> list[Text]:
    """A drawing's warnings: what it held but did not draw, and notes (docs/drawings.md)."""
    return [Text.assemble(("warning: ", "yellow"), line) for line in summary.warnings]
