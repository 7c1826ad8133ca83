"""Fixtures of the G-code tests: LinuxCNC's ``rs274``, fetched and cached by its script."""

from __future__ import annotations

import subprocess
from pathlib import Path

import pytest

from .rs274 import Rs274

ROOT = Path(__file__).resolve().parents[3]
FETCH = ROOT / "scripts" / "fetch-rs274.sh"


@pytest.fixture(scope="session")
def rs274() -> Rs274:
    """The interpreter, fetched once per machine (the script caches it and takes a lock, so
    the xdist workers of one run share a single download)."""
    done = subprocess.run(
        ["bash", str(FETCH)], capture_output=True, text=True, timeout=600, check=False
    )
    if done.returncode != 0:
        pytest.fail(f"{FETCH.name} could not provide rs274:\n{done.stderr}", pytrace=False)
    return Rs274(Path(done.stdout.strip().splitlines()[-1]))
