"""What the command line's tests share: the runner (typer's ``CliRunner``, stdout and stderr
apart, a wide console so that tables do not fold), the golden inputs in ``data/``, and the
test drawings of ``tests/data``."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

import pytest
from typer.testing import CliRunner, Result

from arcspline.cli.app import app

DATA = Path(__file__).parent / "data"
SPIRAL = DATA / "spiral.json"
PATH = DATA / "path.json"
DRAWING_SVG = Path(__file__).parents[1] / "data" / "svg" / "rounded_rect.svg"
DRAWING_DXF = Path(__file__).parents[1] / "data" / "dxf" / "bulge_lwpolyline.dxf"

Invoke = Callable[..., Result]


@pytest.fixture
def cli() -> Invoke:
    """``cli("approx", "x.svg", ..., input=b"...")``: the app in this process."""
    runner = CliRunner(env={"COLUMNS": "200"})

    def invoke(*args: str, input: bytes | str | None = None) -> Result:
        return runner.invoke(app, list(args), input=input)

    return invoke
