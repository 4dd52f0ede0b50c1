"""Responsibility-Sensitive Safety with ad-rss 5.0 semantics (pure: numpy in, results out).

Main entry points: :func:`rss.engine.check_frame` / :func:`rss.engine.check_frames` on a
:class:`rss.batch.ConstellationBatch` built with :func:`rss.batch.stack_constellations`
from :mod:`rss.model` constellations; parameters in :mod:`rss.params`. See ``docs/rss.md``.
Unstructured (trajectory-set) RSS: :func:`check_unstructured` on :class:`UnstructuredAgents`
(``docs/rss_unstructured.md``; prefer these names or ``from rss.unstructured import ...``:
the ad-rss binding, once imported, overwrites the attribute ``rss.unstructured``).
"""

from rss.batch import ConstellationBatch, stack_constellations
from rss.dynamics import RssDynamics
from rss.engine import FrameResult, check_frame, check_frames
from rss.errors import RssCaseError, RssConstellationError, RssError, RssParameterError
from rss.memory import RssMemory
from rss.params import RssParams, parse_rss_params
from rss.unstructured.agents import UnstructuredAgents
from rss.unstructured.engine import UnstructuredResult, check_unstructured
from rss.unstructured.memory import UnstructuredMemory

__all__ = [
    "ConstellationBatch",
    "FrameResult",
    "RssCaseError",
    "RssConstellationError",
    "RssDynamics",
    "RssError",
    "RssMemory",
    "RssParameterError",
    "RssParams",
    "UnstructuredAgents",
    "UnstructuredMemory",
    "UnstructuredResult",
    "check_frame",
    "check_frames",
    "check_unstructured",
    "parse_rss_params",
    "stack_constellations",
]
