"""What a clip is: a time window of a log, where it goes, and what came of it."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from pathlib import Path

__all__ = ["ChannelSpec", "ClipOutcome", "ClipRequest", "SchemaSpec"]


@dataclass(frozen=True)
class ClipRequest:
    """One clip to cut from a log.

    Attributes:
        path: Output ``.mcap`` file (written as ``<path>.part`` and renamed when complete).
        start_ns: First log time kept, inclusive (ns).
        end_ns: Last log time kept, inclusive (ns).
        event: Key/value pairs of the incident, written as one event message at ``start_ns``
            on the clip's event channel (``{}``: no event channel).
        metadata: Named metadata records added to the clip (name -> key/value pairs).
        event_span_ns: ``(start, end)`` the event spans, inclusive (ns; ``None``: the window).
    """

    path: Path
    start_ns: int
    end_ns: int
    event: dict[str, str] = field(default_factory=dict)
    metadata: dict[str, dict[str, str]] = field(default_factory=dict)
    event_span_ns: tuple[int, int] | None = None


@dataclass(frozen=True)
class SchemaSpec:
    """A message schema as an MCAP schema record carries it.

    Attributes:
        key: The source's identity of the schema (unique within one source).
        name: Schema name (``pkg/msg/Type`` for ROS 2, ``pkg/Type`` for ROS 1).
        encoding: ``ros1msg``, ``ros2msg``, ``ros2idl``, ``protobuf``, ``jsonschema`` or ``""``.
        data: The schema text or descriptor bytes.
    """

    key: object
    name: str
    encoding: str
    data: bytes


@dataclass(frozen=True)
class ChannelSpec:
    """A channel (topic) as an MCAP channel record carries it.

    Attributes:
        key: The source's identity of the channel (unique within one source).
        topic: Topic name.
        message_encoding: ``ros1``, ``cdr``, ``protobuf``, ``json``, ...
        schema: The channel's schema (``None``: schemaless).
        metadata: Channel metadata (string pairs).
    """

    key: object
    topic: str
    message_encoding: str
    schema: SchemaSpec | None
    metadata: dict[str, str]


@dataclass(frozen=True)
class ClipOutcome:
    """What was written for one :class:`ClipRequest`.

    Attributes:
        request: The request.
        written: Whether the clip file exists (complete window read).
        messages: Messages copied (including the event message).
        per_topic: Messages copied per source topic.
        reason: Why the clip was not written (``None`` when written).
        profile: The clip's MCAP profile (the log's: ``ros1``, ``ros2``, ``""``, ...).
    """

    request: ClipRequest
    written: bool
    messages: int
    per_topic: dict[str, int]
    reason: str | None = None
    profile: str = ""
