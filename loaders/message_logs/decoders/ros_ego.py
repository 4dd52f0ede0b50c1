"""Ego decoders for ROS messages: ``Odometry``, ``PoseStamped``, ``PoseWithCovarianceStamped``.

``geometry_msgs/PoseWithCovarianceStamped`` (amcl, Autoware localisation) is read like
``PoseStamped``; the covariance is not used.

``nav_msgs/Odometry`` carries the twist in the *child* (body) frame, so the signed speed
along the heading is ``twist.linear.x`` and the yaw rate is ``twist.angular.z``.
``PoseStamped`` and ``PoseWithCovarianceStamped`` leave speed and yaw rate NaN; the frame
assembler derives them by finite differences.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from loaders.message_logs.poses import ego_sample_from_pose, ros_stamp_ns

if TYPE_CHECKING:
    from loaders.message_logs.samples import EgoSample

__all__ = ["decode_odometry", "decode_pose_stamped", "decode_pose_with_covariance"]


def decode_odometry(msg: Any) -> EgoSample:
    """``nav_msgs/Odometry``: pose in the header frame, twist in the child frame."""
    twist = msg.twist.twist
    return ego_sample_from_pose(
        ros_stamp_ns(msg.header.stamp),
        msg.pose.pose,
        float(twist.linear.x),
        float(twist.angular.z),
    )


def decode_pose_stamped(msg: Any) -> EgoSample:
    """``geometry_msgs/PoseStamped``: pose only."""
    return ego_sample_from_pose(
        ros_stamp_ns(msg.header.stamp), msg.pose, float("nan"), float("nan")
    )


def decode_pose_with_covariance(msg: Any) -> EgoSample:
    """``geometry_msgs/PoseWithCovarianceStamped``: pose only (``pose.pose``)."""
    return ego_sample_from_pose(
        ros_stamp_ns(msg.header.stamp), msg.pose.pose, float("nan"), float("nan")
    )
