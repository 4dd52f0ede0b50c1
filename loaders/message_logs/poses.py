"""Small pose helpers shared by the message decoders: stamps, yaw, frame rotations, poses.

Yaw follows the map convention (ENU, 0 = +x, counter-clockwise positive). Rotating a
body-frame velocity into the map frame::

      map y ^            vx_map = cos(yaw) * vx_body - sin(yaw) * vy_body
            |   body x   vy_map = sin(yaw) * vx_body + cos(yaw) * vy_body
            |  /
            | / yaw
            +--------> map x
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any

import numpy as np

from loaders.message_logs.samples import EgoSample

if TYPE_CHECKING:
    from numpy.typing import NDArray

__all__ = [
    "body_to_map",
    "ego_sample_from_pose",
    "protobuf_stamp_ns",
    "ros_stamp_ns",
    "yaw_from_quaternion",
    "yaws_from_quaternions",
]


def yaw_from_quaternion(x: float, y: float, z: float, w: float) -> float:
    """Heading (rotation about +z) of a quaternion, radians in ``(-pi, pi]``."""
    return math.atan2(2.0 * (w * z + x * y), 1.0 - 2.0 * (y * y + z * z))


def yaws_from_quaternions(q: NDArray[np.float64]) -> NDArray[np.float64]:
    """Vectorised :func:`yaw_from_quaternion`.

    Args:
        q: Quaternions as ``(N, 4)`` rows ``x, y, z, w``.

    Returns:
        Yaw angles, ``(N,)``.
    """
    x, y, z, w = q[:, 0], q[:, 1], q[:, 2], q[:, 3]
    return np.arctan2(2.0 * (w * z + x * y), 1.0 - 2.0 * (y * y + z * z))


def body_to_map(
    vx_body: NDArray[np.float64], vy_body: NDArray[np.float64], yaw_rad: NDArray[np.float64]
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Rotate body-frame velocities ``(N,)`` into the map frame by the body yaw ``(N,)``."""
    cos, sin = np.cos(yaw_rad), np.sin(yaw_rad)
    return cos * vx_body - sin * vy_body, sin * vx_body + cos * vy_body


def ros_stamp_ns(stamp: Any) -> int:
    """Nanoseconds of a ROS ``builtin_interfaces/Time`` (ROS 1 times are read the same way)."""
    return int(stamp.sec) * 1_000_000_000 + int(stamp.nanosec)


def protobuf_stamp_ns(stamp: Any) -> int:
    """Nanoseconds of a ``google.protobuf.Timestamp``."""
    return int(stamp.seconds) * 1_000_000_000 + int(stamp.nanos)


def ego_sample_from_pose(
    stamp_ns: int | None, pose: Any, speed_mps: float, yaw_rate_radps: float
) -> EgoSample:
    """An ego sample from a ROS or Foxglove ``Pose`` (``position``, ``orientation``)."""
    p, q = pose.position, pose.orientation
    return EgoSample(
        stamp_ns,
        float(p.x),
        float(p.y),
        float(p.z),
        yaw_from_quaternion(q.x, q.y, q.z, q.w),
        speed_mps,
        yaw_rate_radps,
    )
