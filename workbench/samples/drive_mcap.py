"""Write any drive's frames as a ROS 2 MCAP log of standard messages (``write_drive_mcap``).

Made for CommonRoad scenarios (``workbench evaluate X.mcap --map X.xml`` then sees the
drive ``workbench evaluate X.xml`` sees), it takes any :class:`~loaders.drive.Drive`. Per
frame, at log time = header stamp = the frame's ``t_ns``, in this order::

    /perception/objects   derived_object_msgs/ObjectArray    the actor table
    /planning/trajectory  autoware_planning_msgs/Trajectory  the plan (empty when none)
    /ego/odom             nav_msgs/Odometry                  the ego (written last: the
                                                             frame takes what came before)

What survives the round trip (``docs/maps.md``, CommonRoad scenarios as ROS 2 MCAP logs):

- floats are written as they are (no sample quantisation), so positions, speeds, object
  velocities (map frame, as the CARLA bridge publishes them), sizes and the ego yaw rate
  (``twist.angular.z``) come back bit for bit; yaws pass through a quaternion (within
  ``1e-12`` rad, wrapped to ``(-pi, pi]``); plan speeds are ``float32`` in ``Trajectory``;
- object ids must be unsigned 32-bit integers (``ObjectArray.id``); bus becomes truck
  (the message has one class for both);
- the ego's acceleration is not carried (``Odometry`` has none): the reader takes the
  central difference of the speeds; no engine reads it;
- the ego's size is not carried either: give it with ``--ego-size L,W,H``
  (:func:`ego_size_option` writes that value).
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any

import numpy as np

from loaders.timebase import s_to_ns
from loaders.typestore import typestore
from workbench.errors import WorkbenchError
from workbench.samples.ros_messages import DERIVED_CLASS, MessageFactory
from workbench.samples.ros_writers import write_ros2_mcap

if TYPE_CHECKING:
    from collections.abc import Iterable, Iterator, Mapping
    from pathlib import Path

    from loaders.drive import Drive
    from loaders.records import ActorTable, EgoState, Frame, Plan

__all__ = ["DRIVE_TOPICS", "ego_size_option", "frames_as_messages", "write_drive_mcap"]

#: Topic -> message type of a converted drive, in the order each frame writes them.
DRIVE_TOPICS: dict[str, str] = {
    "/perception/objects": "derived_object_msgs/msg/ObjectArray",
    "/planning/trajectory": "autoware_planning_msgs/msg/Trajectory",
    "/ego/odom": "nav_msgs/msg/Odometry",
}
_OBJECTS, _PLAN, _EGO = DRIVE_TOPICS
_UINT32_MAX = 2**32 - 1
_CLASSES: dict[int, int] = {int(cls): code for cls, code in DERIVED_CLASS.items()}


def _object_id(frame: Frame, raw: str) -> int:
    try:
        value = int(raw)
    except ValueError:
        value = -1
    if not 0 <= value <= _UINT32_MAX:
        msg = (
            f"frame {frame.index} (t={frame.t_ns} ns): object id {raw!r} is not an unsigned "
            "32-bit integer (derived_object_msgs/Object.id)"
        )
        raise WorkbenchError(msg)
    return value


def _objects(f: MessageFactory, frame: Frame) -> Any:
    a: ActorTable = frame.actors
    header = f.header(frame.t_ns)
    objects = []
    for k, raw in enumerate(a.ids.tolist()):
        shape = f.new(
            "shape_msgs/msg/SolidPrimitive",
            type=1,
            dimensions=np.array([a.length_m[k], a.width_m[k], a.height_m[k]]),
            polygon=f.new("geometry_msgs/msg/Polygon", points=[]),
        )
        objects.append(
            f.new(
                "derived_object_msgs/msg/Object",
                header=header,
                id=_object_id(frame, raw),
                detection_level=1,
                object_classified=True,
                pose=f.pose(a.x_m[k], a.y_m[k], a.z_m[k], a.yaw_rad[k]),
                twist=f.twist(f.vec(a.vx_mps[k], a.vy_mps[k]), f.vec()),
                accel=f.new("geometry_msgs/msg/Accel", linear=f.vec(), angular=f.vec()),
                polygon=f.new("geometry_msgs/msg/Polygon", points=[]),
                shape=shape,
                classification=_CLASSES.get(int(a.object_class[k]), 0),
                classification_certainty=255,
                classification_age=0,
            )
        )
    return f.new("derived_object_msgs/msg/ObjectArray", header=header, objects=objects)


def _duration_ns(t_s: float) -> int:
    return s_to_ns(t_s) if math.isfinite(t_s) else 0


def _plan_point(f: MessageFactory, plan: Plan, k: int) -> Any:
    return f.new(
        "autoware_planning_msgs/msg/TrajectoryPoint",
        time_from_start=f.duration(_duration_ns(float(plan.t_offset_s[k]))),
        pose=f.pose(plan.x_m[k], plan.y_m[k], 0.0, plan.yaw_rad[k]),
        longitudinal_velocity_mps=float(plan.speed_mps[k]),
        lateral_velocity_mps=0.0,
        acceleration_mps2=0.0,
        heading_rate_rps=0.0,
        front_wheel_angle_rad=0.0,
        rear_wheel_angle_rad=0.0,
    )


def _plan(f: MessageFactory, t_ns: int, plan: Plan | None) -> Any:
    points = [] if plan is None else [_plan_point(f, plan, k) for k in range(len(plan))]
    return f.new("autoware_planning_msgs/msg/Trajectory", header=f.header(t_ns), points=points)


def _ego(f: MessageFactory, t_ns: int, ego: EgoState) -> Any:
    yaw_rate = ego.yaw_rate_radps if math.isfinite(ego.yaw_rate_radps) else 0.0
    return f.new(
        "nav_msgs/msg/Odometry",
        header=f.header(t_ns),
        child_frame_id="base_link",
        pose=f.with_cov("Pose", f.pose(ego.x_m, ego.y_m, ego.z_m, ego.yaw_rad)),
        twist=f.with_cov("Twist", f.twist(f.vec(ego.speed_mps), f.vec(z=yaw_rate))),
    )


def frames_as_messages(frames: Iterable[Frame]) -> Iterator[tuple[str, int, Any]]:
    """``(topic, t_ns, message)`` of every frame, objects and plan before the ego.

    Raises:
        WorkbenchError: An object id that ``derived_object_msgs/Object.id`` cannot hold.
    """
    f = MessageFactory(typestore(2), 2, quantised=False)
    for frame in frames:
        yield _OBJECTS, frame.t_ns, _objects(f, frame)
        yield _PLAN, frame.t_ns, _plan(f, frame.t_ns, frame.plan)
        yield _EGO, frame.t_ns, _ego(f, frame.t_ns, frame.ego)


def write_drive_mcap(
    drive: Drive,
    path: Path,
    *,
    map_name: str | None = None,
    window: tuple[int | None, int | None] = (None, None),
) -> int:
    """Write a drive's frames as a ROS 2 MCAP (see the module docstring).

    Args:
        drive: An opened drive; the caller closes it.
        path: Output ``.mcap``.
        map_name: The map the log is to be evaluated with (``--map``), recorded in the
            ``drive`` metadata.
        window: ``(start_ns, end_ns)`` bounds of the frames written.

    Returns:
        The number of frames written.

    Raises:
        WorkbenchError: An object id that the message cannot hold (nothing is left at
            ``path``).
        LoaderError: The drive could not be read.
    """
    count = 0

    def counted() -> Iterator[Frame]:
        nonlocal count
        for frame in drive.frames(*window):
            count += 1
            yield frame

    info = drive.info
    metadata: Mapping[str, str] = {
        "source": str(info.path.name),
        "source_format": info.source_format,
        "generator": "rss-workbench write_drive_mcap",
        **({"map": map_name} if map_name is not None else {}),
        **{f"source_{key}": value for key, value in info.notes.items()},
    }
    try:
        write_ros2_mcap(path, DRIVE_TOPICS, frames_as_messages(counted()), metadata=metadata)
    except BaseException:
        path.unlink(missing_ok=True)
        raise
    return count


def ego_size_option(ego: EgoState) -> str:
    """``--ego-size`` value giving the ego's size [m], which ``Odometry`` does not carry."""
    return f"{ego.length_m!r},{ego.width_m!r},{ego.height_m!r}"
