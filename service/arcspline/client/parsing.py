"""Reading large answers into the response models fast (docs/performance.md "Small requests
fast (issue 19)").

A batch's answer is big: 1,000 spirals at 1e-5 are 24 MB of JSON and some twenty Python
objects a segment (the model, its fields, its points), a million objects in all. pydantic
validates the bytes in Rust (``model_validate_json``: no intermediate dicts), but CPython's
cyclic garbage collector, triggered by every 700 new container objects, walks the young
objects each time and, every so often, every object the client already holds: more than
half of the reading time (measured: 15.4 µs a segment with it, 6.5 µs without). The models
hold no reference cycles, so reference counting frees them without the collector; it is
paused while a batch is read.
"""

from __future__ import annotations

import gc
import threading
from collections.abc import Iterator
from contextlib import contextmanager

_lock = threading.Lock()
#: Readers inside :func:`gc_paused` now, and whether the collector was on before the first.
_readers = 0
_was_enabled = False


@contextmanager
def gc_paused() -> Iterator[None]:
    """The cyclic garbage collector off for the block, on again after the last of the
    blocks that overlap (threads of one client read chunks at once); left off if it was
    off before the first."""
    global _readers, _was_enabled
    with _lock:
        if _readers == 0:
            _was_enabled = gc.isenabled()
            gc.disable()
        _readers += 1
    try:
        yield
    finally:
        with _lock:
            _readers -= 1
            if _readers == 0 and _was_enabled:
                gc.enable()
