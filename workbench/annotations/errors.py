"""Errors of the label store: each one line naming the store file."""

from __future__ import annotations

from workbench.errors import WorkbenchError

__all__ = [
    "OpenLabelError",
    "StoreCorruptError",
    "StoreError",
    "StoreLockedError",
    "TagError",
]


class StoreError(WorkbenchError):
    """The label store cannot be opened, read or written."""


class StoreCorruptError(StoreError):
    """The file is not a label store (not SQLite, damaged, or a newer schema)."""


class StoreLockedError(StoreError):
    """Another process held the store locked for longer than the busy timeout."""


class OpenLabelError(WorkbenchError):
    """An OpenLABEL file this workbench cannot import (names the file and the element)."""


class TagError(StoreError):
    """A review tag that is empty, spans lines or is too long (names the tag)."""
