"""Build ROS messages (rosbags dataclasses) for one sample of a scenario.

Frames and conventions (documented in ``docs/samples.md``):

- every header ``frame_id`` is ``map``; the ego child frame is ``base_link``;
- ego pose: rear-axle-free simplification, the pose is the box centre on the ground (z = 0);
- object poses are box centres (z = height / 2);
- ``derived_object_msgs`` twist/accel are in the map frame (as the CARLA bridge does);
  Autoware kinematics and odometry twists are in the body frame (x forward).
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any

import numpy as np

from loaders.records import ObjectClass
from workbench.samples.quantise import ANGLE_STEPS, STEPS_PER_UNIT, quantise_field

if TYPE_CHECKING:
    from rosbags.typesys.store import Typestore

    from workbench.samples.motion import Track
    from workbench.samples.scenario import Scenario

__all__ = [
    "AUTOWARE_CLASS",
    "DERIVED_CLASS",
    "EGO_TYPES",
    "OBJECT_TOPICS",
    "PLAN_TOPICS",
    "T0_NS",
    "MessageFactory",
]

#: Log time of the first sample (2023-11-14T22:13:20Z).
T0_NS = 1_700_000_000 * 10**9

EGO_TYPES = {"odometry": "nav_msgs/msg/Odometry", "pose": "geometry_msgs/msg/PoseStamped"}
OBJECT_TOPICS = {
    "object_array": ("/carla/ego_vehicle/objects", "derived_object_msgs/msg/ObjectArray"),
    "predicted": (
        "/perception/object_recognition/objects",
        "autoware_perception_msgs/msg/PredictedObjects",
    ),
    "tracked": (
        "/perception/object_recognition/tracking/objects",
        "autoware_perception_msgs/msg/TrackedObjects",
    ),
    "detection3d": ("/detections_3d", "vision_msgs/msg/Detection3DArray"),
}
PLAN_TOPICS = {
    "path": ("/planning/path", "nav_msgs/msg/Path"),
    "trajectory": (
        "/planning/scenario_planning/trajectory",
        "autoware_planning_msgs/msg/Trajectory",
    ),
}

DERIVED_CLASS = {
    ObjectClass.CAR: 6,
    ObjectClass.TRUCK: 7,
    ObjectClass.BUS: 7,
    ObjectClass.MOTORCYCLE: 8,
    ObjectClass.BICYCLE: 5,
    ObjectClass.PEDESTRIAN: 4,
}
AUTOWARE_CLASS = {
    ObjectClass.CAR: 1,
    ObjectClass.TRUCK: 2,
    ObjectClass.BUS: 3,
    ObjectClass.MOTORCYCLE: 5,
    ObjectClass.BICYCLE: 6,
    ObjectClass.PEDESTRIAN: 7,
}
#: Plan horizon: waypoints every PLAN_STEP samples (0.25 s), at most PLAN_POINTS of them.
PLAN_STEP, PLAN_POINTS = 5, 21
#: Predicted paths: a pose every 10 samples (0.5 s) for 3 s.
PRED_STEP, PRED_POINTS = 10, 7


class MessageFactory:
    """Message constructors bound to one typestore (ROS 1 Noetic or ROS 2 Humble)."""

    def __init__(self, store: Typestore, ros_version: int, *, quantised: bool = True) -> None:
        """Bind to ``store``; ``ros_version`` selects the header layout.

        ``quantised=False`` keeps every float as given (converted drives, whose values come
        from a file and must survive the round trip bit for bit).
        """
        self.ts = store
        self.ros1 = ros_version == 1
        self._t = store.types
        self._quantised = quantised

    def new(self, name: str, **fields: Any) -> Any:
        """Construct message type ``name`` from keyword fields.

        The one place every ROS message is built: unless the factory was made with
        ``quantised=False``, each float field (and float array) is rounded to the grid of
        :mod:`workbench.samples.quantise` (quaternion components to 1e-9, everything else to
        1e-6 of its unit), so the serialised bytes do not depend on last-bit differences of
        the math before.
        """
        if not self._quantised:
            return self._t[name](**fields)
        steps = ANGLE_STEPS if name == "geometry_msgs/msg/Quaternion" else STEPS_PER_UNIT
        return self._t[name](**{key: quantise_field(v, steps) for key, v in fields.items()})

    def stamp(self, t_ns: int) -> Any:
        """A ``builtin_interfaces/Time``."""
        sec, nsec = divmod(t_ns, 10**9)
        return self.new("builtin_interfaces/msg/Time", sec=sec, nanosec=nsec)

    def duration(self, dt_ns: int) -> Any:
        """A ``builtin_interfaces/Duration``."""
        sec, nsec = divmod(dt_ns, 10**9)
        return self.new("builtin_interfaces/msg/Duration", sec=sec, nanosec=nsec)

    def header(self, t_ns: int, seq: int = 0, frame_id: str = "map") -> Any:
        """A ``std_msgs/Header`` (with ``seq`` in ROS 1)."""
        extra = {"seq": seq} if self.ros1 else {}
        return self.new("std_msgs/msg/Header", stamp=self.stamp(t_ns), frame_id=frame_id, **extra)

    def vec(self, x: float = 0.0, y: float = 0.0, z: float = 0.0) -> Any:
        """A ``geometry_msgs/Vector3``."""
        return self.new("geometry_msgs/msg/Vector3", x=float(x), y=float(y), z=float(z))

    def pose(self, x: float, y: float, z: float, yaw: float) -> Any:
        """A ``geometry_msgs/Pose`` with a yaw-only orientation."""
        point = self.new("geometry_msgs/msg/Point", x=float(x), y=float(y), z=float(z))
        quat = self.new(
            "geometry_msgs/msg/Quaternion",
            x=0.0,
            y=0.0,
            z=math.sin(yaw / 2),
            w=math.cos(yaw / 2),
        )
        return self.new("geometry_msgs/msg/Pose", position=point, orientation=quat)

    def twist(self, linear: Any, angular: Any) -> Any:
        """A ``geometry_msgs/Twist``."""
        return self.new("geometry_msgs/msg/Twist", linear=linear, angular=angular)

    def track_pose(self, track: Track, k: int, z: float = 0.0) -> Any:
        """Pose of ``track`` at sample ``k``."""
        m = track.motion
        return self.pose(m.x_m[k], m.y_m[k], z, m.yaw_rad[k])

    def body_twist(self, track: Track, k: int) -> Any:
        """Body-frame twist (x forward) of ``track`` at sample ``k``."""
        return self.twist(self.vec(track.motion.speed_mps[k]), self.vec(z=track.yaw_rate_radps[k]))

    def with_cov(self, kind: str, value: Any) -> Any:
        """Wrap a pose/twist/accel into its ``*WithCovariance`` message (zero covariance)."""
        field = kind.lower()
        return self.new(
            f"geometry_msgs/msg/{kind}WithCovariance",
            **{field: value, "covariance": np.zeros(36, dtype=np.float64)},
        )

    def ego(self, sc: Scenario, k: int, t_ns: int) -> Any:
        """Ego message (``Odometry`` or ``PoseStamped`` per the scenario layout)."""
        if sc.layout.ego == "pose":
            return self.new(
                "geometry_msgs/msg/PoseStamped",
                header=self.header(t_ns, k),
                pose=self.track_pose(sc.ego, k),
            )
        return self.new(
            "nav_msgs/msg/Odometry",
            header=self.header(t_ns, k),
            child_frame_id="base_link",
            pose=self.with_cov("Pose", self.track_pose(sc.ego, k)),
            twist=self.with_cov("Twist", self.body_twist(sc.ego, k)),
        )

    def tf(self, sc: Scenario, k: int, t_ns: int) -> Any:
        """``tf2_msgs/TFMessage`` with the ``map -> base_link`` transform."""
        p = self.track_pose(sc.ego, k)
        transform = self.new(
            "geometry_msgs/msg/Transform",
            translation=self.vec(p.position.x, p.position.y, p.position.z),
            rotation=p.orientation,
        )
        stamped = self.new(
            "geometry_msgs/msg/TransformStamped",
            header=self.header(t_ns, k),
            child_frame_id="base_link",
            transform=transform,
        )
        return self.new("tf2_msgs/msg/TFMessage", transforms=[stamped])
