"""Re-write a CARLA sample log's objects (``derived_object_msgs/ObjectArray``) in other types.

The ego odometry and the path are copied; every object message becomes one message of the
target type built from the same poses, sizes, classes and (map-frame) velocities. The
target is a ROS 2 MCAP, or a ROS 1 bag when its suffix is ``.bag`` (from a ROS 1 source).
:func:`rewrite_plan` does the same for the path (``nav_msgs/Path``) with plan types.
"""

from __future__ import annotations

import math
import shutil
from typing import TYPE_CHECKING, Any

import numpy as np
from rosbags.highlevel import AnyReader

from loaders.typestore import typestore
from tests.loaders import fixtures
from tests.loaders.msgbuild import build

if TYPE_CHECKING:
    from collections.abc import Callable
    from pathlib import Path

__all__ = [
    "CARLA_TO_AUTOWARE",
    "CARLA_TO_LABEL",
    "PLAN_TARGETS",
    "TARGETS",
    "rewrite_objects",
    "rewrite_plan",
]

#: ``derived_object_msgs`` classification → Autoware ``ObjectClassification.label``.
CARLA_TO_AUTOWARE = {4: 7, 5: 6, 6: 1, 7: 2, 8: 5, 9: 1}
#: ``derived_object_msgs`` classification → Autoware.AI ``DetectedObject.label``.
CARLA_TO_LABEL = {4: "person", 5: "bicycle", 6: "car", 7: "truck", 8: "motorbike", 9: "car"}


def _vec(ts: Any, msgtype: str, v: Any) -> Any:
    return build(ts, msgtype, x=float(v.x), y=float(v.y), z=float(v.z))


def _pose(ts: Any, p: Any) -> Any:
    q = p.orientation
    orientation = build(ts, "geometry_msgs/msg/Quaternion", x=q.x, y=q.y, z=q.z, w=float(q.w))
    return build(
        ts,
        "geometry_msgs/msg/Pose",
        position=_vec(ts, "geometry_msgs/msg/Point", p.position),
        orientation=orientation,
    )


def _yaw(q: Any) -> float:
    return math.atan2(2 * (q.w * q.z + q.x * q.y), 1 - 2 * (q.y * q.y + q.z * q.z))


def _autoware(package: str, kind: str) -> Callable[[Any, Any], Any]:
    def make(ts: Any, msg: Any) -> Any:
        objs = []
        for obj in msg.objects:
            yaw = _yaw(obj.pose.orientation)
            vx, vy = float(obj.twist.linear.x), float(obj.twist.linear.y)
            body = build(
                ts,
                "geometry_msgs/msg/Vector3",
                x=math.cos(yaw) * vx + math.sin(yaw) * vy,
                y=-math.sin(yaw) * vx + math.cos(yaw) * vy,
            )
            twist = build(ts, "geometry_msgs/msg/Twist", linear=body)
            pwc = build(ts, "geometry_msgs/msg/PoseWithCovariance", pose=_pose(ts, obj.pose))
            twc = build(ts, "geometry_msgs/msg/TwistWithCovariance", twist=twist)
            prefix = "initial_" if kind == "Predicted" else ""
            kin_fields = {
                f"{prefix}pose_with_covariance": pwc,
                f"{prefix}twist_with_covariance": twc,
            }
            if kind == "Detected":
                kin_fields["has_twist"] = True
            d = obj.shape.dimensions
            label = CARLA_TO_AUTOWARE.get(int(obj.classification), 0)
            fields: dict[str, Any] = {
                "existence_probability": 1.0,
                "classification": [
                    build(ts, f"{package}/msg/ObjectClassification", label=label, probability=1.0)
                ],
                "kinematics": build(ts, f"{package}/msg/{kind}ObjectKinematics", **kin_fields),
                "shape": build(
                    ts,
                    f"{package}/msg/Shape",
                    dimensions=build(ts, "geometry_msgs/msg/Vector3", x=d[0], y=d[1], z=d[2]),
                ),
            }
            if kind != "Detected":
                fields["object_id"] = build(
                    ts,
                    "unique_identifier_msgs/msg/UUID",
                    uuid=np.frombuffer(int(obj.id).to_bytes(16, "big"), dtype=np.uint8).copy(),
                )
            objs.append(build(ts, f"{package}/msg/{kind}Object", **fields))
        return build(ts, f"{package}/msg/{kind}Objects", header=msg.header, objects=objs)

    return make


def _size(ts: Any, obj: Any) -> Any:
    """The object's box dimensions as a ``Vector3`` (length, width, height)."""
    x, y, z = obj.shape.dimensions[:3]
    return build(ts, "geometry_msgs/msg/Vector3", x=x, y=y, z=z)


def _markers(ts: Any, msg: Any) -> Any:
    markers = [
        build(
            ts,
            "visualization_msgs/msg/Marker",
            header=msg.header,
            ns="carla",
            id=int(obj.id),
            type=1,
            pose=_pose(ts, obj.pose),
            scale=_size(ts, obj),
        )
        for obj in msg.objects
    ]
    # a text label and a DELETEALL marker: counted and ignored by the decoder
    markers.append(build(ts, "visualization_msgs/msg/Marker", header=msg.header, type=9))
    markers.append(build(ts, "visualization_msgs/msg/Marker", header=msg.header, action=3))
    return build(ts, "visualization_msgs/msg/MarkerArray", markers=markers)


def _jsk(ts: Any, msg: Any) -> Any:
    boxes = [
        build(
            ts,
            "jsk_recognition_msgs/msg/BoundingBox",
            header=msg.header,
            pose=_pose(ts, obj.pose),
            dimensions=_size(ts, obj),
            value=1.0,
            label=int(obj.id),
        )
        for obj in msg.objects
    ]
    return build(ts, "jsk_recognition_msgs/msg/BoundingBoxArray", header=msg.header, boxes=boxes)


def _body(ts: Any, obj: Any) -> Any:
    """The object's map-frame velocity in its body frame (a ``Vector3``)."""
    yaw = _yaw(obj.pose.orientation)
    vx, vy = float(obj.twist.linear.x), float(obj.twist.linear.y)
    return build(
        ts,
        "geometry_msgs/msg/Vector3",
        x=math.cos(yaw) * vx + math.sin(yaw) * vy,
        y=-math.sin(yaw) * vx + math.cos(yaw) * vy,
    )


def _dims(ts: Any, obj: Any) -> Any:
    d = obj.shape.dimensions
    return build(ts, "geometry_msgs/msg/Vector3", x=d[0], y=d[1], z=d[2])


def _autoware_ai(ts: Any, msg: Any) -> Any:
    objs = [
        build(
            ts,
            "autoware_msgs/msg/DetectedObject",
            header=msg.header,
            id=int(obj.id),
            label=CARLA_TO_LABEL.get(int(obj.classification), "unknown"),
            score=1.0,
            valid=True,
            pose=_pose(ts, obj.pose),
            dimensions=_dims(ts, obj),
            velocity=build(ts, "geometry_msgs/msg/Twist", linear=_body(ts, obj)),
            pose_reliable=True,
            velocity_reliable=True,
        )
        for obj in msg.objects
    ]
    return build(ts, "autoware_msgs/msg/DetectedObjectArray", header=msg.header, objects=objs)


def _radar(ts: Any, msg: Any) -> Any:
    tracks = [
        build(
            ts,
            "radar_msgs/msg/RadarTrack",
            uuid=build(
                ts,
                "unique_identifier_msgs/msg/UUID",
                uuid=np.frombuffer(int(obj.id).to_bytes(16, "big"), dtype=np.uint8).copy(),
            ),
            position=_vec(ts, "geometry_msgs/msg/Point", obj.pose.position),
            velocity=_vec(ts, "geometry_msgs/msg/Vector3", obj.twist.linear),
            size=_dims(ts, obj),
            classification=32000 + CARLA_TO_AUTOWARE.get(int(obj.classification), 0),
        )
        for obj in msg.objects
    ]
    return build(ts, "radar_msgs/msg/RadarTracks", header=msg.header, tracks=tracks)


#: Target message type → converter ``(typestore, ObjectArray) → message``.
TARGETS: dict[str, Callable[[Any, Any], Any]] = {
    **{
        f"{package}/msg/{kind}Objects": _autoware(package, kind)
        for package in ("autoware_perception_msgs", "autoware_auto_perception_msgs")
        for kind in ("Detected", "Tracked", "Predicted")
    },
    "visualization_msgs/msg/MarkerArray": _markers,
    "jsk_recognition_msgs/msg/BoundingBoxArray": _jsk,
    "autoware_msgs/msg/DetectedObjectArray": _autoware_ai,
    "radar_msgs/msg/RadarTracks": _radar,
}


def _trajectory(package: str) -> Callable[[Any, Any], Any]:
    def make(ts: Any, msg: Any) -> Any:
        points = [
            build(
                ts,
                f"{package}/msg/TrajectoryPoint",
                time_from_start=build(
                    ts, "builtin_interfaces/msg/Duration", sec=k // 10, nanosec=k % 10 * 10**8
                ),
                pose=_pose(ts, p.pose),
                longitudinal_velocity_mps=10.0 + 0.5 * k,
            )
            for k, p in enumerate(msg.poses)
        ]
        return build(ts, f"{package}/msg/Trajectory", header=msg.header, points=points)

    return make


#: Plan type → converter ``(typestore, nav_msgs/Path) → message``: the path's poses, 0.1 s
#: apart, at 10 m/s + 0.5 m/s per point.
PLAN_TARGETS: dict[str, Callable[[Any, Any], Any]] = {
    f"{package}/msg/Trajectory": _trajectory(package)
    for package in ("autoware_planning_msgs", "autoware_auto_planning_msgs")
}


def _write(source: Path, target: Path, convert: Callable[[Any, str, Any], Any]) -> Path:
    """Copy ``source`` into ``target`` with ``convert(typestore, msgtype, msg)`` applied."""
    ros1 = target.suffix == ".bag"
    ts = typestore(1 if ros1 else 2)
    entries = []
    with AnyReader([source]) as reader:
        conns = [c for c in reader.connections if c.topic != "/tf"]
        for conn, t_ns, raw in reader.messages(connections=conns):
            msg = reader.deserialize(raw, conn.msgtype)
            entries.append(
                convert(ts, conn.topic, fixtures.Entry(conn.topic, conn.msgtype, t_ns, msg))
            )
    shutil.copy(source.with_suffix(".osm"), target.with_suffix(".osm"))
    if ros1:
        return fixtures.write_ros1_bag(target, entries)
    return fixtures.write_ros2_mcap(target, entries)


def rewrite_objects(source: Path, target: Path, msgtype: str) -> Path:
    """Write ``target`` (ROS 2 MCAP or ROS 1 ``.bag``, with ``source``'s map sidecar) with
    objects as ``msgtype``."""

    def convert(ts: Any, topic: str, entry: fixtures.Entry) -> fixtures.Entry:
        if entry.msgtype != "derived_object_msgs/msg/ObjectArray":
            return entry
        return fixtures.Entry("/objects", msgtype, entry.t_ns, TARGETS[msgtype](ts, entry.msg))

    return _write(source, target, convert)


def rewrite_plan(source: Path, target: Path, msgtype: str) -> Path:
    """Write ``target`` with the path (``nav_msgs/Path``) as the plan type ``msgtype``."""

    def convert(ts: Any, topic: str, entry: fixtures.Entry) -> fixtures.Entry:
        if entry.msgtype != "nav_msgs/msg/Path":
            return entry
        return fixtures.Entry(topic, msgtype, entry.t_ns, PLAN_TARGETS[msgtype](ts, entry.msg))

    return _write(source, target, convert)
