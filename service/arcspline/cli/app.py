"""The commands: ``approx``, ``batch``, ``preview``, ``serve`` (docs/cli.md).

Each command reads its options into :class:`~arcspline.cli.options.Overrides` and hands
its work to :mod:`~arcspline.cli.commands`, imported only then (with the app and the HTTP
stack), so that ``--help`` and ``--version`` stay fast. No ``from __future__ import
annotations`` here: typer reads the annotations at run time.
"""

from pathlib import Path
from typing import Annotated

import typer

from .errors import guard, run
from .options import (
    ArcFormat,
    ChooseStart,
    Comments,
    CutZ,
    Decimals,
    FeedRate,
    Format,
    FormatOption,
    JoinTolerance,
    Layers,
    LineNumbers,
    MaxRadius,
    MinArcLength,
    Order,
    OutputFile,
    Overrides,
    PlungeFeedRate,
    Quiet,
    SafeZ,
    Server,
    SourceUnitsOption,
    StepDown,
    Strategy,
    Tolerance,
    UnitsOption,
)
from .tooling import (
    CompensationOption,
    CutOption,
    DirectionOption,
    JoinOption,
    LeadRadius,
    MitreLimit,
    OffsetOption,
    Ramp,
    SideOption,
    TabHeight,
    TabsOption,
    TabWidth,
    ToolDiameter,
    Tooling,
    ToolNumber,
)

app = typer.Typer(
    name="arcspline",
    help="Arc splines for CNC tool paths: SVG and DXF drawings, SVG path data and JSON "
    "requests approximated by arcs within a tolerance, as G-code, DXF, SVG or JSON. "
    "Computed here, or by a running service with --server.",
    no_args_is_help=True,
    add_completion=False,
    pretty_exceptions_show_locals=False,
)

InputArgument = Annotated[
    str,
    typer.Argument(
        metavar="INPUT",
        help="An SVG or DXF file, a JSON request (file or inline), SVG path data "
        "('M 0 0 C 10 0 20 10 30 30'), or - for stdin.",
        show_default=False,
    ),
]


def _version(value: bool) -> None:
    if value:
        from arcspline import __version__

        typer.echo(f"arcspline {__version__}")
        raise typer.Exit()


@app.callback()
def root(
    ctx: typer.Context,
    version: Annotated[
        bool,
        typer.Option(
            "--version", callback=_version, is_eager=True, help="Print the version and exit."
        ),
    ] = False,
    debug: Annotated[
        bool, typer.Option("--debug", help="Show the traceback of a failure.")
    ] = False,
) -> None:
    """Exit status: 0 done, 1 the work failed (one line says why), 2 a usage error."""
    ctx.obj = debug


@app.command()
def approx(
    ctx: typer.Context,
    source: InputArgument,
    tolerance: Tolerance = None,
    strategy: Strategy = None,
    units: UnitsOption = None,
    feed_rate: FeedRate = None,
    decimals: Decimals = None,
    arc_format: ArcFormat = None,
    line_numbers: LineNumbers = None,
    comments: Comments = None,
    safe_z: SafeZ = None,
    cut_z: CutZ = None,
    plunge_feed_rate: PlungeFeedRate = None,
    step_down: StepDown = None,
    min_arc_length: MinArcLength = None,
    max_radius: MaxRadius = None,
    layers: Layers = None,
    source_units: SourceUnitsOption = None,
    join_tolerance: JoinTolerance = None,
    order: Order = None,
    choose_start: ChooseStart = None,
    offset: OffsetOption = None,
    side: SideOption = None,
    join: JoinOption = None,
    mitre_limit: MitreLimit = None,
    tool_diameter: ToolDiameter = None,
    cut: CutOption = None,
    direction: DirectionOption = None,
    lead_radius: LeadRadius = None,
    ramp: Ramp = None,
    tabs: TabsOption = None,
    tab_width: TabWidth = None,
    tab_height: TabHeight = None,
    compensation: CompensationOption = None,
    tool_number: ToolNumber = None,
    output: OutputFile = None,
    fmt: FormatOption = None,
    server: Server = None,
    quiet: Quiet = False,
) -> None:
    """Approximate one INPUT: the result to -o (or stdout), a summary table to stderr.

    The format follows --format, else the suffix of -o, else JSON.

    Example: arcspline approx part.svg -t 0.01 --feed-rate 600 --safe-z 5 --cut-z -1 -o part.ngc
    """
    tooling = Tooling.of(
        offset, side, join, mitre_limit, tool_diameter, cut, direction, lead_radius, ramp,
        tabs, tab_width, tab_height, compensation, tool_number,
    )  # fmt: skip
    overrides = Overrides.of(
        tolerance, strategy, units, feed_rate=feed_rate, decimals=decimals,
        arc_format=arc_format, line_numbers=line_numbers, comments=comments, safe_z=safe_z,
        cut_z=cut_z, plunge_feed_rate=plunge_feed_rate, step_down=step_down,
        min_arc_length=min_arc_length, max_radius=max_radius, layers=layers,
        source_units=source_units, join_tolerance=join_tolerance, order=order,
        choose_start=choose_start, tooling=tooling,
    )  # fmt: skip
    from .commands import approximate_input, report

    outcome = run(approximate_input(source, overrides, output, fmt, server, quiet), ctx.obj)
    if not quiet:
        report(outcome)


@app.command()
def batch(
    ctx: typer.Context,
    sources: Annotated[
        list[str],
        typer.Argument(
            metavar="DIR_OR_GLOB...",
            help="Folders (their .svg, .dxf and .json files), globs ('parts/**/*.dxf') or files.",
            show_default=False,
        ),
    ],
    tolerance: Tolerance = None,
    strategy: Strategy = None,
    units: UnitsOption = None,
    feed_rate: FeedRate = None,
    decimals: Decimals = None,
    arc_format: ArcFormat = None,
    line_numbers: LineNumbers = None,
    comments: Comments = None,
    safe_z: SafeZ = None,
    cut_z: CutZ = None,
    plunge_feed_rate: PlungeFeedRate = None,
    step_down: StepDown = None,
    min_arc_length: MinArcLength = None,
    max_radius: MaxRadius = None,
    layers: Layers = None,
    source_units: SourceUnitsOption = None,
    join_tolerance: JoinTolerance = None,
    order: Order = None,
    choose_start: ChooseStart = None,
    offset: OffsetOption = None,
    side: SideOption = None,
    join: JoinOption = None,
    mitre_limit: MitreLimit = None,
    tool_diameter: ToolDiameter = None,
    cut: CutOption = None,
    direction: DirectionOption = None,
    lead_radius: LeadRadius = None,
    ramp: Ramp = None,
    tabs: TabsOption = None,
    tab_width: TabWidth = None,
    tab_height: TabHeight = None,
    compensation: CompensationOption = None,
    tool_number: ToolNumber = None,
    out_dir: Annotated[
        Path | None,
        typer.Option(
            help="Write the outputs here (made if missing); default: beside each input.",
            file_okay=False,
            show_default=False,
            rich_help_panel="Where and how",
        ),
    ] = None,
    fmt: Annotated[
        Format | None,
        typer.Option(
            "--format",
            "-f",
            help="json, gcode, dxf or svg (default: gcode with --feed-rate, else json).",
            show_default=False,
            rich_help_panel="Where and how",
        ),
    ] = None,
    jobs: Annotated[
        int | None,
        typer.Option(
            "--jobs",
            "-j",
            min=1,
            help="Files at once (default: the CPUs available).",
            show_default=False,
            rich_help_panel="Where and how",
        ),
    ] = None,
    server: Server = None,
) -> None:
    """Approximate many files in parallel, with a progress bar and a final table.

    Each output goes to --out-dir (or beside its input) as <name>.ngc, .dxf, .svg or .json.
    A file that fails is named with its reason, the others are still written, and the exit
    status is 1.

    Example: arcspline batch parts/ -t 0.01 --feed-rate 600 --out-dir programs/
    """
    tooling = Tooling.of(
        offset, side, join, mitre_limit, tool_diameter, cut, direction, lead_radius, ramp,
        tabs, tab_width, tab_height, compensation, tool_number,
    )  # fmt: skip
    overrides = Overrides.of(
        tolerance, strategy, units, feed_rate=feed_rate, decimals=decimals,
        arc_format=arc_format, line_numbers=line_numbers, comments=comments, safe_z=safe_z,
        cut_z=cut_z, plunge_feed_rate=plunge_feed_rate, step_down=step_down,
        min_arc_length=min_arc_length, max_radius=max_radius, layers=layers,
        source_units=source_units, join_tolerance=join_tolerance, order=order,
        choose_start=choose_start, tooling=tooling,
    )  # fmt: skip
    from .commands import run_batch

    failed = run(run_batch(sources, overrides, out_dir, fmt, jobs, server, ctx.obj), ctx.obj)
    if failed:
        raise typer.Exit(1)


@app.command()
def preview(
    ctx: typer.Context,
    source: InputArgument,
    tolerance: Tolerance = None,
    strategy: Strategy = None,
    units: UnitsOption = None,
    layers: Layers = None,
    source_units: SourceUnitsOption = None,
    join_tolerance: JoinTolerance = None,
    order: Order = None,
    choose_start: ChooseStart = None,
    offset: OffsetOption = None,
    side: SideOption = None,
    join: JoinOption = None,
    mitre_limit: MitreLimit = None,
    tool_diameter: ToolDiameter = None,
    cut: CutOption = None,
    direction: DirectionOption = None,
    lead_radius: LeadRadius = None,
    ramp: Ramp = None,
    tabs: TabsOption = None,
    tab_width: TabWidth = None,
    tab_height: TabHeight = None,
    compensation: CompensationOption = None,
    tool_number: ToolNumber = None,
    output: OutputFile = None,
    server: Server = None,
) -> None:
    """Draw INPUT's approximation as an SVG picture, to -o (or stdout).

    The arcs and their centres, the deviation magnified within the tolerance band; a
    drawing's toolpaths numbered in cutting order.

    Example: arcspline preview part.dxf -t 0.01 -o preview.svg
    """
    tooling = Tooling.of(
        offset, side, join, mitre_limit, tool_diameter, cut, direction, lead_radius, ramp,
        tabs, tab_width, tab_height, compensation, tool_number,
    )  # fmt: skip
    overrides = Overrides.of(
        tolerance, strategy, units, layers=layers, source_units=source_units,
        join_tolerance=join_tolerance, order=order, choose_start=choose_start, tooling=tooling,
    )  # fmt: skip
    from .commands import preview_input

    run(preview_input(source, overrides, output, server), ctx.obj)


@app.command()
def serve(
    ctx: typer.Context,
    host: Annotated[
        str | None,
        typer.Option(help="Address (default: ARCSPLINE_HOST, else 127.0.0.1).", show_default=False),
    ] = None,
    port: Annotated[
        int | None,
        typer.Option(help="Port (default: ARCSPLINE_PORT, else 8000).", show_default=False),
    ] = None,
) -> None:
    """Serve the HTTP API, as python -m arcspline does.

    The settings are those of the environment (ARCSPLINE_*, docs/http-api.md); SIGTERM
    drains the requests in flight and exits 0.
    """
    from arcspline.__main__ import serve as serve_api

    with guard(ctx.obj):  # a bad setting is one line too
        serve_api(host, port)
