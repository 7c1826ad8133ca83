"""A real server for the client's tests: ``python -m arcspline`` on a free port."""

from __future__ import annotations

from collections.abc import Iterator

import pytest

from tests.support.server import Server, running_server


@pytest.fixture(scope="package")
def server(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Server]:
    """A server with the default limits and a pool of two workers."""
    with running_server(tmp_path_factory.mktemp("server"), pool_size=2) as server:
        yield server
