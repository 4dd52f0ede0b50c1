"""Raw records of ROS bags (ROS 1 ``.bag``, rosbag2 directories, bare ``.db3``), for clips.

The payloads are copied as stored: a ROS 1 bag holds ROS 1 serialisation (MCAP profile
``ros1``, schema encoding ``ros1msg``), a rosbag2 holds CDR (profile ``ros2``, ``ros2msg``).
Definitions come from the bag where it has them (ROS 1 bags, rosbag2 from Iron on) and are
generated with rosbags' typestore for older rosbag2 bags that carry none.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from rosbags.highlevel import AnyReader
from rosbags.interfaces import ConnectionExtRosbag1, MessageDefinitionFormat

from loaders.clips.mcap_input import RawMessage
from loaders.clips.model import ChannelSpec, SchemaSpec
from loaders.errors import CorruptLogError, UnsupportedFormatError
from loaders.message_logs.rosbags_source import READ_ERRORS
from loaders.typestore import typestore

if TYPE_CHECKING:
    from collections.abc import Collection, Iterator
    from pathlib import Path

    from rosbags.interfaces import Connection

__all__ = ["BagClipInput"]


def _ros1_name(msgtype: str) -> str:
    return msgtype.replace("/msg/", "/", 1)


class BagClipInput:
    """Streams a ROS bag's raw messages as MCAP-ready records."""

    def __init__(self, path: Path) -> None:
        """Open ``path``.

        Raises:
            CorruptLogError: The bag's index cannot be read.
        """
        self.path = path
        self._reader = AnyReader([path], default_typestore=typestore(2))
        try:
            self._reader.open()
        except READ_ERRORS as err:
            raise CorruptLogError(path, f"cannot open the bag: {err}") from err
        self.profile = "ros2" if self._reader.is2 else "ros1"
        self._channels: dict[int, ChannelSpec] = {}
        #: Clips of bags are zstd-compressed MCAP.
        self.compression = "zstd"
        #: rosbags reads time windows through the bag's index.
        self.indexed = True

    def _spec(self, conn: Connection) -> ChannelSpec:
        spec = self._channels.get(conn.id)
        if spec is not None:
            return spec
        if self.profile == "ros1":
            schema = SchemaSpec(
                conn.msgtype, _ros1_name(conn.msgtype), "ros1msg", conn.msgdef.data.encode()
            )
            ext = conn.ext
            metadata = {"md5sum": conn.digest}
            if isinstance(ext, ConnectionExtRosbag1):
                metadata["callerid"] = ext.callerid or ""
                metadata["latching"] = str(int(ext.latching or 0))
            spec = ChannelSpec(conn.id, conn.topic, "ros1", schema, metadata)
        else:
            text = conn.msgdef.data
            encoding = "ros2idl" if conn.msgdef.format == MessageDefinitionFormat.IDL else "ros2msg"
            if conn.msgdef.format == MessageDefinitionFormat.NONE or not text:
                try:
                    text = self._reader.typestore.generate_msgdef(conn.msgtype, ros_version=2)[0]
                except READ_ERRORS as err:
                    raise UnsupportedFormatError(
                        self.path,
                        f"no message definition for {conn.msgtype} (bag has none, none known)",
                        topic=conn.topic,
                    ) from err
                encoding = "ros2msg"
            schema = SchemaSpec(conn.msgtype, conn.msgtype, encoding, text.encode())
            spec = ChannelSpec(conn.id, conn.topic, "cdr", schema, {})
        self._channels[conn.id] = spec
        return spec

    def messages(
        self, start_ns: int, end_ns: int, topics: Collection[str] | None
    ) -> Iterator[RawMessage]:
        """Messages with ``start_ns <= log_time <= end_ns`` on ``topics`` (``None``: all).

        Raises:
            CorruptLogError: The bag breaks off; every message before the damage was yielded.
        """
        conns = [c for c in self._reader.connections if topics is None or c.topic in topics]
        last = None
        try:
            for conn, t_ns, raw in self._reader.messages(
                connections=conns, start=start_ns, stop=end_ns + 1
            ):
                last = t_ns
                yield RawMessage(self._spec(conn), t_ns, bytes(raw), t_ns, 0)
        except READ_ERRORS as err:
            raise CorruptLogError(
                self.path, f"{type(err).__name__} {err}".strip(), t_ns=last
            ) from err

    def attachments(self) -> list[tuple[str, str, bytes, int, int]]:
        """Bags have no attachments."""
        return []

    def metadata(self) -> list[tuple[str, dict[str, str]]]:
        """Bags have no metadata records."""
        return []

    def close(self) -> None:
        """Close the bag."""
        self._reader.close()
