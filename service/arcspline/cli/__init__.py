"""The command line ``arcspline`` (docs/cli.md): SVG and DXF drawings, SVG path data and
JSON requests approximated into G-code, DXF, SVG or JSON; many files at once; a preview;
the server itself.

Every command works through :mod:`arcspline.client`: without ``--server`` the service's own
app runs in this process (:func:`arcspline.client.local_client`), with ``--server URL`` the
same requests go to a running service, so both give the same bytes.

Modules: ``app`` (the commands), ``options`` (what the options change in a request),
``tooling`` (the offset and machining options), ``inputs`` (INPUT to request), ``work`` (a
request to its output, through a client), ``outputs`` (formats, files), ``summary`` (the
tables), ``batch`` (many files), ``errors`` (one line per failure, exit codes).
"""

from __future__ import annotations


def main() -> None:
    """The ``arcspline`` console script. Only typer is imported to read the command line;
    the app, the HTTP stack and rich load when a command needs them, so ``--version`` and
    ``--help`` answer at once."""
    from .app import app

    app()
