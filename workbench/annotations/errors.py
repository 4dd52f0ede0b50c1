"""Errors of the label store: each one line naming the store file."""

from __future__ import annotations

from workbench.errors import WorkbenchError

__all__ = ["StoreCorruptError", "StoreError", "StoreLockedError"]


class StoreError(WorkbenchError):
    """The label store cannot be opened, read or written."""


class StoreCorruptError(StoreError):
    """The file is not a label store (not SQLite, damaged, or a newer schema)."""


class StoreLockedError(StoreError):
    """Another process held the store locked for longer than the busy timeout."""
