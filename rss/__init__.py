"""Responsibility-Sensitive Safety with ad-rss 5.0 semantics (pure: numpy in, results out).

One entry point per engine, same shape ``evaluate_frames(inputs, params, state) -> (results,
state)`` with the memory explicit, so a replay can restart at any frame:

* :func:`evaluate_frames` (:mod:`rss.evaluate`): structured RSS of ``F`` frames of boxes on
  a lane map: scene creation (:mod:`rss.scene`) then the structured kernels
  (:mod:`rss.structured`: :func:`stack_constellations` into a :class:`ConstellationBatch`,
  :func:`check_frames`), one :class:`FrameVerdict` per frame, :class:`RssMemory` state.
* :func:`rss.unstructured.evaluate_frames`: unstructured (trajectory-set) RSS of ``F``
  frames of :class:`UnstructuredAgents`, :class:`UnstructuredMemory` state
  (``docs/rss_unstructured.md``; import it as ``from rss.unstructured import ...``: the
  ad-rss binding, once imported, overwrites the attribute ``rss.unstructured``).

Shared records at the top: :mod:`rss.model` (constellations), :mod:`rss.params` /
:mod:`rss.dynamics` (parameters), :mod:`rss.physics` (tolerant kernels), :mod:`rss.errors`.
The conformance case format is :mod:`rss.conformance`. See ``docs/rss.md``.

Importing ``rss`` imports no submodule: the names below load their module on first use,
so an application can switch the compiled modules on first (``rss.compiled.activate``).
"""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from rss.dynamics import RssDynamics
    from rss.errors import RssCaseError, RssConstellationError, RssError, RssParameterError
    from rss.evaluate import FrameVerdict, evaluate_frames
    from rss.params import RssParams, parse_rss_params
    from rss.structured.batch import ConstellationBatch
    from rss.structured.engine import FrameResult, check_frame, check_frames
    from rss.structured.memory import RssMemory
    from rss.structured.stacking import stack_constellations
    from rss.unstructured.agents import UnstructuredAgents
    from rss.unstructured.engine import UnstructuredResult, check_unstructured
    from rss.unstructured.memory import UnstructuredMemory

#: Module of each top-level name (loaded on first access).
_HOME = {
    "ConstellationBatch": "rss.structured.batch",
    "FrameResult": "rss.structured.engine",
    "FrameVerdict": "rss.evaluate",
    "RssCaseError": "rss.errors",
    "RssConstellationError": "rss.errors",
    "RssDynamics": "rss.dynamics",
    "RssError": "rss.errors",
    "RssMemory": "rss.structured.memory",
    "RssParameterError": "rss.errors",
    "RssParams": "rss.params",
    "UnstructuredAgents": "rss.unstructured.agents",
    "UnstructuredMemory": "rss.unstructured.memory",
    "UnstructuredResult": "rss.unstructured.engine",
    "check_frame": "rss.structured.engine",
    "check_frames": "rss.structured.engine",
    "check_unstructured": "rss.unstructured.engine",
    "evaluate_frames": "rss.evaluate",
    "parse_rss_params": "rss.params",
    "stack_constellations": "rss.structured.stacking",
}

__all__ = [
    "ConstellationBatch",
    "FrameResult",
    "FrameVerdict",
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
    "evaluate_frames",
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
