"""Where a download goes: a file that appears only once complete."""

from __future__ import annotations

import contextlib
from collections.abc import Iterator
from pathlib import Path
from typing import BinaryIO


@contextlib.contextmanager
def atomic_writer(to: Path | BinaryIO) -> Iterator[BinaryIO]:
    """``to`` itself (an open binary stream), or a new file at ``to`` that appears only once
    complete: written beside it and renamed, so a failure leaves no partial file and an
    older file at ``to`` stays as it was."""
    if not isinstance(to, Path):
        yield to
        return
    partial = to.with_name(f".{to.name}.partial")
    try:
        with partial.open("wb") as file:
            yield file
        partial.replace(to)
    finally:
        partial.unlink(missing_ok=True)
