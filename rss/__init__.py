"""Responsibility-Sensitive Safety with ad-rss 5.0 semantics (pure: numpy in, results out).

Main entry points: :func:`rss.engine.check_frame` / :func:`rss.engine.check_frames` on a
:class:`rss.batch.ConstellationBatch` built with :func:`rss.batch.stack_constellations`
from :mod:`rss.model` constellations; parameters in :mod:`rss.params`. See ``docs/rss.md``.
"""

from rss.batch import ConstellationBatch, stack_constellations
from rss.dynamics import RssDynamics
from rss.engine import FrameResult, check_frame, check_frames
from rss.errors import RssCaseError, RssConstellationError, RssError, RssParameterError
from rss.memory import RssMemory
from rss.params import RssParams, parse_rss_params

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
    "check_frame",
    "check_frames",
    "parse_rss_params",
    "stack_constellations",
]
