"""Where a download goes: whole, or not at all."""

from __future__ import annotations

import contextlib
import os
import shutil
import tempfile
import uuid
from collections.abc import Iterator
from pathlib import Path
from typing import BinaryIO, TypeAlias

#: A file to write (its path), or a binary stream the caller opened.
Destination: TypeAlias = str | os.PathLike[str] | BinaryIO
#: How much of a download into a stream is kept in memory before it spills to a file.
SPOOL_BYTES = 8 * 1024 * 1024


@contextlib.contextmanager
def atomic_writer(to: Destination) -> Iterator[BinaryIO]:
    """A file to write ``to`` into, that reaches ``to`` only once complete.

    A path gets a temporary file beside it (a name of its own, so two writers never
    share one), renamed over it at the end: a failure leaves no partial file, and an older
    file stays as it was. A stream gets the bytes only at the end too (held in a spooled
    temporary file meanwhile), so a download tried again never writes twice into it.
    """
    if isinstance(to, str | os.PathLike):
        target = Path(to)
        partial = target.with_name(f".{target.name}.{uuid.uuid4().hex}.partial")
        try:
            with partial.open("xb") as file:
                yield file
            partial.replace(target)
        finally:
            partial.unlink(missing_ok=True)
        return
    with tempfile.SpooledTemporaryFile(SPOOL_BYTES) as spool:
        yield spool  # type: ignore[misc]
        spool.seek(0)
        shutil.copyfileobj(spool, to)
