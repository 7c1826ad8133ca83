"""The installed console script ``arcspline`` (``[project.scripts]``), as a user runs it: a
program that LinuxCNC's ``rs274`` accepts, a traceback only under ``--debug``, and
``--version``/``--help`` without loading the app."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

from tests.cli.conftest import SPIRAL
from tests.support.rs274 import Rs274

SCRIPT = Path(sys.executable).parent / "arcspline"


def _run(*args: str, cwd: Path) -> subprocess.CompletedProcess[str]:
    if not SCRIPT.exists():
        pytest.fail(f"{SCRIPT} is missing: pip install --no-deps --no-build-isolation -e .")
    return subprocess.run(
        [str(SCRIPT), *args], cwd=cwd, capture_output=True, text=True, timeout=120, check=False
    )


def test_the_installed_command_writes_a_program_rs274_accepts(tmp_path: Path, rs274: Rs274) -> None:
    done = _run("approx", str(SPIRAL), "-t", "1e-5", "--feed-rate", "600", "--safe-z", "5",
                "--cut-z", "-1", "-o", "spiral.ngc", cwd=tmp_path)  # fmt: skip
    assert done.returncode == 0, done.stderr
    verdict = rs274.run((tmp_path / "spiral.ngc").read_text())
    assert verdict.accepted, verdict.describe()
    assert "spiral.ngc" in done.stderr
    assert "max deviation" in done.stderr


def test_debug_shows_the_traceback(tmp_path: Path) -> None:
    done = _run("--debug", "approx", str(SPIRAL), "-t", "0", cwd=tmp_path)
    assert done.returncode == 1
    assert "Traceback" in done.stderr
    assert "ServiceError" in done.stderr


def test_version_and_help_load_neither_the_app_nor_the_http_stack(tmp_path: Path) -> None:
    """``import arcspline`` (the package's own ``__init__``) loads the geometry core with
    numpy before any command line code runs; beyond that, nothing."""
    code = (
        "import sys\n"
        "from arcspline.cli import main\n"
        "for argv in (['--version'], ['--help'], ['approx', '--help']):\n"
        "    sys.argv = ['arcspline', *argv]\n"
        "    try:\n"
        "        main()\n"
        "    except SystemExit as done:\n"
        "        assert done.code in (0, None), done.code\n"
        "heavy = ('fastapi', 'starlette', 'pydantic', 'httpx', 'uvicorn', 'ezdxf', 'orjson')\n"
        "ours = ('arcspline.api', 'arcspline.client', 'arcspline.worker', 'arcspline.drawings')\n"
        "print(sorted(m for m in sys.modules if m.split('.')[0] in heavy or m.startswith(ours)))\n"
    )
    done = subprocess.run(
        [sys.executable, "-c", code], cwd=tmp_path, capture_output=True, text=True,
        timeout=60, check=False,
    )  # fmt: skip
    assert done.returncode == 0, done.stderr
    assert done.stdout.startswith("arcspline ")
    assert "approx" in done.stdout
    assert done.stdout.splitlines()[-1] == "[]"
