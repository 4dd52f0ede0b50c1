"""Plan decoders for ROS messages: ``nav_msgs/Path`` and Autoware(.Auto) ``Trajectory``."""

from __future__ import annotations

from typing import Any

import numpy as np

from loaders.message_logs.poses import ros_stamp_ns, yaws_from_quaternions
from loaders.message_logs.samples import PlanSample
from loaders.records import Plan
from loaders.timebase import ns_to_s

__all__ = ["decode_path", "decode_trajectory"]


def _plan_from_poses(poses: list[Any], t_offset_s: Any, speed_mps: Any) -> Plan:
    xy = np.array([(p.position.x, p.position.y) for p in poses], dtype=np.float64).reshape(-1, 2)
    q = np.array(
        [(p.orientation.x, p.orientation.y, p.orientation.z, p.orientation.w) for p in poses],
        dtype=np.float64,
    ).reshape(-1, 4)
    n = len(poses)
    return Plan(
        x_m=xy[:, 0],
        y_m=xy[:, 1],
        yaw_rad=yaws_from_quaternions(q),
        t_offset_s=np.asarray(t_offset_s, dtype=np.float64).reshape(n),
        speed_mps=np.asarray(speed_mps, dtype=np.float64).reshape(n),
    )


def decode_path(msg: Any) -> PlanSample:
    """``nav_msgs/Path``: yaw from each orientation; timing and speed are NaN."""
    n = len(msg.poses)
    nan = np.full(n, np.nan)
    return PlanSample(
        ros_stamp_ns(msg.header.stamp), _plan_from_poses([p.pose for p in msg.poses], nan, nan)
    )


def decode_trajectory(msg: Any) -> PlanSample:
    """``autoware_(auto_)planning_msgs/Trajectory``: ``time_from_start``, longitudinal speed.

    The Autoware.Auto package has the same layout under its older name.
    """
    pts = msg.points
    t = [ns_to_s(ros_stamp_ns(p.time_from_start)) for p in pts]
    v = [float(p.longitudinal_velocity_mps) for p in pts]
    return PlanSample(ros_stamp_ns(msg.header.stamp), _plan_from_poses([p.pose for p in pts], t, v))
