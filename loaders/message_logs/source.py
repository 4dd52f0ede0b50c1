"""The message-source protocol both container readers implement (rosbags and mcap)."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any, Protocol

if TYPE_CHECKING:
    from collections.abc import Collection, Iterator
    from pathlib import Path

    from loaders.drive import TopicInfo

__all__ = ["MessageSource"]


class MessageSource(Protocol):
    """Topics, decoded messages in time order and attachments of one log container."""

    path: Path
    source_format: str
    start_ns: int
    end_ns: int
    topics: tuple[TopicInfo, ...]
    #: What the container reader left out or changed (e.g. ignored channels), for ``DriveInfo``.
    notes: dict[str, str]

    def messages(
        self, topics: Collection[str], start_ns: int | None, stop_ns: int | None
    ) -> Iterator[tuple[str, int, Any]]:
        """Yield ``(topic, log_time_ns, decoded message)`` in log-time order.

        Only ``topics`` are read and decoded; ``[start_ns, stop_ns)`` bounds the log time.
        Raises ``CorruptLogError`` after the last readable message of a damaged log.
        """
        ...

    def attachments(self) -> Iterator[tuple[str, bytes]]:
        """Yield ``(name, data)`` of every attachment (MCAP only; bags have none)."""
        ...

    def close(self) -> None:
        """Release file handles."""
        ...
