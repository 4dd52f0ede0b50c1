"""Decoders for Foxglove protobuf schemas in MCAP: ego poses and ``foxglove.SceneUpdate``.

``foxglove.Odometry`` carries its velocities in the body frame, like ``nav_msgs/Odometry``
(signed speed = ``linear_velocity.x``, yaw rate = ``angular_velocity.z``);
``foxglove.PoseInFrame`` and ``foxglove.FrameTransform`` are pose-only (the frame assembler
derives speed and yaw rate by finite differences).

A ``SceneUpdate`` message is read as the complete object list at its time: every entity
with at least one cube becomes a row (the first cube is the box; its size is the full box),
the entity id is the object id and the metadata key ``class`` the class name. Deletions and
lifetimes are not replayed. It carries no velocity, so ``has_velocity=False``.
"""

from __future__ import annotations

from typing import Any

from loaders.message_logs.poses import (
    ego_sample_from_pose,
    protobuf_stamp_ns,
    yaw_from_quaternion,
)
from loaders.message_logs.samples import EgoSample, ObjectColumns, class_from_name

__all__ = [
    "decode_foxglove_frame_transform",
    "decode_foxglove_odometry",
    "decode_foxglove_pose_in_frame",
    "decode_scene_update",
]

_NAN = float("nan")


def decode_foxglove_odometry(msg: Any) -> EgoSample:
    """``foxglove.Odometry``: velocities in the body frame, like ``nav_msgs/Odometry``."""
    return ego_sample_from_pose(
        protobuf_stamp_ns(msg.timestamp),
        msg.pose,
        float(msg.linear_velocity.x),
        float(msg.angular_velocity.z),
    )


def decode_foxglove_pose_in_frame(msg: Any) -> EgoSample:
    """``foxglove.PoseInFrame``: pose only."""
    return ego_sample_from_pose(protobuf_stamp_ns(msg.timestamp), msg.pose, _NAN, _NAN)


def decode_foxglove_frame_transform(msg: Any) -> EgoSample:
    """``foxglove.FrameTransform``: the ego transform (parent = map, child = ego body)."""
    t, q = msg.translation, msg.rotation
    return EgoSample(
        protobuf_stamp_ns(msg.timestamp),
        float(t.x),
        float(t.y),
        float(t.z),
        yaw_from_quaternion(q.x, q.y, q.z, q.w),
    )


def _metadata_class(entity: Any) -> str:
    for pair in entity.metadata:
        if pair.key == "class":
            return str(pair.value)
    return ""


def decode_scene_update(msg: Any) -> ObjectColumns:
    """``foxglove.SceneUpdate``: cubes → boxes, entity id → id, metadata ``class`` → class."""
    ids, classes, rows = [], [], []
    stamp: int | None = None
    for entity in msg.entities:
        if not entity.cubes:
            continue
        cube = entity.cubes[0]
        p, q, s = cube.pose.position, cube.pose.orientation, cube.size
        if stamp is None and entity.HasField("timestamp"):
            stamp = protobuf_stamp_ns(entity.timestamp)
        ids.append(str(entity.id))
        classes.append(class_from_name(_metadata_class(entity)))
        yaw = yaw_from_quaternion(q.x, q.y, q.z, q.w)
        rows.append((p.x, p.y, p.z, yaw, _NAN, _NAN, s.x, s.y, s.z))
    return ObjectColumns.from_rows(stamp, ids, classes, rows, has_velocity=False)
