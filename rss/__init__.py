"""Responsibility-Sensitive Safety with ad-rss 5.0 semantics (pure: numpy in, results out).

Main entry points: :func:`rss.engine.check_frame` / :func:`rss.engine.check_frames` on a
:class:`rss.batch.ConstellationBatch` built with :func:`rss.batch.stack_constellations`
from :mod:`rss.model` constellations; parameters in :mod:`rss.params`. See ``docs/rss.md``.
Unstructured (trajectory-set) RSS: :func:`check_unstructured` on :class:`UnstructuredAgents`
(``docs/rss_unstructured.md``; prefer these names or ``from rss.unstructured import ...``:
the ad-rss binding, once imported, overwrites the attribute ``rss.unstructured``).
"""

from rss.compiled import activate

activate(__name__, __path__)  # before any submodule import: rss.batch may run compiled

from rss.batch import ConstellationBatch, stack_constellations  # noqa: E402
from rss.dynamics import RssDynamics  # noqa: E402
from rss.engine import FrameResult, check_frame, check_frames  # noqa: E402
from rss.errors import RssCaseError, RssConstellationError, RssError, RssParameterError  # noqa: E402
from rss.memory import RssMemory  # noqa: E402
from rss.params import RssParams, parse_rss_params  # noqa: E402
from rss.unstructured.agents import UnstructuredAgents  # noqa: E402
from rss.unstructured.engine import UnstructuredResult, check_unstructured  # noqa: E402
from rss.unstructured.memory import UnstructuredMemory  # noqa: E402

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
