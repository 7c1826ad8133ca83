"""The warm-up the forkserver runs before it forks workers covers every kind of job."""

from __future__ import annotations

from typing import Any

import pytest

from arcspline.geometry import fit
from arcspline.outputs import WRITERS
from arcspline.worker import pool, warm


def test_the_forkserver_preloads_the_warm_up() -> None:
    assert "arcspline.worker.warm" in pool.PRELOAD


def test_the_warm_up_runs_every_strategy_and_every_writer(monkeypatch: pytest.MonkeyPatch) -> None:
    used: set[str] = set()

    def counting(name: str, run: Any) -> Any:
        def wrapper(*args: Any, **kwargs: Any) -> Any:
            used.add(name)
            return run(*args, **kwargs)

        return wrapper

    for name, run in list(fit.STRATEGIES.items()):
        monkeypatch.setitem(fit.STRATEGIES, name, counting(f"strategy {name}", run))
    for name, writer in list(WRITERS.items()):
        monkeypatch.setattr(writer, "write", counting(f"writer {name}", writer.write))
    warm.warm()
    expected = {f"strategy {n}" for n in fit.STRATEGIES} | {f"writer {n}" for n in WRITERS}
    assert used == expected
