"""Many files at once: each read, approximated and written on its own through one shared
client, ``jobs`` at a time, with a progress bar; a file that fails is reported with its
reason and the others still finish.

Locally the client's app has a pool of ``jobs`` worker processes (never more than there
are files), so the files are computed in parallel; with ``--server`` the same requests go
to the service, ``jobs`` in flight.
"""

from __future__ import annotations

import asyncio
import glob
import time
from collections import Counter
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeElapsedColumn

from arcspline.client import AsyncClient

from .errors import CommandError, UsageError, describe, stderr
from .inputs import SUFFIXES, read_file
from .options import Format, Overrides
from .outputs import OWN_OUTPUTS, output_path, write
from .summary import Outcome
from .work import connect, produce


@dataclass(frozen=True)
class Plan:
    """What a batch does: its files and where each one's output goes."""

    files: list[Path]
    outputs: dict[Path, Path]
    fmt: Format


def expand(patterns: Sequence[str]) -> list[Path]:
    """The files named: a folder's SVG, DXF and JSON files, a glob's matches (``**``
    recurses), or a file itself; in the order given, each once. A folder or a glob leaves
    out this command's own outputs (``*.arcs.json``, ``.svg``, ``.dxf``)."""
    found: dict[Path, None] = {}
    for pattern in patterns:
        path = Path(pattern)
        if path.is_file():
            matches = [path]
        else:
            if path.is_dir():
                matches = [p for p in sorted(path.iterdir()) if p.suffix.lower() in SUFFIXES]
            else:
                matches = [Path(p) for p in sorted(glob.glob(pattern, recursive=True))]
                matches = [p for p in matches if p.is_file()]
            matches = [p for p in matches if not p.name.lower().endswith(OWN_OUTPUTS)]
        if not matches:
            raise CommandError(f"no files in {pattern}")
        found.update(dict.fromkeys(matches))
    return list(found)


def plan(files: list[Path], out_dir: Path | None, fmt: Format) -> Plan:
    """Each file's output: named by its stem, or by its whole name where two inputs would
    share one output, or an output would replace an input."""
    inputs = {f.resolve() for f in files}
    by_stem = Counter(output_path(f, out_dir, fmt, False).resolve() for f in files)
    outputs = {}
    for f in files:
        target = output_path(f, out_dir, fmt, False)
        if by_stem[target.resolve()] > 1 or target.resolve() in inputs:
            target = output_path(f, out_dir, fmt, True)
        outputs[f] = target
    clashes = Counter(t.resolve() for t in outputs.values())
    shared = [f for f, t in outputs.items() if clashes[t.resolve()] > 1]
    if shared:
        names = ", ".join(str(f) for f in shared)
        raise UsageError(f"these files would write the same output: {names}", "--out-dir")
    return Plan(files, outputs, fmt)


async def run(
    batch: Plan, overrides: Overrides, server: str | None, jobs: int, debug: bool
) -> list[Outcome]:
    """Every file of ``batch``, ``jobs`` at a time; one :class:`Outcome` per file, in order."""
    workers = min(jobs, len(batch.files))
    async with connect(server, workers, jobs) as client:
        if server is not None:
            await client.health()  # an unreachable server is one error, not one per file
        slots = asyncio.Semaphore(jobs)
        columns = (
            TextColumn("{task.description}"),
            BarColumn(),
            MofNCompleteColumn(),
            TimeElapsedColumn(),
        )
        console = stderr()
        # On a terminal only: in a log, the table says it all.
        with Progress(
            *columns, console=console, transient=True, disable=not console.is_terminal
        ) as progress:
            task = progress.add_task("approximating", total=len(batch.files))

            async def one(file: Path) -> Outcome:
                async with slots:
                    outcome = await _file(client, file, batch, overrides, debug)
                progress.advance(task)
                return outcome

            return list(await asyncio.gather(*(one(f) for f in batch.files)))


async def _file(
    client: AsyncClient, file: Path, batch: Plan, overrides: Overrides, debug: bool
) -> Outcome:
    """One file, start to finish; any failure becomes its outcome."""
    target = batch.outputs[file]
    started = time.perf_counter()
    try:
        source = read_file(file)
        request = overrides.apply(source.request, source.kind)
        product = await produce(client, source.kind, request, batch.fmt)
        write(product.content, target)
    except Exception as error:
        if debug:
            stderr().print_exception()
        return Outcome(str(file), "", None, time.perf_counter() - started, describe(error))
    return Outcome(str(file), str(target), product.summary, product.seconds)
