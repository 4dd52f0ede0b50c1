"""The typed error of the reach-set case format (``docs/reachset-cases.md``)."""

from __future__ import annotations

from reachsets.errors import ReachSetError

__all__ = ["ReachCaseError"]

#: Longest ``repr`` of an offending value quoted in a message.
_VALUE_CHARS = 60


def _short(value: object) -> str:
    text = repr(value)
    return text if len(text) <= _VALUE_CHARS else text[: _VALUE_CHARS - 3] + "..."


class ReachCaseError(ReachSetError):
    """A reach-set case document or one of its cases cannot be read.

    Attributes:
        source: The document's name (the file the CLI read, ``<document>`` otherwise).
        case_id: The case's ``id`` (``#k`` when it has none; ``<defaults>`` / ``<document>``
            for the document's own keys).
        field: Dotted path of the offending field inside the case, e.g. ``objects.1.speed``.
        value: The offending value.
        reason: The violated rule.
    """

    def __init__(self, source: str, case_id: str, field: str, value: object, reason: str) -> None:
        """Build the one-line message from the file, case, field, value and rule."""
        self.source = source
        self.case_id = case_id
        self.field = field
        self.value = value
        self.reason = reason
        super().__init__(
            f"reach-set cases {source}, case {case_id!r}, {field}={_short(value)}: {reason}"
        )
