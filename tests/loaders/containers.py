"""Rewrite the sample logs into other containers with the libraries' writers (no binaries).

| writer | from | gives |
|---|---|---|
| ``ros1_mcap`` | a ROS 1 ``.bag`` | MCAP with ``ros1msg`` schemas and ``ros1`` messages |
| ``bare_db3`` | a rosbag2 directory | one uncompressed ``.db3`` file, no ``metadata.yaml`` |
| ``split_rosbag2`` | a rosbag2 directory | a rosbag2 directory of two ``.db3`` files |
| ``with_service_events`` | a ROS 2 ``.mcap`` | the same MCAP plus a Jazzy service-event channel |
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from mcap.reader import make_reader
from mcap.writer import Writer as McapWriter
from rosbags.highlevel import AnyReader
from rosbags.rosbag2 import StoragePlugin
from rosbags.rosbag2 import Writer as Bag2Writer
from ruamel.yaml import YAML

from loaders.typestore import typestore

if TYPE_CHECKING:
    from pathlib import Path

__all__ = ["bare_db3", "ros1_mcap", "split_rosbag2", "with_service_events"]


def ros1_mcap(bag: Path, out: Path) -> Path:
    """The messages of a ROS 1 bag in an MCAP file (ROS 1 encoding, zstd chunks of 16 KiB)."""
    with AnyReader([bag]) as reader, out.open("wb") as f:
        writer = McapWriter(f, chunk_size=16 * 1024)
        writer.start(profile="ros1", library="rss-workbench tests")
        channels: dict[int, int] = {}
        for conn in reader.connections:
            name = conn.msgtype.replace("/msg/", "/")
            schema = writer.register_schema(name, "ros1msg", conn.msgdef.data.encode())
            channels[conn.id] = writer.register_channel(conn.topic, "ros1", schema)
        for conn, t_ns, raw in reader.messages():
            writer.add_message(channels[conn.id], t_ns, bytes(raw), t_ns)
        writer.finish()  # type: ignore[no-untyped-call]
    return out


def _rewrite(src: Path, dst: Path, keep: Any) -> int:
    """Copy the messages of ``src`` with ``keep(index)`` true into a new rosbag2 ``dst``."""
    store = typestore(2)
    written = 0
    with (
        AnyReader([src], default_typestore=store) as reader,
        Bag2Writer(dst, version=9, storage_plugin=StoragePlugin.SQLITE3) as writer,
    ):
        conns = {
            c.id: writer.add_connection(c.topic, c.msgtype, typestore=store)
            for c in reader.connections
        }
        for k, (conn, t_ns, raw) in enumerate(reader.messages()):
            if keep(k):
                writer.write(conns[conn.id], t_ns, raw)
                written += 1
    return written


def bare_db3(rosbag2: Path, out_dir: Path) -> Path:
    """The messages of a rosbag2 directory in one uncompressed ``.db3`` without metadata."""
    bag = out_dir / "bag"
    _rewrite(rosbag2, bag, lambda _: True)
    db3 = next(bag.glob("*.db3"))
    return db3.rename(out_dir / "drive.db3")


def split_rosbag2(rosbag2: Path, out_dir: Path) -> Path:
    """A rosbag2 directory whose messages are split over two ``.db3`` files."""
    with AnyReader([rosbag2], default_typestore=typestore(2)) as reader:
        half = reader.message_count // 2
    parts = [out_dir / "part0", out_dir / "part1"]
    _rewrite(rosbag2, parts[0], lambda k: k < half)
    _rewrite(rosbag2, parts[1], lambda k: k >= half)
    bag = out_dir / "split"
    bag.mkdir()
    infos = []
    for k, part in enumerate(parts):
        info = YAML(typ="safe").load(part / "metadata.yaml")["rosbag2_bagfile_information"]
        db3 = next(part.glob("*.db3")).rename(bag / f"split_{k}.db3")
        info["relative_file_paths"] = [db3.name]
        info["files"][0]["path"] = db3.name
        infos.append(info)
    merged = infos[0]
    merged["relative_file_paths"] += infos[1]["relative_file_paths"]
    merged["files"] += infos[1]["files"]
    merged["message_count"] += infos[1]["message_count"]
    end = infos[1]["starting_time"]["nanoseconds_since_epoch"] + infos[1]["duration"]["nanoseconds"]
    merged["duration"]["nanoseconds"] = end - merged["starting_time"]["nanoseconds_since_epoch"]
    counts = {t["topic_metadata"]["name"]: t for t in merged["topics_with_message_count"]}
    for topic in infos[1]["topics_with_message_count"]:
        name = topic["topic_metadata"]["name"]
        if name in counts:
            counts[name]["message_count"] += topic["message_count"]
        else:
            merged["topics_with_message_count"].append(topic)
    YAML(typ="safe").dump({"rosbag2_bagfile_information": merged}, bag / "metadata.yaml")
    return bag


def with_service_events(mcap: Path, out: Path) -> Path:
    """The ROS 2 MCAP plus a service-event channel as Jazzy records it (no usable schema)."""
    with mcap.open("rb") as f, out.open("wb") as g:
        reader = make_reader(f)
        writer = McapWriter(g)
        writer.start(profile="ros2", library="rss-workbench tests")
        schemas: dict[int, int] = {}
        channels: dict[int, int] = {}
        t_first = None
        for schema, channel, message in reader.iter_messages():
            assert schema is not None
            if schema.id not in schemas:
                schemas[schema.id] = writer.register_schema(
                    schema.name, schema.encoding, schema.data
                )
            if channel.id not in channels:
                channels[channel.id] = writer.register_channel(
                    channel.topic, channel.message_encoding, schemas[schema.id], channel.metadata
                )
            writer.add_message(
                channels[channel.id], message.log_time, message.data, message.publish_time
            )
            t_first = message.log_time if t_first is None else t_first
        service = writer.register_schema("std_srvs/srv/SetBool_Event", "unknown", b"")
        topic = writer.register_channel("/set_flag/_service_event", "cdr", service)
        writer.add_message(topic, t_first or 0, bytes(48), t_first or 0)
        writer.finish()  # type: ignore[no-untyped-call]
    return out
