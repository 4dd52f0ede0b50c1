"""Unstructured RSS (ad-rss 5.0 trajectory sets, conditions 22.1/22.2, drive-away).

Entry point :func:`evaluate_frames` ``(frames, params, memory) -> (results, memory)``:
``F`` consecutive :class:`FrameInputs` (the ego and ``(N,)`` agents as
:class:`UnstructuredAgents` in the ENU map frame) in one batch, one
:class:`UnstructuredResult` per frame, the memory explicit (:class:`UnstructuredMemory`)
so a replay can restart at any frame. :func:`check_unstructured` is one frame with every
dynamics given. See ``docs/rss_unstructured.md``.
"""

from rss.unstructured.agents import MotionModel, UnstructuredAgents
from rss.unstructured.decision import Decisions, UnstructuredResponse
from rss.unstructured.engine import (
    FrameInputs,
    UnstructuredResult,
    check_unstructured,
    evaluate_frames,
    trajectory_sets,
)
from rss.unstructured.errors import UnstructuredInputError
from rss.unstructured.memory import UnstructuredMemory
from rss.unstructured.response import UnstructuredProperResponse
from rss.unstructured.sets import TrajectorySets

__all__ = [
    "Decisions",
    "FrameInputs",
    "MotionModel",
    "TrajectorySets",
    "UnstructuredAgents",
    "UnstructuredInputError",
    "UnstructuredMemory",
    "UnstructuredProperResponse",
    "UnstructuredResponse",
    "UnstructuredResult",
    "check_unstructured",
    "evaluate_frames",
    "trajectory_sets",
]
