"""Plan decoders: ``nav_msgs/Path``, ``autoware_planning_msgs/Trajectory``, our JSON plan."""

from __future__ import annotations

from typing import Any

import numpy as np

from loaders.records import Plan
from loaders.ros.poses import ros_stamp_ns, yaws_from_quaternions
from loaders.ros.samples import PlanSample

__all__ = ["decode_json_plan", "decode_path", "decode_trajectory"]


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
    """``autoware_planning_msgs/Trajectory``: ``time_from_start`` and longitudinal speed."""
    pts = msg.points
    t = [ros_stamp_ns(p.time_from_start) / 1e9 for p in pts]
    v = [float(p.longitudinal_velocity_mps) for p in pts]
    return PlanSample(ros_stamp_ns(msg.header.stamp), _plan_from_poses([p.pose for p in pts], t, v))


def decode_json_plan(msg: dict[str, Any]) -> PlanSample:
    """Our JSON plan schema ``workbench.Plan`` (see ``docs/loaders.md``)."""
    pts = msg.get("points", [])

    def col(key: str) -> Any:
        return np.array([np.nan if p.get(key) is None else p[key] for p in pts], dtype=float)

    stamp = msg.get("timestamp_ns")
    return PlanSample(
        None if stamp is None else int(stamp),
        Plan(
            x_m=col("x_m"),
            y_m=col("y_m"),
            yaw_rad=col("yaw_rad"),
            t_offset_s=col("t_offset_s"),
            speed_mps=col("speed_mps"),
        ),
    )
