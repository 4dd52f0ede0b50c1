"""Responsibility-Sensitive Safety with ad-rss 5.0 semantics (pure: numpy in, results out).

Main entry points: :func:`rss.engine.check_frame` / :func:`rss.engine.check_frames` on a
:class:`rss.batch.ConstellationBatch` built with :func:`rss.batch.stack_constellations`
from :mod:`rss.model` constellations; parameters in :mod:`rss.params`. See ``docs/rss.md``.
Unstructured (trajectory-set) RSS: :func:`check_unstructured` on :class:`UnstructuredAgents`
(``docs/rss_unstructured.md``; prefer these names or ``from rss.unstructured import ...``:
the ad-rss binding, once imported, overwrites the attribute ``rss.unstructured``).

Importing ``rss`` imports no submodule: the names below load their module on first use,
so an application can switch the compiled modules on first (``rss.compiled.activate``).
"""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from rss.batch import ConstellationBatch, stack_constellations
    from rss.dynamics import RssDynamics
    from rss.engine import FrameResult, check_frame, check_frames
    from rss.errors import RssCaseError, RssConstellationError, RssError, RssParameterError
    from rss.memory import RssMemory
    from rss.params import RssParams, parse_rss_params
    from rss.unstructured.agents import UnstructuredAgents
    from rss.unstructured.engine import UnstructuredResult, check_unstructured
    from rss.unstructured.memory import UnstructuredMemory

#: Module of each top-level name (loaded on first access).
_HOME = {
    "ConstellationBatch": "rss.batch",
    "FrameResult": "rss.engine",
    "RssCaseError": "rss.errors",
    "RssConstellationError": "rss.errors",
    "RssDynamics": "rss.dynamics",
    "RssError": "rss.errors",
    "RssMemory": "rss.memory",
    "RssParameterError": "rss.errors",
    "RssParams": "rss.params",
    "UnstructuredAgents": "rss.unstructured.agents",
    "UnstructuredMemory": "rss.unstructured.memory",
    "UnstructuredResult": "rss.unstructured.engine",
    "check_frame": "rss.engine",
    "check_frames": "rss.engine",
    "check_unstructured": "rss.unstructured.engine",
    "parse_rss_params": "rss.params",
    "stack_constellations": "rss.batch",
}

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


def __getattr__(name: str) -> object:
    """Load a top-level name from its module on first access (see module docstring)."""
    home = _HOME.get(name)
    if home is None:
        raise AttributeError(f"module 'rss' has no attribute {name!r}")
    value = getattr(importlib.import_module(home), name)
    globals()[name] = value
    return value
