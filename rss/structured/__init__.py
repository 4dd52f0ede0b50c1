"""Structured RSS kernels (ad-rss 5.0 ``RssSituationExtraction`` / checkers / response).

Constellations of :mod:`rss.model` -> :func:`stack_constellations` (padded structure of
arrays, :class:`ConstellationBatch`) -> :func:`check_frames` (extraction, merging of
similar constellations, checks, memory, proper response) over ``F`` consecutive frames,
the :class:`RssMemory` passed in and out. Scene creation from a lane map, which produces
the constellations, is :mod:`rss.scene`; both together are :func:`rss.evaluate_frames`.
The batch modules run compiled (mypyc) when the application switched the fresh build on
(``rss.compiled.activate``).
"""

from rss.structured.batch import ConstellationBatch
from rss.structured.engine import FrameResult, check_frame, check_frames, select_frame
from rss.structured.memory import RssMemory
from rss.structured.stacking import stack_constellations

__all__ = [
    "ConstellationBatch",
    "FrameResult",
    "RssMemory",
    "check_frame",
    "check_frames",
    "select_frame",
    "stack_constellations",
]
