"""Fetching rs274 where the machine cannot (tests/support/rs274.py, scripts/fetch-rs274.sh):
the G-code tests skip with the reason, and fail only in CI."""

from __future__ import annotations

import os
import shutil
from pathlib import Path

import pytest

from tests.support.rs274 import provide

FETCH = Path(__file__).resolve().parents[2] / "scripts" / "fetch-rs274.sh"
#: What the script runs before it looks for apt-get (and bash, which runs it).
TOOLS = ("bash", "dirname", "uname", "mkdir", "flock")


@pytest.fixture
def without_apt(tmp_path: Path) -> dict[str, str]:
    """An environment like a machine without Debian's package tools: a PATH with only the
    tools the script needs before it looks for them, and an empty cache."""
    bin_dir = tmp_path / "bin"
    bin_dir.mkdir()
    for tool in TOOLS:
        found = shutil.which(tool)
        assert found, f"{tool} is needed to run this test"
        (bin_dir / tool).symlink_to(found)
    return {
        "PATH": str(bin_dir),
        "HOME": str(tmp_path),
        "RS274_CACHE_DIR": str(tmp_path / "cache"),
    }


def test_without_apt_the_tests_skip_with_the_reason(without_apt: dict[str, str]) -> None:
    with pytest.raises(pytest.skip.Exception, match="needs apt-get and dpkg"):
        provide(FETCH, ci=False, env=without_apt)


def test_without_apt_in_ci_the_tests_fail(without_apt: dict[str, str]) -> None:
    with pytest.raises(pytest.fail.Exception, match="needs apt-get and dpkg"):
        provide(FETCH, ci=True, env=without_apt)


def test_a_broken_cache_fails_even_outside_ci(tmp_path: Path) -> None:
    """Not an unavailable machine but a broken setup: a cache that cannot be created."""
    blocked = tmp_path / "file"
    blocked.write_text("")
    env = {**os.environ, "RS274_CACHE_DIR": str(blocked / "cache")}
    with pytest.raises(pytest.fail.Exception, match="cannot create the cache directory"):
        provide(FETCH, ci=False, env=env)
