"""Unstructured RSS (ad-rss 5.0 trajectory sets, conditions 22.1/22.2, drive-away).

Entry point :func:`check_unstructured` on :class:`UnstructuredAgents` in the ENU map frame;
memory is explicit (:class:`UnstructuredMemory`). See ``docs/rss_unstructured.md``.
"""

from rss.unstructured.agents import MotionModel, UnstructuredAgents
from rss.unstructured.decision import Decisions, UnstructuredResponse
from rss.unstructured.engine import UnstructuredResult, check_unstructured, trajectory_sets
from rss.unstructured.errors import UnstructuredInputError
from rss.unstructured.memory import UnstructuredMemory
from rss.unstructured.response import UnstructuredProperResponse
from rss.unstructured.sets import TrajectorySets

__all__ = [
    "Decisions",
    "MotionModel",
    "TrajectorySets",
    "UnstructuredAgents",
    "UnstructuredInputError",
    "UnstructuredMemory",
    "UnstructuredProperResponse",
    "UnstructuredResponse",
    "UnstructuredResult",
    "check_unstructured",
    "trajectory_sets",
]
