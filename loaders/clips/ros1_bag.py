"""A ROS 1 clip also as a ROS 1 bag: the same raw records, for tools that read only bags.

rosbags (0.11) reads MCAP files of the ``ros2`` profile only (``AnyReaderError: Profile is
not ros2``), and ROS 1 tooling reads bags. The MCAP clip of a ROS 1 log is therefore
re-written record by record as a ``.bag`` beside it: definitions from the MCAP schemas,
MD5 sums and caller ids from the channel metadata, payloads unchanged.
"""

from __future__ import annotations

import contextlib
from typing import TYPE_CHECKING

from mcap.reader import make_reader
from rosbags.rosbag1 import Writer

from loaders.clips.errors import ClipWriteError

if TYPE_CHECKING:
    from pathlib import Path

    from rosbags.interfaces import Connection

__all__ = ["write_ros1_bag"]


def _msgtype(schema_name: str) -> str:
    package, _, name = schema_name.partition("/")
    return f"{package}/msg/{name}"


def write_ros1_bag(clip: Path, bag: Path) -> int:
    """Write the ``ros1`` MCAP ``clip`` as the ROS 1 bag ``bag``; return the message count.

    Written to ``<bag>.part`` and renamed when complete.

    Raises:
        ValueError: ``clip`` is not a ``ros1`` MCAP.
    """
    part = bag.with_name(bag.name + ".part")
    count = 0
    try:
        part.unlink(missing_ok=True)
        with clip.open("rb") as f:
            reader = make_reader(f)
            if reader.get_header().profile != "ros1":
                msg = f"{clip}: not a ros1 MCAP"
                raise ValueError(msg)
            writer = Writer(part)
            writer.open()
            try:
                connections: dict[int, Connection] = {}
                for schema, channel, message in reader.iter_messages():
                    conn = connections.get(channel.id)
                    if conn is None:
                        meta = channel.metadata
                        conn = connections[channel.id] = writer.add_connection(
                            channel.topic,
                            _msgtype(schema.name if schema else ""),
                            msgdef=(schema.data.decode() if schema else ""),
                            md5sum=meta.get("md5sum"),
                            callerid=meta.get("callerid") or None,
                            latching=int(meta["latching"]) if meta.get("latching") else None,
                        )
                    writer.write(conn, message.log_time, message.data)
                    count += 1
            finally:
                writer.close()
        part.replace(bag)
    except OSError as err:
        raise ClipWriteError(bag, err.strerror or type(err).__name__) from err
    finally:
        with contextlib.suppress(OSError):
            part.unlink(missing_ok=True)
    return count
