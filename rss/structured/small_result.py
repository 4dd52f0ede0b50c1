"""Results of the small-frame path whose arrays are built when first read.

:func:`rss.structured.engine.check_frame` evaluates a small frame row by row
(:mod:`rss.structured.small`): every verdict, the proper response and the memory after the
frame are computed in the call, as Python values. Turning them into the ~45 ``(C,)``
arrays of a :class:`FrameResult` and the six of an :class:`RssMemory` costs more than the
evaluation itself at a few constellations, and a monitor usually reads only the proper
response and the dangerous flags. :class:`SmallMemory` (here) and
``engine.SmallFrameResult`` therefore build each field on its first read (and keep it):
reading one gives the same array the batched engine returns.

A :class:`SmallMemory` handed back to the next call is read from its entries by key (the
dict the row path built) without building its arrays.
"""

from __future__ import annotations

from typing import Any

from rss.structured.memory import RssMemory
from rss.structured.small_arrays import memory_columns

__all__ = ["SmallMemory"]

_FIELDS = (
    "ego_id",
    "object_id",
    "constellation_type",
    "lon_safe",
    "lat_safe",
    "intersection_state",
)


class SmallMemory(RssMemory):
    """An :class:`RssMemory` of ``M >= 1`` entries whose arrays are built on first read.

    Attributes:
        before: The entries by key (``small_output.recall`` layout), for the next frame.
    """

    before: dict[tuple[int, int, int], tuple[bool, bool, int]]

    def __init__(self, after: dict[tuple[int, int, int], tuple[bool, bool, int]]) -> None:  # noqa: D107
        self.__dict__["before"] = after  # frozen: no generated ``__setattr__`` per field

    def __getattr__(self, name: str) -> Any:
        """Build the six arrays on the first read of one of them."""
        if name not in _FIELDS:
            raise AttributeError(name)
        for field, value in zip(_FIELDS, memory_columns(self.before), strict=True):
            object.__setattr__(self, field, value)
        return self.__dict__[name]

    @property
    def size(self) -> int:
        """Number of remembered constellations ``M``."""
        return len(self.before)
