"""Unstructured RSS (ad-rss 5.0 trajectory sets, conditions 22.1/22.2, drive-away).

Entry points :func:`check_unstructured` (one frame) and :func:`check_unstructured_frames`
(consecutive frames in one batch) on :class:`UnstructuredAgents` in the ENU map frame;
memory is explicit (:class:`UnstructuredMemory`). See ``docs/rss_unstructured.md``.
"""

from rss.unstructured.agents import MotionModel, UnstructuredAgents
from rss.unstructured.decision import Decisions, UnstructuredResponse
from rss.unstructured.engine import (
    FrameInputs,
    UnstructuredResult,
    check_unstructured,
    check_unstructured_frames,
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
    "check_unstructured_frames",
    "trajectory_sets",
]
