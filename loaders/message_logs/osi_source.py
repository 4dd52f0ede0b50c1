"""ASAM OSI binary trace files (``.osi``): length-prefixed GroundTruth or SensorView messages.

A trace file is a sequence of ``<uint32 little-endian length><serialized message>`` records
of one message type, told by the OSI trace file naming convention
(``<timestamp>_<type>_<osi version>_<protobuf version>_<frames>_<custom>.osi`` with type
``gt`` or ``sv``; ``betterosi.io.osi_message_type_from_filename``). Messages are read with
``betterosi.read``; a first pass over the length prefixes counts them and notes where the
data breaks off. The log has one topic (``ground_truth`` or ``sensor_view``) whose log time
is each message's ``timestamp``.
"""

from __future__ import annotations

import struct
from typing import TYPE_CHECKING, Any

import betterosi
from betterosi.io import osi_message_type_from_filename

from loaders.drive import TopicInfo
from loaders.errors import CorruptLogError, EmptyLogError, UnsupportedFormatError
from loaders.message_logs.decoders.osi import osi_stamp_ns

if TYPE_CHECKING:
    from collections.abc import Collection, Iterator
    from pathlib import Path

__all__ = ["OSI_TOPICS", "OsiTraceSource"]

#: Trace message type → (topic, normalised type name).
OSI_TOPICS: dict[str, tuple[str, str]] = {
    "GroundTruth": ("ground_truth", "osi3.GroundTruth"),
    "SensorView": ("sensor_view", "osi3.SensorView"),
}
_PREFIX = 4  # bytes of the length prefix
#: What reading a damaged trace raises (wrapped into ``CorruptLogError``); the protobuf
#: decoder gives up on groups nested too deep with ``RecursionError``.
_OSI_ERRORS: tuple[type[Exception], ...] = (
    ValueError,
    KeyError,
    IndexError,
    struct.error,
    OSError,
    RecursionError,
)


def _scan(path: Path) -> tuple[list[tuple[int, int]], tuple[int, str] | None]:
    """``(offset, length)`` of every complete record and the damage ``(offset, what)``."""
    records: list[tuple[int, int]] = []
    size = path.stat().st_size
    offset = 0
    with path.open("rb") as f:
        while offset < size:
            head = f.read(_PREFIX)
            if len(head) < _PREFIX:
                return records, (offset, "truncated length prefix")
            (length,) = struct.unpack("<I", head)
            if offset + _PREFIX + length > size:
                return records, (offset, f"message of {length} bytes runs past the end")
            records.append((offset, length))
            offset += _PREFIX + length
            f.seek(offset)
    return records, None


class OsiTraceSource:
    """A ``.osi`` trace file read with ``betterosi`` (see the module docstring)."""

    source_format = "osi-trace"

    def __init__(self, path: Path) -> None:
        """Tell the message type from the name, index the records, read the time bounds."""
        self.path = path
        kind = osi_message_type_from_filename(path)
        if kind not in OSI_TOPICS:
            raise UnsupportedFormatError(
                path,
                f"OSI trace of {kind or 'unknown'} messages; only GroundTruth and SensorView "
                "traces are read, named by the OSI trace file naming convention "
                "(<timestamp>_gt_... or <timestamp>_sv_...)",
            )
        self._kind = kind
        self._records, self._damage = _scan(path)
        self.notes: dict[str, str] = {}
        if not self._records:
            if self._damage is not None:
                raise CorruptLogError(
                    path, f"no readable message: {self._damage[1]}", offset=self._damage[0]
                )
            raise EmptyLogError(path, "the OSI trace holds no messages")
        self.start_ns = self._stamp(0)
        try:
            self.end_ns = self._stamp(len(self._records) - 1)
        except CorruptLogError:
            self.end_ns = self.start_ns  # the damage is reported when the messages are read
        topic, msgtype = OSI_TOPICS[kind]
        self.topics: tuple[TopicInfo, ...] = (TopicInfo(topic, msgtype, len(self._records)),)

    def _stamp(self, k: int) -> int:
        offset, length = self._records[k]
        with self.path.open("rb") as f:
            f.seek(offset + _PREFIX)
            data = f.read(length)
        try:
            stamp = osi_stamp_ns(getattr(betterosi, self._kind).from_binary(data))
        except _OSI_ERRORS as err:
            raise CorruptLogError(self.path, f"{type(err).__name__}: {err}", offset=offset) from err
        if stamp is None:
            raise CorruptLogError(self.path, f"{self._kind} without timestamp", offset=offset)
        return stamp

    def messages(
        self, topics: Collection[str], start_ns: int | None, stop_ns: int | None
    ) -> Iterator[tuple[str, int, Any]]:
        """Yield ``(topic, timestamp_ns, message)`` in file order; see ``MessageSource``."""
        topic = self.topics[0].topic
        if topic not in topics:
            return
        t_ns: int | None = None
        read = 0
        try:
            for msg in betterosi.read(str(self.path), osi_message_type=self._kind):
                stamp = osi_stamp_ns(msg)
                if stamp is None:
                    raise CorruptLogError(
                        self.path,
                        f"{self._kind} without timestamp",
                        topic=topic,
                        t_ns=t_ns,
                        offset=self._records[read][0],
                    )
                read += 1
                t_ns = stamp
                if (start_ns is None or t_ns >= start_ns) and (stop_ns is None or t_ns < stop_ns):
                    yield topic, t_ns, msg
        except _OSI_ERRORS as err:
            offset = self._records[read][0] if read < len(self._records) else None
            if offset is None and self._damage is not None:
                offset = self._damage[0]
            raise CorruptLogError(
                self.path, f"{type(err).__name__}: {err}", topic=topic, t_ns=t_ns, offset=offset
            ) from err

    def attachments(self) -> Iterator[tuple[str, bytes]]:
        """A trace has no attachments (its lane geometry is not read: use ``--map``)."""
        return iter(())

    def close(self) -> None:
        """Nothing stays open between reads."""
