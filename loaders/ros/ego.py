"""Ego decoders: ROS odometry/pose messages, Foxglove protobuf poses and our JSON ego schema.

``nav_msgs/Odometry`` (and ``foxglove.Odometry``) carry the twist in the *child* (body)
frame, so the signed speed along the heading is ``twist.linear.x`` and the yaw rate is
``twist.angular.z``. Pose-only messages leave speed and yaw rate NaN; the frame assembler
derives them by finite differences.
"""

from __future__ import annotations

from typing import Any

from loaders.ros.poses import protobuf_stamp_ns, ros_stamp_ns, yaw_from_quaternion
from loaders.ros.samples import EgoSample

__all__ = [
    "decode_foxglove_frame_transform",
    "decode_foxglove_odometry",
    "decode_foxglove_pose_in_frame",
    "decode_json_ego",
    "decode_odometry",
    "decode_pose_stamped",
]


def _from_pose(stamp_ns: int | None, pose: Any, speed: float, yaw_rate: float) -> EgoSample:
    p, q = pose.position, pose.orientation
    return EgoSample(
        stamp_ns,
        float(p.x),
        float(p.y),
        float(p.z),
        yaw_from_quaternion(q.x, q.y, q.z, q.w),
        speed,
        yaw_rate,
    )


def decode_odometry(msg: Any) -> EgoSample:
    """``nav_msgs/Odometry``: pose in the header frame, twist in the child frame."""
    twist = msg.twist.twist
    return _from_pose(
        ros_stamp_ns(msg.header.stamp),
        msg.pose.pose,
        float(twist.linear.x),
        float(twist.angular.z),
    )


def decode_pose_stamped(msg: Any) -> EgoSample:
    """``geometry_msgs/PoseStamped``: pose only."""
    return _from_pose(ros_stamp_ns(msg.header.stamp), msg.pose, float("nan"), float("nan"))


def decode_foxglove_odometry(msg: Any) -> EgoSample:
    """``foxglove.Odometry``: velocities in the body frame, like ``nav_msgs/Odometry``."""
    return _from_pose(
        protobuf_stamp_ns(msg.timestamp),
        msg.pose,
        float(msg.linear_velocity.x),
        float(msg.angular_velocity.z),
    )


def decode_foxglove_pose_in_frame(msg: Any) -> EgoSample:
    """``foxglove.PoseInFrame``: pose only."""
    return _from_pose(protobuf_stamp_ns(msg.timestamp), msg.pose, float("nan"), float("nan"))


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


def _opt_float(value: Any) -> float:
    return float("nan") if value is None else float(value)


def decode_json_ego(msg: dict[str, Any]) -> EgoSample:
    """Our JSON ego schema ``workbench.EgoState`` (see ``docs/loaders.md``)."""
    stamp = msg.get("timestamp_ns")
    return EgoSample(
        None if stamp is None else int(stamp),
        _opt_float(msg.get("x_m")),
        _opt_float(msg.get("y_m")),
        float(msg.get("z_m", 0.0)),
        _opt_float(msg.get("yaw_rad")),
        _opt_float(msg.get("speed_mps")),
        _opt_float(msg.get("yaw_rate_radps")),
    )
