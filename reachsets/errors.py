"""Typed errors of the reach-set supervisor."""

from __future__ import annotations

from typing import Any

__all__ = ["InputShapeError", "ParamsError", "ReachSetError", "ZoneFileError"]


class ReachSetError(Exception):
    """Root of every error the reach-set engine raises."""


class InputShapeError(ReachSetError):
    """An input array has the wrong shape, length or non-finite values.

    Attributes:
        field: Name of the offending input field.
        value: The offending value (shape or sample).
    """

    def __init__(self, field: str, detail: str, value: Any = None) -> None:
        """Build the message from the field name, an explanation and the value."""
        self.field = field
        self.detail = detail
        self.value = value
        text = f"invalid reach-set input {field}: {detail}"
        if value is not None:
            text += f" (value: {value!r})"
        super().__init__(text)


class ParamsError(ReachSetError):
    """A parameter is out of its documented range.

    Attributes:
        name: Parameter name.
        value: Offending value.
    """

    def __init__(self, name: str, value: Any, expected: str) -> None:
        """Build the message from the parameter name, its value and the allowed range."""
        self.name = name
        self.value = value
        super().__init__(f"reach-set parameter {name}={value!r} is invalid: expected {expected}")


class ZoneFileError(ReachSetError):
    """A Roborace zone map (already parsed JSON) lacks keys or has bad indices."""

    def __init__(self, detail: str) -> None:
        """Build the message from an explanation."""
        self.detail = detail
        super().__init__(f"invalid Roborace zone map: {detail}")
