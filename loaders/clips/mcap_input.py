"""Raw records of an MCAP file, for clips: copied as they are, never decoded.

Healthy files are read through their index in log-time order; a file whose summary cannot
be read (truncated, damaged) is read as a record stream up to the damage, which is reported
as :class:`~loaders.errors.CorruptLogError` with the last good log time.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

from mcap.reader import NonSeekingReader, SeekingReader
from mcap.records import Attachment, Metadata
from mcap.stream_reader import StreamReader

from loaders.clips.model import ChannelSpec, SchemaSpec
from loaders.errors import CorruptLogError
from loaders.message_logs.mcap_source import MCAP_ERRORS

if TYPE_CHECKING:
    from collections.abc import Collection, Iterator
    from pathlib import Path

    from mcap.records import Channel, Schema

__all__ = ["McapClipInput", "RawMessage"]


@dataclass(frozen=True)
class RawMessage:
    """One message as bytes on the wire, with the channel it belongs to."""

    channel: ChannelSpec
    log_time: int
    data: bytes
    publish_time: int
    sequence: int


class McapClipInput:
    """Streams an MCAP file's messages, attachments and metadata records."""

    def __init__(self, path: Path) -> None:
        """Open ``path`` (kept open until :meth:`close`)."""
        self.path = path
        self._file = path.open("rb")
        self._channels: dict[int, ChannelSpec] = {}
        reader = SeekingReader(self._file)
        try:
            self.profile = reader.get_header().profile
        except MCAP_ERRORS as err:
            self._file.close()
            raise CorruptLogError(path, f"cannot read the MCAP header: {err}", offset=0) from err
        #: Chunk compression of the log (``zstd``, ``lz4``, ``""``); clips keep it.
        self.compression = "zstd"
        #: The indexed reader, or ``None`` when the summary is unreadable (read as a stream).
        self._indexed: SeekingReader | None = None
        try:
            summary = reader.get_summary()
        except MCAP_ERRORS:
            summary = None
        if summary is not None:
            self._indexed = reader
            if summary.chunk_indexes:
                self.compression = summary.chunk_indexes[0].compression
        #: Whether time windows are read through the index (else as one stream).
        self.indexed = self._indexed is not None

    def _spec(self, schema: Schema | None, channel: Channel) -> ChannelSpec:
        spec = self._channels.get(channel.id)
        if spec is None:
            schema_spec = (
                None
                if schema is None
                else SchemaSpec(schema.id, schema.name, schema.encoding, bytes(schema.data))
            )
            spec = ChannelSpec(
                channel.id,
                channel.topic,
                channel.message_encoding,
                schema_spec,
                dict(channel.metadata),
            )
            self._channels[channel.id] = spec
        return spec

    def messages(
        self, start_ns: int, end_ns: int, topics: Collection[str] | None
    ) -> Iterator[RawMessage]:
        """Messages with ``start_ns <= log_time <= end_ns`` on ``topics`` (``None``: all).

        Raises:
            CorruptLogError: The file breaks off; every message before the damage was yielded.
        """
        last = None
        selected = None if topics is None else list(topics)
        try:
            if self._indexed is not None:
                records = self._indexed.iter_messages(
                    topics=selected, starting_at=start_ns, ending_at=end_ns
                )
            else:
                self._file.seek(0)
                records = NonSeekingReader(self._file).iter_messages(
                    topics=selected,
                    starting_at=start_ns,
                    ending_at=end_ns,
                    log_time_order=False,  # file order: sorting would read the whole file first
                )
            for schema, channel, message in records:
                last = message.log_time
                yield RawMessage(
                    self._spec(schema, channel),
                    message.log_time,
                    bytes(message.data),
                    message.publish_time,
                    message.sequence,
                )
        except MCAP_ERRORS as err:
            raise CorruptLogError(
                self.path,
                f"{type(err).__name__} {err}".strip(),
                t_ns=last,
                offset=self._file.tell(),
            ) from err

    def _stream_records(self) -> Iterator[object]:
        """The file's top-level records from its start up to the damage (unindexed files)."""
        self._file.seek(0)
        try:
            yield from StreamReader(self._file).records
        except MCAP_ERRORS:
            return

    def attachments(self) -> list[tuple[str, str, bytes, int, int]]:
        """``(name, media_type, data, create_time, log_time)`` of every readable attachment.

        Through the summary; a file without a readable one (truncated) is scanned from its
        start up to the damage, so an attachment written before it is kept.
        """
        if self._indexed is None:
            return [
                (r.name, r.media_type, bytes(r.data), r.create_time, r.log_time)
                for r in self._stream_records()
                if isinstance(r, Attachment)
            ]
        try:
            return [
                (a.name, a.media_type, bytes(a.data), a.create_time, a.log_time)
                for a in self._indexed.iter_attachments()
            ]
        except MCAP_ERRORS:
            return []

    def metadata(self) -> list[tuple[str, dict[str, str]]]:
        """``(name, pairs)`` of every readable metadata record (summary, else a scan)."""
        if self._indexed is None:
            return [
                (r.name, dict(r.metadata))
                for r in self._stream_records()
                if isinstance(r, Metadata)
            ]
        try:
            return [(m.name, dict(m.metadata)) for m in self._indexed.iter_metadata()]
        except MCAP_ERRORS:
            return []

    def close(self) -> None:
        """Close the file."""
        self._file.close()
