"""The summary tables (``arcspline.cli.summary``): every number is the answer's own, a
failure its reason, and what is not known is not shown."""

from __future__ import annotations

import io

from rich.console import Console

from arcspline.cli.summary import Outcome, Summary, details, table

SPIRAL = Summary("spiral", 1, 12, 12, 0, 0.000958845, 0.001, 0.001, None)
DRAWING = Summary("drawing", 3, 48, 44, 4, 0.0025, 0.0099, 0.01, "mm", ("g#a: hidden (2×)",))


def _text(renderable: object) -> str:
    console = Console(width=200, record=True, file=io.StringIO())
    console.print(renderable)
    return console.export_text()


def test_one_input_shows_its_statistics() -> None:
    text = _text(details(Outcome("paper.json", "paper.ngc", SPIRAL, 0.0123), "approx"))
    for line in ("kind            spiral", "segments        12", "arcs / lines    12 / 0",
                 "max deviation   0.0009588 (95.9%)", "tolerance       0.001",
                 "time            0.01 s", "output          paper.ngc"):  # fmt: skip
        assert line in text


def test_a_drawing_shows_its_tolerance_as_given_and_as_fitted() -> None:
    text = _text(details(Outcome("part.svg", "part.dxf", DRAWING, 1.0), "approx"))
    assert "drawing, 3 toolpaths" in text
    assert "0.01 mm (fit 0.0099)" in text
    assert "0.0025 (25.3%)" in text
    assert "fitted within what joining" in text


def test_a_batch_row_per_input_with_failures_and_their_reasons() -> None:
    outcomes = [
        Outcome("a.svg", "a.ngc", DRAWING, 0.5),
        Outcome("b.svg", "", None, 0.1, "body.document: not well-formed XML"),
        Outcome("c.json", "c.dxf", None, 0.2),
    ]
    lines = _text(table(outcomes, "batch")).splitlines()
    row = {line.split()[0]: line for line in lines if line.strip()[:2] in ("a.", "b.", "c.")}
    assert "48" in row["a.svg"]
    assert "failed: body.document: not well-formed XML" in row["b.svg"]
    assert row["c.json"].split() == ["c.json", "0.20", "s", "c.dxf"]
