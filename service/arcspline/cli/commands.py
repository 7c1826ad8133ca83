"""What each command does once its options are read: INPUT to request, the request through
a client (the app in this process, or ``--server``), the output written, the table shown.
Everything fallible happens before anything is written."""

from __future__ import annotations

from pathlib import Path

import typer

from .errors import stderr
from .inputs import resolve
from .options import Format, Overrides
from .outputs import STDOUT, check_writable, format_of, write
from .summary import Outcome, details, table, warnings
from .work import connect, picture, produce


async def approximate_input(
    argument: str,
    overrides: Overrides,
    output: Path | None,
    fmt: Format | None,
    server: str | None,
    quiet: bool,
) -> Outcome:
    """``approx``: one INPUT, its jobs run in a thread of this process when local."""
    source = resolve(argument, typer.get_binary_stream("stdin"))
    fmt = format_of(output, fmt, source.output or "json")
    request = overrides.apply(source.request, source.kind)
    check_writable(output, source.name)
    async with connect(server, 0, 2) as client:
        product = await produce(client, source.kind, request, fmt, stats=not quiet)
    write(product.content, output)
    where = "stdout" if output is None or output == STDOUT else str(output)
    return Outcome(source.name, where, product.summary, product.seconds)


def report(outcome: Outcome) -> None:
    """The summary table of one INPUT, and a drawing's warnings."""
    console = stderr()
    console.print(details(outcome, "arcspline approx"))
    if outcome.summary is not None:
        for line in warnings(outcome.summary):
            console.print(line)


async def preview_input(
    argument: str, overrides: Overrides, output: Path | None, server: str | None
) -> None:
    """``preview``: the picture of one INPUT's approximation."""
    source = resolve(argument, typer.get_binary_stream("stdin"))
    request = overrides.apply(source.request, source.kind)
    check_writable(output, source.name)
    async with connect(server, 0, 1) as client:
        content = await picture(client, request)
    write(content, output)


async def run_batch(
    patterns: list[str],
    overrides: Overrides,
    out_dir: Path | None,
    fmt: Format | None,
    jobs: int | None,
    server: str | None,
    debug: bool,
) -> bool:
    """``batch``: every file, then the table; whether any failed."""
    from arcspline.settings import available_cpus

    from .batch import expand, plan
    from .batch import run as run_files

    fmt = fmt or ("gcode" if overrides.asks_for_program else "json")
    files = expand(patterns)
    batch = plan(files, out_dir, fmt)
    if out_dir is not None:
        out_dir.mkdir(parents=True, exist_ok=True)
    outcomes = await run_files(batch, overrides, server, jobs or available_cpus(), debug)
    failed = sum(o.error is not None for o in outcomes)
    title = f"arcspline batch: {len(outcomes) - failed} written, {failed} failed"
    stderr().print(table(outcomes, title))
    return failed > 0
