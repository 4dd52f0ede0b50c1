"""ROS messages of the synthetic drive, for any rosbags typestore (ROS 1 or ROS 2)."""

from __future__ import annotations

from typing import Any

import numpy as np

from tests.loaders import synthetic as syn
from tests.loaders.msgbuild import build, header, pose

__all__ = [
    "CARLA_CLASS",
    "LABELS",
    "autoware_objects",
    "carla_objects",
    "detection3d",
    "odometry",
    "path",
    "pointcloud",
    "pose_stamped",
    "trajectory",
    "uuid_hex",
]

CARLA_CLASS = {"car": 6, "truck": 7, "pedestrian": 4}
LABELS = {"car": 1, "truck": 2, "pedestrian": 7}


def uuid_hex(actor_id: int) -> str:
    """The id the loader reports for an Autoware object of the synthetic actor."""
    return actor_id.to_bytes(16, "big").hex()


def _vec(ts: Any, x: float = 0.0, y: float = 0.0, z: float = 0.0) -> Any:
    return build(ts, "geometry_msgs/msg/Vector3", x=float(x), y=float(y), z=float(z))


def _twist(ts: Any, vx: float, vy: float = 0.0, wz: float = 0.0) -> Any:
    return build(ts, "geometry_msgs/msg/Twist", linear=_vec(ts, vx, vy), angular=_vec(ts, z=wz))


def odometry(ts: Any, t_ns: int, *, x: float | None = None) -> Any:
    ex, ey, eyaw = syn.ego_state(t_ns)
    ex = ex if x is None else x
    return build(
        ts,
        "nav_msgs/msg/Odometry",
        header=header(ts, t_ns),
        child_frame_id="ego_vehicle",
        pose=build(ts, "geometry_msgs/msg/PoseWithCovariance", pose=pose(ts, ex, ey, 0.0, eyaw)),
        twist=build(ts, "geometry_msgs/msg/TwistWithCovariance", twist=_twist(ts, syn.EGO_SPEED)),
    )


def pose_stamped(ts: Any, t_ns: int) -> Any:
    ex, ey, eyaw = syn.ego_state(t_ns)
    return build(
        ts, "geometry_msgs/msg/PoseStamped", header=header(ts, t_ns), pose=pose(ts, ex, ey, 0, eyaw)
    )


def carla_objects(ts: Any, t_ns: int) -> Any:
    objs = []
    for a in syn.ACTORS:
        x, y = syn.actor_state(a, t_ns)
        shape = build(
            ts,
            "shape_msgs/msg/SolidPrimitive",
            type=1,
            dimensions=np.array([a.length, a.width, a.height]),
        )
        objs.append(
            build(
                ts,
                "derived_object_msgs/msg/Object",
                header=header(ts, t_ns),
                id=a.id,
                pose=pose(ts, x, y, a.height / 2, a.yaw),
                twist=_twist(ts, a.vx, a.vy),  # CARLA: map frame
                shape=shape,
                classification=CARLA_CLASS[a.cls],
            )
        )
    return build(ts, "derived_object_msgs/msg/ObjectArray", header=header(ts, t_ns), objects=objs)


def autoware_objects(ts: Any, t_ns: int, *, tracked: bool) -> Any:
    kind = "Tracked" if tracked else "Predicted"
    objs = []
    for a in syn.ACTORS:
        x, y = syn.actor_state(a, t_ns)
        pwc = build(ts, "geometry_msgs/msg/PoseWithCovariance", pose=pose(ts, x, y, 0, a.yaw))
        speed = float(np.hypot(a.vx, a.vy))
        twc = build(ts, "geometry_msgs/msg/TwistWithCovariance", twist=_twist(ts, speed))  # body
        prefix = "" if tracked else "initial_"
        kin = build(
            ts,
            f"autoware_perception_msgs/msg/{kind}ObjectKinematics",
            **{f"{prefix}pose_with_covariance": pwc, f"{prefix}twist_with_covariance": twc},
        )
        cls = build(
            ts,
            "autoware_perception_msgs/msg/ObjectClassification",
            label=LABELS[a.cls],
            probability=0.9,
        )
        shape = build(
            ts,
            "autoware_perception_msgs/msg/Shape",
            type=0,
            dimensions=_vec(ts, a.length, a.width, a.height),
        )
        uuid = build(
            ts,
            "unique_identifier_msgs/msg/UUID",
            uuid=np.frombuffer(a.id.to_bytes(16, "big"), dtype=np.uint8).copy(),
        )
        objs.append(
            build(
                ts,
                f"autoware_perception_msgs/msg/{kind}Object",
                object_id=uuid,
                existence_probability=1.0,
                classification=[cls],
                kinematics=kin,
                shape=shape,
            )
        )
    return build(
        ts, f"autoware_perception_msgs/msg/{kind}Objects", header=header(ts, t_ns), objects=objs
    )


def detection3d(ts: Any, t_ns: int) -> Any:
    dets = []
    for a in syn.ACTORS:
        x, y = syn.actor_state(a, t_ns)
        hyp = build(ts, "vision_msgs/msg/ObjectHypothesis", class_id=a.cls, score=0.8)
        result = build(ts, "vision_msgs/msg/ObjectHypothesisWithPose", hypothesis=hyp)
        bbox = build(
            ts,
            "vision_msgs/msg/BoundingBox3D",
            center=pose(ts, x, y, 0, a.yaw),
            size=_vec(ts, a.length, a.width, a.height),
        )
        dets.append(
            build(
                ts,
                "vision_msgs/msg/Detection3D",
                header=header(ts, t_ns),
                results=[result],
                bbox=bbox,
                id=str(a.id),
            )
        )
    return build(ts, "vision_msgs/msg/Detection3DArray", header=header(ts, t_ns), detections=dets)


def path(ts: Any, t_ns: int) -> Any:
    poses = [
        build(
            ts, "geometry_msgs/msg/PoseStamped", header=header(ts, t_ns), pose=pose(ts, x, y, 0, 0)
        )
        for x, y, _, _ in syn.plan_points(t_ns)
    ]
    return build(ts, "nav_msgs/msg/Path", header=header(ts, t_ns), poses=poses)


def trajectory(ts: Any, t_ns: int) -> Any:
    pts = [
        build(
            ts,
            "autoware_planning_msgs/msg/TrajectoryPoint",
            time_from_start=build(ts, "builtin_interfaces/msg/Duration", sec=int(t), nanosec=0),
            pose=pose(ts, x, y, 0, 0),
            longitudinal_velocity_mps=v,
        )
        for x, y, t, v in syn.plan_points(t_ns)
    ]
    return build(ts, "autoware_planning_msgs/msg/Trajectory", header=header(ts, t_ns), points=pts)


def pointcloud(ts: Any, t_ns: int, nbytes: int, rng: np.random.Generator) -> Any:
    """A ``sensor_msgs/PointCloud2`` of ``nbytes`` random payload (padding for size tests)."""
    data = rng.integers(0, 255, size=nbytes, dtype=np.uint8)
    return build(
        ts,
        "sensor_msgs/msg/PointCloud2",
        header=header(ts, t_ns, "lidar"),
        height=1,
        width=nbytes // 16,
        point_step=16,
        row_step=nbytes,
        data=data,
    )
