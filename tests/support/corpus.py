"""The shared corpus of real drawings, read in place: ``$SHARED_CORPUS`` or the
``shared/corpus`` folder beside this checkout. (Not an ``ARCSPLINE_`` variable: the service
refuses unknown ones, and the tests start it.) Absent, a corpus test skips saying so, and
fails in CI, where the corpus is always there."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
ENV = "SHARED_CORPUS"


def corpus_dir() -> Path | None:
    """The corpus folder (with ``svg/`` and ``dxf/``), or ``None`` when it is not here."""
    candidates = [Path(os.environ[ENV])] if os.environ.get(ENV) else []
    candidates += [ROOT.parent / "shared" / "corpus", Path("/work/shared/corpus")]
    return next((p for p in candidates if (p / "svg").is_dir() and (p / "dxf").is_dir()), None)


def corpus_files(kind: str) -> list[Path]:
    """Every ``kind`` (``svg`` or ``dxf``) file of the corpus; skips (fails in CI) without it."""
    where = corpus_dir()
    if where is None:
        reason = f"the shared corpus (${ENV} or ../shared/corpus) is not beside this checkout"
        if os.environ.get("CI") == "true":
            pytest.fail(f"{reason}, and CI must have it")
        pytest.skip(reason)
    return sorted(p for p in (where / kind).iterdir() if p.suffix.lower() == f".{kind}")
