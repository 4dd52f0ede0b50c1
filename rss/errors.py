"""Typed errors of the RSS engine."""

from __future__ import annotations

__all__ = ["RssCaseError", "RssConstellationError", "RssError", "RssParameterError"]


class RssError(Exception):
    """Root of every error the RSS engine raises (bad parameters, bad constellations)."""


class RssParameterError(RssError):
    """An RSS dynamics or scene parameter is missing, unknown or outside its valid range."""

    def __init__(self, field: str, value: object, reason: str) -> None:
        """Build the message from the offending field, its value and the violated rule.

        Args:
            field: Parameter name as written in TOML / ad-rss (e.g. ``"vehicle.brake_min"``).
            value: The offending value.
            reason: The violated rule, e.g. ``"must be < 0 (brakes are negative)"``.
        """
        self.field = field
        self.value = value
        self.reason = reason
        super().__init__(f"RSS parameter {field}={value!r}: {reason}")


class RssConstellationError(RssError):
    """A constellation (road area, occupied region, type) is malformed."""

    def __init__(self, what: str, value: object, reason: str) -> None:
        """Build the message from the offending item, its value and the violated rule.

        Args:
            what: Which item is wrong, e.g. ``"constellation_type"`` or ``"lane 3 length"``.
            value: The offending value.
            reason: The violated rule.
        """
        self.what = what
        self.value = value
        self.reason = reason
        super().__init__(f"RSS constellation {what}={value!r}: {reason}")


class RssCaseError(RssError):
    """A conformance case cannot be read (missing key, wrong type, unknown kind)."""

    def __init__(self, case_id: str, reason: str) -> None:
        """Build the message from the case id and the reason.

        Args:
            case_id: The ``id`` of the case (or its index when it has none).
            reason: What is wrong with it.
        """
        self.case_id = case_id
        self.reason = reason
        super().__init__(f"RSS case {case_id!r}: {reason}")
