"""Errors of the workbench layer and the set of errors the CLI reports as one line."""

from __future__ import annotations

from loaders.errors import LoaderError
from reachsets.errors import ReachSetError
from rss.errors import RssError

__all__ = ["USER_ERRORS", "WorkbenchError"]


class WorkbenchError(Exception):
    """Root of errors raised by the pipeline, sinks, annotation store and exporters."""


#: Errors that are the user's input, not our bug: the CLI prints them as one line.
USER_ERRORS: tuple[type[Exception], ...] = (LoaderError, RssError, ReachSetError, WorkbenchError)
