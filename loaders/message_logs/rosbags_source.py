"""ROS logs through rosbags' ``AnyReader``: ROS 1 bags, rosbag2 directories, ROS 2 MCAP files."""

from __future__ import annotations

import re
import sqlite3
import struct
from typing import TYPE_CHECKING, Any

import apsw
from backports.zstd import ZstdError
from rosbags.highlevel import AnyReader, AnyReaderError
from rosbags.rosbag1 import ReaderError as Bag1ReaderError
from rosbags.rosbag2 import ReaderError as Bag2ReaderError
from rosbags.serde import SerdeError
from rosbags.typesys.base import TypesysError

from loaders.drive import TopicInfo
from loaders.errors import CorruptLogError, EmptyLogError, UnsupportedFormatError
from loaders.message_logs.mcap_source import osm_attachments
from loaders.message_logs.registry import normalize_msgtype
from loaders.typestore import typestore

if TYPE_CHECKING:
    from collections.abc import Collection, Iterator
    from pathlib import Path

__all__ = ["READ_ERRORS", "RosbagsSource"]

#: What a damaged container raises while reading (wrapped into ``CorruptLogError``).
READ_ERRORS: tuple[type[Exception], ...] = (
    AnyReaderError,
    apsw.Error,  # rosbag2 sqlite3 storage: a damaged page met while reading messages
    Bag1ReaderError,
    Bag2ReaderError,
    struct.error,
    EOFError,
    ValueError,
    OverflowError,  # a record length past the index range
    MemoryError,  # a record length past what memory holds
    IndexError,
    KeyError,
    OSError,
    RuntimeError,  # lz4 frame errors
    ZstdError,
    AssertionError,  # rosbags asserts on some malformed ROS 1 records
    SerdeError,
    TypesysError,
    sqlite3.Error,
)
_SERIALIZATION = re.compile(r"Serialization format (\{.*\}) is not supported")
#: What opening a container raises besides: rosbags computes with a rosbag2
#: ``metadata.yaml``'s values before it checks their types.
_OPEN_ERRORS: tuple[type[Exception], ...] = (*READ_ERRORS, TypeError, AttributeError)


def _size(path: Path) -> int:
    if path.is_dir():
        return sum(p.stat().st_size for p in path.iterdir() if p.is_file())
    return path.stat().st_size


class RosbagsSource:
    """A ROS log opened with ``AnyReader`` (``default_typestore`` for bags without definitions).

    Raises ``CorruptLogError`` at open when the container index cannot be read (rosbags
    needs the index of bags and the summary of MCAP files); the offset is the file size,
    i.e. where the data ends.
    """

    def __init__(self, path: Path, source_format: str) -> None:
        """Open ``path``; see the class docstring for errors."""
        self.path = path
        self.source_format = source_format
        self.notes: dict[str, str] = {}
        self._reader = AnyReader([path], default_typestore=typestore(2))
        try:
            self._reader.open()
        except SyntaxError as err:  # rosbags compiles the definitions (see check_definitions)
            detail = f"a message definition has a name that is not a Python name: {err.msg}"
            raise CorruptLogError(path, detail, offset=_size(path)) from err
        except _OPEN_ERRORS as err:
            if found := _SERIALIZATION.search(str(err)):
                raise UnsupportedFormatError(
                    path, f"serialization format {found.group(1)}; only cdr is read"
                ) from err
            raise CorruptLogError(
                path, f"cannot read the index: {type(err).__name__}: {err}", offset=_size(path)
            ) from err
        if self._reader.message_count == 0:
            self._reader.close()
            raise EmptyLogError(path, "the container holds no messages")
        self.start_ns = int(self._reader.start_time)
        self.end_ns = int(self._reader.end_time) - 1  # rosbags reports last + 1
        counts: dict[str, int] = {}
        types: dict[str, str] = {}
        for conn in self._reader.connections:
            if not isinstance(conn.topic, str) or not isinstance(conn.msgtype, str):
                self._reader.close()  # a damaged sqlite3 topics table can hold bytes
                detail = "a topic name or message type is not text"
                value = (conn.topic, conn.msgtype)
                raise CorruptLogError(path, detail, value=value, offset=_size(path))
            counts[conn.topic] = counts.get(conn.topic, 0) + int(conn.msgcount)
            types[conn.topic] = normalize_msgtype(conn.msgtype)
        self.topics = tuple(TopicInfo(t, types[t], counts[t]) for t in sorted(types))

    def messages(
        self, topics: Collection[str], start_ns: int | None, stop_ns: int | None
    ) -> Iterator[tuple[str, int, Any]]:
        """Yield decoded messages of ``topics`` in log-time order; see ``MessageSource``."""
        conns = [c for c in self._reader.connections if c.topic in topics]
        topic, t_ns = None, None
        try:
            for conn, t, raw in self._reader.messages(conns, start=start_ns, stop=stop_ns):
                topic, t_ns = conn.topic, t
                yield conn.topic, t, self._reader.deserialize(raw, conn.msgtype)
        except READ_ERRORS as err:
            where = "after the last readable message" if topic else "before any message"
            raise CorruptLogError(
                self.path,
                f"{where}: {type(err).__name__}: {err}",
                topic=topic,
                t_ns=t_ns,
                offset=self._chunk_offset(t_ns, start_ns),
            ) from err

    def _chunk_offset(self, last_ns: int | None, start_ns: int | None) -> int | None:
        """Byte offset of the ROS 1 chunk that failed (``None`` for rosbag2 storage).

        rosbags loads a chunk once the merge reaches its start time: every chunk starting at
        or before the last good message was read, so the damaged one is the first chunk
        starting after it (or the first one read at all).
        """
        chunks = sorted(
            (info.pos, info.start_time, info.end_time)
            for reader in self._reader.readers
            for info in getattr(reader, "chunk_infos", ())
        )
        if last_ns is not None:
            after = [pos for pos, start, _ in chunks if start > last_ns]
        else:
            after = [pos for pos, _, end in chunks if start_ns is None or end >= start_ns]
        return after[0] if after and len(self._reader.readers) == 1 else None

    def attachments(self) -> Iterator[tuple[str, bytes]]:
        """``.osm`` attachments of the MCAP file(s); bags and sqlite3 storage have none."""
        if self.path.is_dir():
            files = sorted(self.path.glob("*.mcap"))
        else:
            files = [self.path] if self.path.suffix.lower() == ".mcap" else []
        for file in files:
            yield from osm_attachments(file)

    def close(self) -> None:
        """Close the reader."""
        if self._reader.stack is not None:
            self._reader.close()
