"""A real server: ``python -m arcspline`` in a subprocess, reached over HTTP."""

from __future__ import annotations

from collections.abc import Iterator

import pytest

from tests.support.server import Server, running_server


@pytest.fixture(scope="module")
def server(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Server]:
    """A server with a pool of two workers, shared by a module's tests."""
    with running_server(tmp_path_factory.mktemp("server"), pool_size=2) as server:
        yield server
