"""Errors of the workbench layer and the base set of errors the CLI reports as one line.

Each engine adds its own error types through its spec (``EngineSpec.errors``);
:func:`workbench.engines.registry.user_errors` is the whole set.
"""

from __future__ import annotations

from loaders.errors import LoaderError

__all__ = ["USER_ERRORS", "WorkbenchError"]


class WorkbenchError(Exception):
    """Root of errors raised by the pipeline, sinks, annotation store and exporters."""


#: Errors that are the user's input, not our bug, besides the engines' own (their specs).
USER_ERRORS: tuple[type[Exception], ...] = (LoaderError, WorkbenchError)
