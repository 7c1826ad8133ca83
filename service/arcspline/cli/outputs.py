"""Where an output goes and in what format: the format by ``--format``, else by the suffix
of ``-o``; the bytes to stdout, or into a file that appears only once complete (written
beside it, then renamed: a failure leaves no partial file, and an older file stays as it
was)."""

from __future__ import annotations

from pathlib import Path

import typer

from .errors import CommandError, UsageError
from .options import Format

#: Output suffixes and their formats.
SUFFIXES: dict[str, Format] = {
    ".ngc": "gcode",
    ".gcode": "gcode",
    ".nc": "gcode",
    ".dxf": "dxf",
    ".svg": "svg",
    ".json": "json",
}
#: The suffix each format is written with when the command names the file: a format that
#: is also an input (JSON, SVG, DXF) is marked ``.arcs``, so that a later batch over the
#: same folder does not take its own outputs for inputs.
EXTENSIONS: dict[Format, str] = {
    "gcode": ".ngc",
    "dxf": ".arcs.dxf",
    "svg": ".arcs.svg",
    "json": ".arcs.json",
}
OWN_OUTPUTS = tuple(suffix for suffix in EXTENSIONS.values() if suffix.startswith(".arcs."))
STDOUT = Path("-")


def format_of(output: Path | None, given: Format | None, default: Format) -> Format:
    """``given``, else the format ``output``'s suffix names, else ``default`` (stdout)."""
    if given is not None:
        return given
    if output is None or output == STDOUT:
        return default
    found = SUFFIXES.get(output.suffix.lower())
    if found is None:
        known = " ".join(SUFFIXES)
        raise UsageError(f"{output.name}: its suffix is none of {known}; give --format", "-o")
    return found


def check_writable(output: Path | None, source: str | None = None) -> None:
    """Fail before the work when ``output`` cannot be written (no such folder), or would
    replace ``source``, the input file."""
    if output is None or output == STDOUT:
        return
    if source is not None and Path(source).is_file() and output.resolve() == Path(source).resolve():
        raise UsageError(f"{output} is the input: the output would replace it", "-o")
    parent = output.parent
    if not parent.is_dir():
        raise CommandError(f"no such folder: {parent} (for {output})")
    if output.is_dir():
        raise CommandError(f"{output} is a folder")


def write(content: bytes, output: Path | None) -> None:
    """``content`` to ``output`` (whole or not at all), or to stdout."""
    if output is None or output == STDOUT:
        stream = typer.get_binary_stream("stdout")
        stream.write(content)
        stream.flush()
        return
    from arcspline.client import atomic_writer

    with atomic_writer(output) as file:
        file.write(content)


def output_path(source: Path, out_dir: Path | None, fmt: Format, keep_suffix: bool) -> Path:
    """Where a batch writes ``source``'s output: in ``out_dir`` (else beside it), named by
    its stem (with its suffix too when ``keep_suffix``, so ``a.svg`` and ``a.dxf`` or
    ``a.json`` and its own output do not meet)."""
    name = source.name if keep_suffix else source.stem
    return (out_dir or source.parent) / f"{name}{EXTENSIONS[fmt]}"
