"""Write the synthetic drive in every format we read, with the libraries' own writers.

| format | ego | objects | plan |
|-------------------|----------------------------|----------------------------|-------------|
| ros1-bag | nav_msgs/Odometry | derived_object_msgs | nav_msgs/Path |
| rosbag2-sqlite3 | nav_msgs/Odometry | autoware PredictedObjects | autoware Trajectory |
| rosbag2-mcap | geometry_msgs/PoseStamped | autoware TrackedObjects | nav_msgs/Path |
| ros2-mcap | nav_msgs/Odometry | vision_msgs Detection3DArray | autoware Trajectory |
| mcap-json | workbench.EgoState | workbench.ObjectList | workbench.Plan |
| mcap-protobuf | foxglove.Odometry | foxglove.SceneUpdate | — |
"""

from __future__ import annotations

import json
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from mcap.writer import CompressionType
from mcap.writer import Writer as McapWriter
from rosbags.rosbag1 import Writer as Bag1Writer
from rosbags.rosbag2 import StoragePlugin
from rosbags.rosbag2 import Writer as Bag2Writer

from loaders.typestore import typestore
from tests.loaders import rosmsgs
from tests.loaders import synthetic as syn

if TYPE_CHECKING:
    from collections.abc import Callable, Iterable
    from pathlib import Path

__all__ = [
    "FORMATS",
    "Entry",
    "expected_id",
    "ros_entries",
    "write_format",
    "write_mcap_json",
    "write_mcap_protobuf",
    "write_ros1_bag",
    "write_ros2_mcap",
    "write_rosbag2",
]

ODOM = "nav_msgs/msg/Odometry"


@dataclass(frozen=True)
class Entry:
    """One message to write."""

    topic: str
    msgtype: str
    t_ns: int
    msg: Any


def _sorted(entries: Iterable[Entry]) -> list[Entry]:
    return sorted(entries, key=lambda e: e.t_ns)


def ros_entries(ros_version: int, ego: str, objects: str, plan: str | None) -> list[Entry]:
    """The synthetic drive as ROS messages of the given types."""
    ts = typestore(ros_version)
    ego_make: Callable[[Any, int], Any] = {
        ODOM: rosmsgs.odometry,
        "geometry_msgs/msg/PoseStamped": rosmsgs.pose_stamped,
    }[ego]
    obj_make: dict[str, Callable[[Any, int], Any]] = {
        "derived_object_msgs/msg/ObjectArray": rosmsgs.carla_objects,
        "autoware_perception_msgs/msg/PredictedObjects": lambda s, t: rosmsgs.autoware_objects(
            s, t, tracked=False
        ),
        "autoware_perception_msgs/msg/TrackedObjects": lambda s, t: rosmsgs.autoware_objects(
            s, t, tracked=True
        ),
        "vision_msgs/msg/Detection3DArray": rosmsgs.detection3d,
    }
    out = [Entry("/ego/odometry", ego, t, ego_make(ts, t)) for t in syn.ego_times()]
    out += [
        Entry("/perception/objects", objects, t, obj_make[objects](ts, t))
        for t in syn.object_times()
    ]
    if plan is not None:
        plan_make = rosmsgs.path if plan == "nav_msgs/msg/Path" else rosmsgs.trajectory
        out += [Entry("/planning/trajectory", plan, t, plan_make(ts, t)) for t in syn.plan_times()]
    return _sorted(out)


def write_ros1_bag(path: Path, entries: Iterable[Entry]) -> Path:
    """A ROS 1 bag (LZ4 chunks)."""
    ts = typestore(1)
    writer = Bag1Writer(path)
    writer.set_compression(Bag1Writer.CompressionFormat.LZ4)
    conns: dict[str, Any] = {}
    with writer:
        for e in entries:
            if e.topic not in conns:
                conns[e.topic] = writer.add_connection(e.topic, e.msgtype, typestore=ts)
            writer.write(conns[e.topic], e.t_ns, ts.serialize_ros1(e.msg, e.msgtype))
    return path


def write_rosbag2(path: Path, entries: Iterable[Entry], storage: str) -> Path:
    """A rosbag2 directory with ``sqlite3`` or ``mcap`` storage."""
    ts = typestore(2)
    plugin = StoragePlugin.SQLITE3 if storage == "sqlite3" else StoragePlugin.MCAP
    conns: dict[str, Any] = {}
    with Bag2Writer(path, version=9, storage_plugin=plugin) as writer:
        for e in entries:
            if e.topic not in conns:
                conns[e.topic] = writer.add_connection(e.topic, e.msgtype, typestore=ts)
            writer.write(conns[e.topic], e.t_ns, ts.serialize_cdr(e.msg, e.msgtype))
    return path


def write_ros2_mcap(
    path: Path,
    entries: Iterable[Entry],
    attachments: dict[str, bytes] | None = None,
    chunk_size: int = 256 * 1024,
    compression: CompressionType = CompressionType.ZSTD,
) -> Path:
    """A bare ROS 2 MCAP file (``ros2msg`` schemas, ``cdr`` messages) via ``mcap``'s writer."""
    ts = typestore(2)
    with path.open("wb") as f:
        writer = McapWriter(f, chunk_size=chunk_size, compression=compression)
        writer.start(profile="ros2", library="rss-workbench tests")
        schemas: dict[str, int] = {}
        channels: dict[str, int] = {}
        for e in entries:
            if e.msgtype not in schemas:
                text = ts.generate_msgdef(e.msgtype, ros_version=2)[0]
                schemas[e.msgtype] = writer.register_schema(e.msgtype, "ros2msg", text.encode())
            if e.topic not in channels:
                channels[e.topic] = writer.register_channel(e.topic, "cdr", schemas[e.msgtype])
            data = ts.serialize_cdr(e.msg, e.msgtype)
            writer.add_message(channels[e.topic], e.t_ns, bytes(data), e.t_ns)
        for name, blob in (attachments or {}).items():
            writer.add_attachment(syn.T0, syn.T0, name, "application/xml", blob)
        writer.finish()  # type: ignore[no-untyped-call]
    return path


def _json_entries() -> list[tuple[str, str, int, dict[str, Any]]]:
    out: list[tuple[str, str, int, dict[str, Any]]] = []
    for t in syn.ego_times():
        x, y, yaw = syn.ego_state(t)
        ego = {"timestamp_ns": t, "x_m": x, "y_m": y, "yaw_rad": yaw, "speed_mps": syn.EGO_SPEED}
        out.append(("/ego/state", "workbench.EgoState", t, ego))
    for t in syn.object_times():
        objs = []
        for a in syn.ACTORS:
            ax, ay = syn.actor_state(a, t)
            objs.append(
                {
                    "id": str(a.id),
                    "class": a.cls,
                    "x_m": ax,
                    "y_m": ay,
                    "yaw_rad": a.yaw,
                    "vx_mps": a.vx,
                    "vy_mps": a.vy,
                    "length_m": a.length,
                    "width_m": a.width,
                    "height_m": a.height,
                }
            )
        out.append(("/objects", "workbench.ObjectList", t, {"timestamp_ns": t, "objects": objs}))
    for t in syn.plan_times():
        pts = [
            {"x_m": x, "y_m": y, "yaw_rad": 0.0, "t_offset_s": s, "speed_mps": v}
            for x, y, s, v in syn.plan_points(t)
        ]
        out.append(("/plan", "workbench.Plan", t, {"timestamp_ns": t, "points": pts}))
    return sorted(out, key=lambda e: e[2])


def write_mcap_json(path: Path, attachments: dict[str, bytes] | None = None) -> Path:
    """A non-ROS MCAP with our JSON schemas (``jsonschema`` schemas, ``json`` messages)."""
    with path.open("wb") as f:
        writer = McapWriter(f)
        writer.start(profile="", library="rss-workbench tests")
        channels: dict[str, int] = {}
        for topic, name, t, payload in _json_entries():
            if topic not in channels:
                sid = writer.register_schema(
                    name, "jsonschema", json.dumps({"type": "object"}).encode()
                )
                channels[topic] = writer.register_channel(topic, "json", sid)
            writer.add_message(channels[topic], t, json.dumps(payload).encode(), t)
        for name, blob in (attachments or {}).items():
            writer.add_attachment(syn.T0, syn.T0, name, "application/xml", blob)
        writer.finish()  # type: ignore[no-untyped-call]
    return path


def _pb_stamp(t_ns: int) -> Any:
    from google.protobuf.timestamp_pb2 import Timestamp  # noqa: PLC0415

    return Timestamp(seconds=t_ns // 10**9, nanos=t_ns % 10**9)


def _pb_pose(x: float, y: float, z: float, yaw: float) -> Any:
    import math  # noqa: PLC0415

    from foxglove_schemas_protobuf.Pose_pb2 import Pose  # noqa: PLC0415
    from foxglove_schemas_protobuf.Quaternion_pb2 import Quaternion  # noqa: PLC0415
    from foxglove_schemas_protobuf.Vector3_pb2 import Vector3  # noqa: PLC0415

    return Pose(
        position=Vector3(x=x, y=y, z=z),
        orientation=Quaternion(z=math.sin(yaw / 2), w=math.cos(yaw / 2)),
    )


def write_mcap_protobuf(path: Path, ego_kind: str = "odometry") -> Path:
    """A Foxglove protobuf MCAP: ego as ``foxglove.Odometry`` (or ``pose``/``transform``)."""
    from foxglove_schemas_protobuf.CubePrimitive_pb2 import CubePrimitive  # noqa: PLC0415
    from foxglove_schemas_protobuf.FrameTransform_pb2 import FrameTransform  # noqa: PLC0415
    from foxglove_schemas_protobuf.KeyValuePair_pb2 import KeyValuePair  # noqa: PLC0415
    from foxglove_schemas_protobuf.Odometry_pb2 import Odometry  # noqa: PLC0415
    from foxglove_schemas_protobuf.PoseInFrame_pb2 import PoseInFrame  # noqa: PLC0415
    from foxglove_schemas_protobuf.SceneEntity_pb2 import SceneEntity  # noqa: PLC0415
    from foxglove_schemas_protobuf.SceneUpdate_pb2 import SceneUpdate  # noqa: PLC0415
    from foxglove_schemas_protobuf.Vector3_pb2 import Vector3  # noqa: PLC0415
    from mcap_protobuf.writer import Writer as PbWriter  # noqa: PLC0415

    msgs: list[tuple[str, int, Any]] = []
    for t in syn.ego_times():
        x, y, yaw = syn.ego_state(t)
        p = _pb_pose(x, y, 0.0, yaw)
        if ego_kind == "odometry":
            ego: Any = Odometry(
                timestamp=_pb_stamp(t),
                frame_id="map",
                body_frame_id="ego",
                pose=p,
                linear_velocity=Vector3(x=syn.EGO_SPEED),
            )
        elif ego_kind == "pose":
            ego = PoseInFrame(timestamp=_pb_stamp(t), frame_id="map", pose=p)
        else:
            ego = FrameTransform(
                timestamp=_pb_stamp(t),
                parent_frame_id="map",
                child_frame_id="ego",
                translation=p.position,
                rotation=p.orientation,
            )
        msgs.append(("/ego", t, ego))
    for t in syn.object_times():
        entities = []
        for a in syn.ACTORS:
            ax, ay = syn.actor_state(a, t)
            cube = CubePrimitive(
                pose=_pb_pose(ax, ay, 0.0, a.yaw), size=Vector3(x=a.length, y=a.width, z=a.height)
            )
            entities.append(
                SceneEntity(
                    timestamp=_pb_stamp(t),
                    frame_id="map",
                    id=str(a.id),
                    cubes=[cube],
                    metadata=[KeyValuePair(key="class", value=a.cls)],
                )
            )
        msgs.append(("/scene/objects", t, SceneUpdate(entities=entities)))
    with path.open("wb") as f:
        writer = PbWriter(f)
        for topic, t, msg in sorted(msgs, key=lambda m: m[1]):
            writer.write_message(topic, msg, log_time=t, publish_time=t)
        writer.finish()  # type: ignore[no-untyped-call]
    return path


def _ros(ros_version: int, ego: str, objects: str, plan: str | None) -> list[Entry]:
    return ros_entries(ros_version, ego, objects, plan)


#: Format name → writer into a directory; the contract test runs over all of them.
FORMATS: dict[str, Callable[[Path], Path]] = {
    "ros1-bag": lambda d: write_ros1_bag(
        d / "drive.bag", _ros(1, ODOM, "derived_object_msgs/msg/ObjectArray", "nav_msgs/msg/Path")
    ),
    "rosbag2-sqlite3": lambda d: write_rosbag2(
        d / "drive_sqlite3",
        _ros(
            2,
            ODOM,
            "autoware_perception_msgs/msg/PredictedObjects",
            "autoware_planning_msgs/msg/Trajectory",
        ),
        "sqlite3",
    ),
    "rosbag2-mcap": lambda d: write_rosbag2(
        d / "drive_mcap",
        _ros(
            2,
            "geometry_msgs/msg/PoseStamped",
            "autoware_perception_msgs/msg/TrackedObjects",
            "nav_msgs/msg/Path",
        ),
        "mcap",
    ),
    "ros2-mcap": lambda d: write_ros2_mcap(
        d / "drive.mcap",
        _ros(2, ODOM, "vision_msgs/msg/Detection3DArray", "autoware_planning_msgs/msg/Trajectory"),
    ),
    "mcap-json": lambda d: write_mcap_json(d / "drive_json.mcap"),
    "mcap-protobuf": lambda d: write_mcap_protobuf(d / "drive_pb.mcap"),
}


def write_format(name: str, directory: Path) -> Path:
    """Write the synthetic drive as ``name`` (a key of ``FORMATS``) into ``directory``."""
    return FORMATS[name](directory)


def expected_id(fmt: str, actor_id: int) -> str:
    """The object id the loader should report for a synthetic actor in format ``fmt``."""
    return rosmsgs.uuid_hex(actor_id) if fmt.startswith("rosbag2") else str(actor_id)
