"""The garbage-collector policy while engines evaluate a drive."""

from __future__ import annotations

import gc
from contextlib import contextmanager
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from collections.abc import Iterator

__all__ = ["ENGINE_GC_THRESHOLD", "engine_gc"]

#: Young-generation threshold of Python's cyclic garbage collector while a drive is
#: evaluated (CPython's default is 700). Scene creation keeps tens of thousands of small
#: per-frame memo objects alive for one frame, none in reference cycles: at 700 the
#: collector runs mid-frame hundreds of times per chunk, promotes the memos and then
#: sweeps the whole heap, about 0.9 ms of a 6 ms frame (Town01, 50 objects; measured
#: with ``gc.callbacks``). At this threshold it runs only when 50,000 container objects
#: have accumulated: a few times per drive.
ENGINE_GC_THRESHOLD = 50_000


@contextmanager
def engine_gc() -> Iterator[None]:
    """Raise the young-generation GC threshold to :data:`ENGINE_GC_THRESHOLD` inside.

    Only the threshold changes (never lowered; the collector stays on, cyclic garbage is
    still collected). On exit the young generation is collected once, here rather than
    at the next allocation after it (so the drive pays for it and a benchmark times
    it), and the threshold is restored.
    """
    old = gc.get_threshold()
    gc.set_threshold(max(old[0], ENGINE_GC_THRESHOLD), *old[1:])
    try:
        yield
    finally:
        if gc.isenabled():
            gc.collect(0)
        gc.set_threshold(*old)
