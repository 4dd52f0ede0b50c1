"""Typed loader errors: each names the file and, where known, topic, time, offset and value."""

from __future__ import annotations

from pathlib import Path
from typing import Any

__all__ = [
    "CorruptLogError",
    "EmptyLogError",
    "InvalidValueError",
    "LoaderError",
    "LogNotFoundError",
    "MapError",
    "MissingEgoTopicError",
    "ProfileError",
    "UnknownMessageTypeError",
    "UnsupportedFormatError",
]


#: Longest detail and value text in a message (characters); a library's error can quote a
#: whole message definition.
MAX_DETAIL_CHARS = 300


def _printable(text: str) -> str:
    """``text`` with characters that do not print escaped (a topic name of a damaged file)."""
    return "".join(c if c.isprintable() else repr(c)[1:-1] for c in text)


def _one_line(text: str) -> str:
    """``text`` on one line (runs of white space become one space), cut to the limit."""
    flat = _printable(" ".join(text.split()))
    if len(flat) <= MAX_DETAIL_CHARS:
        return flat
    return flat[: MAX_DETAIL_CHARS - 3] + "..."


class LoaderError(Exception):
    """Root of every error the loaders raise.

    The message is built from structured fields so that the CLI can print one clear line:
    the detail and the value are put on one line and cut to :data:`MAX_DETAIL_CHARS` (the
    fields themselves keep what was given).
    """

    what = "cannot read drive"

    def __init__(
        self,
        path: str | Path,
        detail: str = "",
        *,
        topic: str | None = None,
        t_ns: int | None = None,
        offset: int | None = None,
        value: Any = None,
    ) -> None:
        """Build the error from its fields.

        Args:
            path: File (or bag directory) the error is about.
            detail: Human-readable explanation.
            topic: Topic concerned, if any.
            t_ns: Message time in nanoseconds, if known.
            offset: Byte offset or record index, if known.
            value: The offending value, if any.
        """
        self.path = Path(path)
        self.detail = detail
        self.topic = topic
        self.t_ns = t_ns
        self.offset = offset
        self.value = value
        super().__init__(self._message())

    def _message(self) -> str:
        parts = [_printable(str(self.path))]
        if self.topic is not None:
            parts.append(f"topic {_printable(self.topic)}")
        if self.t_ns is not None:
            parts.append(f"t={self.t_ns} ns")
        if self.offset is not None:
            parts.append(f"offset {self.offset}")
        where = ", ".join(parts)
        text = f"{where}: {self.what}"
        if self.detail:
            text += f": {_one_line(self.detail)}"
        if self.value is not None:
            text += f" (value: {_one_line(repr(self.value))})"
        return text


class LogNotFoundError(LoaderError):
    """The drive path does not exist."""

    what = "no such file or directory"


class UnsupportedFormatError(LoaderError):
    """The path is not a drive format we read."""

    what = "unsupported drive format"


class EmptyLogError(LoaderError):
    """The file holds no messages (or no frames could be built)."""

    what = "log is empty"


class CorruptLogError(LoaderError):
    """The file is truncated or corrupted; raised after every readable frame was yielded."""

    what = "log is truncated or corrupted"


class UnknownMessageTypeError(LoaderError):
    """A topic named by the profile has a message type we cannot decode."""

    what = "unknown message type"


class MissingEgoTopicError(LoaderError):
    """No ego topic could be detected or the profile's ego topic is absent."""

    what = "no ego topic"


class InvalidValueError(LoaderError):
    """A value that makes a whole frame unusable (e.g. a NaN ego pose)."""

    what = "invalid value"


class ProfileError(LoaderError):
    """The TOML topic profile is malformed or names topics that do not exist."""

    what = "bad topic profile"


class MapError(LoaderError):
    """A map file cannot be read."""

    what = "cannot read map"
