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
"""

from rss.compiled import activate

activate(__name__, __path__)  # before any submodule import: rss.batch may run compiled

from rss.dynamics import RssDynamics  # noqa: E402
from rss.errors import RssCaseError, RssConstellationError, RssError, RssParameterError  # noqa: E402
from rss.evaluate import FrameVerdict, evaluate_frames  # noqa: E402
from rss.params import RssParams, parse_rss_params  # noqa: E402
from rss.structured import (  # noqa: E402
    ConstellationBatch,
    FrameResult,
    RssMemory,
    check_frame,
    check_frames,
    stack_constellations,
)
from rss.unstructured import (  # noqa: E402
    UnstructuredAgents,
    UnstructuredMemory,
    UnstructuredResult,
    check_unstructured,
)

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
