"""Errors of clip cutting: each one line naming the clip file."""

from __future__ import annotations

from loaders.errors import LoaderError

__all__ = ["ClipWriteError"]


class ClipWriteError(LoaderError):
    """A clip file cannot be written (permissions, read-only file system, disk full)."""

    what = "cannot write clip"
