"""MCAP files through ``mcap``'s reader: ROS 1, JSON and protobuf channels, damaged ROS 2 files.

Healthy files are read through the summary and chunk index (``SeekingReader``). Files
without a readable summary (truncated, or written without one) are read as a record
stream: a first pass lists channels, counts and attachments and notes where the data
breaks off; message reading then yields every message before that point and raises
``CorruptLogError`` with the byte offset.

Decoders are resolved once per channel and cached: ``protobuf`` through ``betterosi``
for ASAM OSI schemas (``osi3.GroundTruth``, ``osi3.SensorView``, …) and ``mcap_protobuf``
otherwise, ``json`` with the standard library, ``cdr`` (ROS 2) and ``ros1`` through
a rosbags typestore built from the channel's ``ros2msg``/``ros1msg`` schema. ROS 2 service-event
channels (``*/_service_event``, ``*/srv/*_Event`` schemas) are left out of the topics.
"""

from __future__ import annotations

import json
import re
import struct
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from backports.zstd import ZstdError as BackportsZstdError
from betterosi import BetterOsiDecoderFactory
from betterosi.mcap_reader import osi_type_name
from google.protobuf.message import DecodeError
from mcap.data_stream import ReadDataStream
from mcap.exceptions import McapError
from mcap.reader import SeekingReader
from mcap.records import Attachment, Channel, Message, Schema
from mcap.stream_reader import StreamReader
from mcap_protobuf.decoder import DecoderFactory as ProtobufDecoderFactory
from rosbags.serde import SerdeError
from rosbags.typesys import Stores, get_types_from_msg, get_typestore
from rosbags.typesys.base import TypesysError
from zstandard import ZstdError

from loaders.drive import TopicInfo
from loaders.errors import CorruptLogError, EmptyLogError, UnsupportedFormatError
from loaders.message_logs.registry import normalize_msgtype
from loaders.typestore import check_definitions

if TYPE_CHECKING:
    from collections.abc import Callable, Collection, Iterator
    from pathlib import Path
    from typing import BinaryIO

__all__ = ["MCAP_ERRORS", "McapSource", "is_service_event", "osm_attachments"]

#: What a damaged MCAP raises while reading (wrapped into ``CorruptLogError``).
MCAP_ERRORS: tuple[type[Exception], ...] = (
    McapError,
    struct.error,
    EOFError,
    ValueError,
    OverflowError,  # a record length past the index range
    MemoryError,  # a record length past what memory holds
    KeyError,
    OSError,
    RuntimeError,
    IndexError,
    ZstdError,
    BackportsZstdError,
    DecodeError,
    AssertionError,
    TypesysError,
    SerdeError,
)
_FORMATS = {
    "cdr": "ros2-mcap",
    "ros1": "ros1-mcap",
    "json": "mcap-json",
    "protobuf": "mcap-protobuf",
}
#: ROS 2 (Jazzy) service-event channels: recorded service calls, never a drive's topic.
_SERVICE_EVENT = re.compile(r"/_service_event$")
_SERVICE_SCHEMA = re.compile(r"/srv/\w+_Event$")


def is_service_event(channel: Channel, schema: Schema | None) -> bool:
    """Whether ``channel`` records ROS 2 service calls (ignored, with a note)."""
    name = schema.name if schema is not None else ""
    return bool(_SERVICE_EVENT.search(channel.topic) or _SERVICE_SCHEMA.search(name))


def _ros_decoder(schema: Schema, *, ros1: bool) -> Callable[[bytes], Any]:
    store = get_typestore(Stores.EMPTY)
    types = check_definitions(get_types_from_msg(schema.data.decode(), schema.name))
    store.register(types)
    name = next(iter(types))
    if ros1:
        return lambda data: store.deserialize_ros1(data, name)
    return lambda data: store.deserialize_cdr(data, name)


@dataclass
class _Index:
    """What a pass over the records found."""

    schemas: dict[int, Schema] = field(default_factory=dict)
    channels: dict[int, Channel] = field(default_factory=dict)
    counts: dict[int, int] = field(default_factory=dict)
    start_ns: int | None = None
    end_ns: int = 0
    maps: list[tuple[str, bytes]] = field(default_factory=list)
    damage: tuple[int, str] | None = None


def _scan(stream: BinaryIO) -> _Index:
    index = _Index()
    reader = StreamReader(stream, record_size_limit=2**31)
    try:
        for record in reader.records:
            if isinstance(record, Schema):
                index.schemas[record.id] = record
            elif isinstance(record, Channel):
                index.channels[record.id] = record
            elif isinstance(record, Message):
                index.counts[record.channel_id] = index.counts.get(record.channel_id, 0) + 1
                t = record.log_time
                index.start_ns = t if index.start_ns is None else min(index.start_ns, t)
                index.end_ns = max(index.end_ns, t)
            elif isinstance(record, Attachment) and record.name.endswith(".osm"):
                index.maps.append((record.name, bytes(record.data)))
    except MCAP_ERRORS as err:
        index.damage = (stream.tell(), f"{type(err).__name__}: {err}")
    return index


def osm_attachments(path: Path) -> Iterator[tuple[str, bytes]]:
    """Yield ``(name, data)`` of the ``.osm`` attachments of an indexed MCAP file."""
    with path.open("rb") as f:
        reader = SeekingReader(f)
        summary = reader.get_summary()
        if summary is None:
            return
        for index in summary.attachment_indexes:
            if index.name.endswith(".osm"):
                f.seek(index.offset + 1 + 8)
                record = Attachment.read(ReadDataStream(f))
                yield record.name, bytes(record.data)


class McapSource:
    """An MCAP file read with ``mcap`` (see the module docstring)."""

    def __init__(self, path: Path) -> None:
        """Open ``path`` and read its summary (or scan it when it has none)."""
        self.path = path
        self._file = path.open("rb")
        self._reader: SeekingReader | None = None
        self._protobuf = ProtobufDecoderFactory()
        self._osi = BetterOsiDecoderFactory()
        self._decoders: dict[int, Callable[[bytes], Any]] = {}
        try:
            reader = SeekingReader(self._file)
            summary = reader.get_summary()
        except MCAP_ERRORS:
            summary = None
        if summary is not None and summary.statistics is not None and summary.chunk_indexes:
            self._reader = reader
            stats = summary.statistics
            index = _Index(
                summary.schemas,
                summary.channels,
                dict(stats.channel_message_counts),
                stats.message_start_time,
                stats.message_end_time,
            )
        else:
            self._file.seek(0)
            index = _scan(self._file)
        self._index = index
        self.ignored = self._drop_service_events()
        self.notes = {"ignored_service_channels": ", ".join(self.ignored)} if self.ignored else {}
        if not any(index.counts.get(cid) for cid, _ in self._channels()) or index.start_ns is None:
            self.close()
            if index.damage is not None:
                raise CorruptLogError(
                    path, f"no readable message: {index.damage[1]}", offset=index.damage[0]
                )
            raise EmptyLogError(path, "the MCAP holds no messages")
        self.start_ns, self.end_ns = index.start_ns, index.end_ns
        encodings = {c.message_encoding for _, c in self._channels()}
        known = sorted(_FORMATS[e] for e in encodings if e in _FORMATS)
        if not known:
            self.close()
            raise UnsupportedFormatError(path, f"no channel encoding we read: {sorted(encodings)}")
        ros = [k for k in ("ros2-mcap", "ros1-mcap") if k in known]
        self.source_format = (
            ros[0] if ros else "mcap-" + "+".join(k.removeprefix("mcap-") for k in known)
        )
        self.topics = self._topic_infos()

    def _drop_service_events(self) -> tuple[str, ...]:
        """Leave service-event channels out of the topics; return their topics."""
        index = self._index
        self._ignored_ids = {
            cid
            for cid, channel in index.channels.items()
            if is_service_event(channel, index.schemas.get(channel.schema_id))
        }
        return tuple(sorted({index.channels[cid].topic for cid in self._ignored_ids}))

    def _channels(self) -> Iterator[tuple[int, Channel]]:
        """The channels read as topics (service events left out)."""
        for cid, channel in self._index.channels.items():
            if cid not in self._ignored_ids:
                yield cid, channel

    @property
    def indexed(self) -> bool:
        """True when the file was opened through its summary and chunk index."""
        return self._reader is not None

    def _msgtype(self, channel: Channel) -> str:
        schema = self._index.schemas.get(channel.schema_id)
        if schema is None:
            return channel.message_encoding
        osi = osi_type_name(schema) if channel.message_encoding == "protobuf" else None
        return f"osi3.{osi}" if osi is not None else normalize_msgtype(schema.name)

    def _topic_infos(self) -> tuple[TopicInfo, ...]:
        counts: dict[str, int] = {}
        types: dict[str, str] = {}
        for cid, channel in self._channels():
            counts[channel.topic] = counts.get(channel.topic, 0) + self._index.counts.get(cid, 0)
            types[channel.topic] = self._msgtype(channel)
        return tuple(TopicInfo(t, types[t], counts[t]) for t in sorted(types))

    def _decoder(self, channel: Channel) -> Callable[[bytes], Any]:
        decode = self._decoders.get(channel.id)
        if decode is None:
            schema = self._index.schemas.get(channel.schema_id)
            if channel.message_encoding == "json":
                decode = json.loads
            elif channel.message_encoding in {"cdr", "ros1"} and schema is not None:
                decode = _ros_decoder(schema, ros1=channel.message_encoding == "ros1")
            else:
                found = self._protobuf_decoder(channel, schema)
                if found is None:
                    raise UnsupportedFormatError(
                        self.path, f"cannot decode {channel.message_encoding}", topic=channel.topic
                    )
                decode = found
            self._decoders[channel.id] = decode
        return decode

    def _protobuf_decoder(
        self, channel: Channel, schema: Schema | None
    ) -> Callable[[bytes], Any] | None:
        """The decoder of a protobuf channel: betterosi for ASAM OSI, else ``mcap_protobuf``."""
        try:
            return self._osi.decoder_for(
                channel.message_encoding, schema
            ) or self._protobuf.decoder_for(channel.message_encoding, schema)
        except TypeError as err:  # mcap_protobuf: a descriptor set that does not build
            name = None if schema is None else schema.name
            raise CorruptLogError(
                self.path, f"schema {name} does not build: {err}", topic=channel.topic
            ) from err

    def _records(
        self, topics: Collection[str], start_ns: int | None, stop_ns: int | None
    ) -> Iterator[tuple[Channel, Message]]:
        if self._reader is not None:
            for _, channel, message in self._reader.iter_messages(
                topics=list(topics), starting_at=start_ns, ending_before=stop_ns
            ):
                yield channel, message
            return
        self._file.seek(0)
        channels: dict[int, Channel] = {}
        for record in StreamReader(self._file, record_size_limit=2**31).records:
            if isinstance(record, Channel):
                channels[record.id] = record
            elif isinstance(record, Message):
                channel = channels[record.channel_id]
                t = record.log_time
                if channel.topic not in topics or (start_ns is not None and t < start_ns):
                    continue
                if stop_ns is None or t < stop_ns:
                    yield channel, record

    def messages(
        self, topics: Collection[str], start_ns: int | None, stop_ns: int | None
    ) -> Iterator[tuple[str, int, Any]]:
        """Yield decoded messages of ``topics``; see ``MessageSource``."""
        topic, t_ns = None, None
        try:
            for channel, message in self._records(topics, start_ns, stop_ns):
                topic, t_ns = channel.topic, message.log_time
                yield topic, t_ns, self._decoder(channel)(message.data)
        except MCAP_ERRORS as err:
            raise CorruptLogError(
                self.path,
                f"{type(err).__name__}: {err}",
                topic=topic,
                t_ns=t_ns,
                offset=self._file.tell(),
            ) from err
        if self._index.damage is not None and (stop_ns is None or stop_ns > self._index.end_ns):
            offset, detail = self._index.damage
            raise CorruptLogError(self.path, detail, topic=topic, t_ns=t_ns, offset=offset)

    def attachments(self) -> Iterator[tuple[str, bytes]]:
        """Yield ``(name, data)`` of the ``.osm`` attachments."""
        if self._reader is None:
            yield from self._index.maps
            return
        yield from osm_attachments(self.path)

    def close(self) -> None:
        """Close the file."""
        self._file.close()
