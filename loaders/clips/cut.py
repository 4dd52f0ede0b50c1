"""Cut many clips from one log in one pass: raw messages copied into one MCAP per window.

Every window's writer is opened when its first message arrives and all are finished after
the single pass, so a log is read once however many clips it yields. A clip is written to
``<name>.part`` and renamed when complete: a clip whose window the log does not cover whole
(the log breaks off before the window's end) is removed and reported, never left half.
"""

from __future__ import annotations

import contextlib
from typing import TYPE_CHECKING, BinaryIO, Protocol

from mcap.writer import CompressionType, Writer

from loaders.clips.bag_input import BagClipInput
from loaders.clips.errors import ClipWriteError
from loaders.clips.events import EVENT_TOPIC, event_codec
from loaders.clips.mcap_input import McapClipInput, RawMessage
from loaders.clips.model import ChannelSpec, ClipOutcome, ClipRequest
from loaders.errors import CorruptLogError, UnsupportedFormatError

if TYPE_CHECKING:
    from collections.abc import Callable, Collection, Iterator, Sequence
    from pathlib import Path

__all__ = ["MapAttachment", "write_clips"]

#: ``(name, media_type, data, create_time_ns)`` of a map attached to every clip (its log time
#: is each clip's start, so that a clip's bytes depend on nothing but its window).
MapAttachment = tuple[str, str, bytes, int]


#: Beyond any log time (ns).
_END_OF_TIME = 2**63 - 1
#: MCAP chunk compression by name; clips keep their log's (unknown or none read: zstd).
_COMPRESSION = {"zstd": CompressionType.ZSTD, "lz4": CompressionType.LZ4, "": CompressionType.NONE}


class _Input(Protocol):
    profile: str
    compression: str
    indexed: bool

    def messages(
        self, start_ns: int, end_ns: int, topics: Collection[str] | None
    ) -> Iterator[RawMessage]: ...
    def attachments(self) -> list[tuple[str, str, bytes, int, int]]: ...
    def metadata(self) -> list[tuple[str, dict[str, str]]]: ...
    def close(self) -> None: ...


def _open_input(path: Path) -> _Input:
    if path.is_dir() or path.suffix.lower() in {".bag", ".db3"}:
        return BagClipInput(path)
    if path.suffix.lower() == ".mcap":
        return McapClipInput(path)
    raise UnsupportedFormatError(path, "raw clips are cut from .mcap, .bag, .db3 or rosbag2 logs")


class _ClipFile:
    """One clip being written."""

    def __init__(self, request: ClipRequest, profile: str, compression: str) -> None:
        self.request = request
        self.part = request.path.with_name(request.path.name + ".part")
        try:
            self.part.parent.mkdir(parents=True, exist_ok=True)
            self._file: BinaryIO = self.part.open("wb")
        except OSError as err:
            raise ClipWriteError(request.path, err.strerror or type(err).__name__) from err
        self.writer = Writer(
            self._file, compression=_COMPRESSION.get(compression, CompressionType.ZSTD)
        )
        self.writer.start(profile=profile, library="rss-workbench clip")
        self._schemas: dict[object, int] = {}
        self._channels: dict[object, int] = {}
        self.per_topic: dict[str, int] = {}
        self.messages = 0
        self.done = False
        codec = event_codec(profile)
        if request.event:
            schema = self.writer.register_schema(
                codec.schema_name, codec.schema_encoding, codec.schema_data
            )
            channel = self.writer.register_channel(
                EVENT_TOPIC, codec.message_encoding, schema, codec.channel_metadata
            )
            start_ns, end_ns = request.event_span_ns or (request.start_ns, request.end_ns)
            data = codec.encode(start_ns, end_ns, request.event)
            self.writer.add_message(channel, request.start_ns, data, request.start_ns)
            self.messages += 1

    def _channel(self, spec: ChannelSpec) -> int:
        cid = self._channels.get(spec.key)
        if cid is None:
            sid = 0
            if spec.schema is not None:
                sid = self._schemas.get(spec.schema.key, -1)
                if sid < 0:
                    sid = self.writer.register_schema(
                        spec.schema.name, spec.schema.encoding, spec.schema.data
                    )
                    self._schemas[spec.schema.key] = sid
            cid = self.writer.register_channel(
                spec.topic, spec.message_encoding, sid, spec.metadata
            )
            self._channels[spec.key] = cid
        return cid

    def add(self, message: RawMessage) -> None:
        self.writer.add_message(
            self._channel(message.channel),
            message.log_time,
            message.data,
            message.publish_time,
            message.sequence,
        )
        topic = message.channel.topic
        self.per_topic[topic] = self.per_topic.get(topic, 0) + 1
        self.messages += 1

    def finish(
        self,
        attachments: Sequence[tuple[str, str, bytes, int, int]],
        metadata: Sequence[tuple[str, dict[str, str]]],
    ) -> None:
        try:
            for name, media_type, data, create_time, log_time in attachments:
                self.writer.add_attachment(create_time, log_time, name, media_type, data)
            for name, pairs in metadata:
                self.writer.add_metadata(name, pairs)
            self.writer.finish()  # type: ignore[no-untyped-call]
            self._file.close()
            self.part.replace(self.request.path)
        except OSError as err:
            raise ClipWriteError(self.request.path, err.strerror or type(err).__name__) from err
        self.done = True

    def discard(self) -> None:
        self.done = True
        self._file.close()
        self.part.unlink(missing_ok=True)


def write_clips(
    log: Path,
    requests: Sequence[ClipRequest],
    *,
    topics: Collection[str] | None = None,
    map_file: MapAttachment | None = None,
    source_name: str | None = None,
    on_message: Callable[[int], None] | None = None,
) -> list[ClipOutcome]:
    """Write one MCAP clip per request from ``log``, reading it once.

    Args:
        log: ``.mcap``, ROS 1 ``.bag``, rosbag2 directory or bare ``.db3``.
        requests: The windows to cut (may overlap).
        topics: Topics to copy (``None``: all).
        map_file: A map attached to every clip (besides the log's own attachments; left out
            when the log already holds an attachment of that name or those bytes).
        source_name: Name of the log recorded in each clip's ``clip`` metadata record.
        on_message: Called with each copied message's payload size (bytes), for progress.

    Returns:
        One outcome per request, in request order.

    Raises:
        LoaderError: The log cannot be opened at all.
    """
    if not requests:
        return []
    source = _open_input(log)
    cut = _Cut(requests, source.profile, source.compression)
    try:
        start = min(r.start_ns for r in requests)
        try:
            # An unindexed (damaged) log is read as one stream from the first window on, to its
            # end or its damage: how far it reaches decides which windows are whole.
            spans = _merged_spans(requests) if source.indexed else [(start, _END_OF_TIME)]
            for first, last in spans:
                for message in source.messages(first, last, topics):
                    cut.route(message)
                    if on_message is not None:
                        on_message(len(message.data))
        except CorruptLogError as err:
            cut.broke = err
        attachments = source.attachments()
        if map_file is not None and any(
            a[0] == map_file[0] or a[2] == map_file[2] for a in attachments
        ):
            map_file = None
        return cut.finish(attachments, source.metadata(), source_name or log.name, map_file)
    finally:
        cut.discard_unfinished()
        source.close()


def _merged_spans(requests: Sequence[ClipRequest]) -> list[tuple[int, int]]:
    """The union of the windows as sorted, disjoint inclusive spans (ns): only these are read."""
    spans: list[tuple[int, int]] = []
    for a, b in sorted((r.start_ns, r.end_ns) for r in requests):
        if spans and a <= spans[-1][1] + 1:
            spans[-1] = (spans[-1][0], max(spans[-1][1], b))
        else:
            spans.append((a, b))
    return spans


class _Cut:
    """The state of one pass: the open clips, how far the log was read, the damage."""

    def __init__(self, requests: Sequence[ClipRequest], profile: str, compression: str) -> None:
        self.requests = requests
        self.profile = profile
        self.compression = compression
        self.files: dict[int, _ClipFile] = {}
        self.reached: int | None = None
        self.broke: CorruptLogError | None = None

    def route(self, message: RawMessage) -> None:
        t = message.log_time
        self.reached = t if self.reached is None else max(self.reached, t)
        for index, request in enumerate(self.requests):
            if request.start_ns <= t <= request.end_ns:
                clip = self.files.get(index)
                if clip is None:
                    clip = self.files[index] = _ClipFile(request, self.profile, self.compression)
                clip.add(message)

    def finish(
        self,
        attachments: list[tuple[str, str, bytes, int, int]],
        metadata: list[tuple[str, dict[str, str]]],
        source_name: str,
        map_file: MapAttachment | None,
    ) -> list[ClipOutcome]:
        outcomes = []
        for index, request in enumerate(self.requests):
            clip = self.files.get(index)
            if self.broke is not None and (self.reached is None or self.reached < request.end_ns):
                if clip is not None:
                    clip.discard()
                where = "before any message" if self.reached is None else f"at {self.reached} ns"
                reason = f"log breaks off {where} ({self.broke.detail})"
                outcomes.append(
                    ClipOutcome(request, written=False, messages=0, per_topic={}, reason=reason)
                )
                continue
            if clip is None:
                clip = self.files[index] = _ClipFile(request, self.profile, self.compression)
            record = {
                "source": source_name,
                "start_ns": str(request.start_ns),
                "end_ns": str(request.end_ns),
            }
            own = [] if map_file is None else [(*map_file, request.start_ns)]
            clip.finish(
                [*attachments, *own], [*metadata, *request.metadata.items(), ("clip", record)]
            )
            outcomes.append(
                ClipOutcome(
                    request,
                    written=True,
                    messages=clip.messages,
                    per_topic=dict(clip.per_topic),
                    profile=self.profile,
                )
            )
        return outcomes

    def discard_unfinished(self) -> None:
        for clip in self.files.values():
            if not clip.done:
                with contextlib.suppress(OSError):
                    clip.discard()
