"""Errors of the unstructured engine (all derive from :class:`rss.errors.RssError`)."""

from __future__ import annotations

from rss.errors import RssError

__all__ = ["UnstructuredInputError"]


class UnstructuredInputError(RssError):
    """An agent table is malformed (mismatched lengths, unknown dynamics count)."""

    def __init__(self, what: str, reason: str) -> None:
        """Store the offending field and build the message.

        Args:
            what: Name of the offending field.
            reason: What is wrong with it.
        """
        self.what = what
        self.reason = reason
        super().__init__(f"unstructured input {what}: {reason}")
