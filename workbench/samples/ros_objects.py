"""Object-list and plan messages (CARLA, Autoware, vision_msgs, nav_msgs) for one sample."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np

from loaders.timebase import s_to_ns
from workbench.samples.motion import DT_S
from workbench.samples.ros_messages import (
    AUTOWARE_CLASS,
    DERIVED_CLASS,
    PLAN_POINTS,
    PLAN_STEP,
    PRED_POINTS,
    PRED_STEP,
)

if TYPE_CHECKING:
    from workbench.samples.motion import Track
    from workbench.samples.ros_messages import MessageFactory
    from workbench.samples.scenario import ObjectsKind, PlanKind, Scenario

__all__ = ["objects_message", "plan_indices", "plan_message"]

_NS_PER_SAMPLE = s_to_ns(DT_S)


def _uuid(track_id: int) -> Any:
    return np.frombuffer(track_id.to_bytes(16, "big"), dtype=np.uint8).copy()


def _derived(f: MessageFactory, tr: Track, k: int, t_ns: int, seq: int) -> Any:
    m = tr.motion
    c, s = np.cos(m.yaw_rad[k]), np.sin(m.yaw_rad[k])
    v, a = m.speed_mps[k], tr.accel_mps2[k]
    shape_fields: dict[str, Any] = {
        "type": 1,
        "dimensions": np.array([tr.length_m, tr.width_m, tr.height_m]),
    }
    if not f.ros1:
        shape_fields["polygon"] = f.new("geometry_msgs/msg/Polygon", points=[])
    return f.new(
        "derived_object_msgs/msg/Object",
        header=f.header(t_ns, seq),
        id=tr.id,
        detection_level=1,
        object_classified=True,
        pose=f.track_pose(tr, k, tr.height_m / 2),
        twist=f.twist(f.vec(v * c, v * s), f.vec(z=tr.yaw_rate_radps[k])),
        accel=f.new("geometry_msgs/msg/Accel", linear=f.vec(a * c, a * s), angular=f.vec()),
        polygon=f.new("geometry_msgs/msg/Polygon", points=[]),
        shape=f.new("shape_msgs/msg/SolidPrimitive", **shape_fields),
        classification=DERIVED_CLASS[tr.object_class],
        classification_certainty=round(tr.confidence * 255),
        classification_age=k // 2,
    )


def _autoware_common(f: MessageFactory, tr: Track) -> dict[str, Any]:
    label = f.new(
        "autoware_perception_msgs/msg/ObjectClassification",
        label=AUTOWARE_CLASS[tr.object_class],
        probability=tr.confidence,
    )
    shape = f.new(
        "autoware_perception_msgs/msg/Shape",
        type=0,
        footprint=f.new("geometry_msgs/msg/Polygon", points=[]),
        dimensions=f.vec(tr.length_m, tr.width_m, tr.height_m),
    )
    return {
        "object_id": f.new("unique_identifier_msgs/msg/UUID", uuid=_uuid(tr.id)),
        "existence_probability": tr.confidence,
        "classification": [label],
        "shape": shape,
    }


def _autoware(f: MessageFactory, tr: Track, k: int, *, predicted: bool) -> Any:
    pose = f.with_cov("Pose", f.track_pose(tr, k, tr.height_m / 2))
    twist = f.with_cov("Twist", f.body_twist(tr, k))
    accel = f.with_cov(
        "Accel",
        f.new("geometry_msgs/msg/Accel", linear=f.vec(tr.accel_mps2[k]), angular=f.vec()),
    )
    if predicted:
        last = len(tr.motion.x_m) - 1
        idx = [min(k + j * PRED_STEP, last) for j in range(PRED_POINTS)]
        path = f.new(
            "autoware_perception_msgs/msg/PredictedPath",
            path=[f.track_pose(tr, i, tr.height_m / 2) for i in idx],
            time_step=f.duration(PRED_STEP * _NS_PER_SAMPLE),
            confidence=1.0,
        )
        kin = f.new(
            "autoware_perception_msgs/msg/PredictedObjectKinematics",
            initial_pose_with_covariance=pose,
            initial_twist_with_covariance=twist,
            initial_acceleration_with_covariance=accel,
            predicted_paths=[path],
        )
        kind = "PredictedObject"
    else:
        kin = f.new(
            "autoware_perception_msgs/msg/TrackedObjectKinematics",
            pose_with_covariance=pose,
            twist_with_covariance=twist,
            acceleration_with_covariance=accel,
            orientation_availability=2,
            is_stationary=bool(abs(tr.motion.speed_mps[k]) < 0.1),  # noqa: PLR2004
        )
        kind = "TrackedObject"
    return f.new(f"autoware_perception_msgs/msg/{kind}", kinematics=kin, **_autoware_common(f, tr))


def _detection(f: MessageFactory, tr: Track, k: int, t_ns: int) -> Any:
    pose = f.track_pose(tr, k, tr.height_m / 2)
    hypothesis = f.new(
        "vision_msgs/msg/ObjectHypothesisWithPose",
        hypothesis=f.new(
            "vision_msgs/msg/ObjectHypothesis",
            class_id=tr.object_class.label,
            score=tr.confidence,
        ),
        pose=f.with_cov("Pose", pose),
    )
    return f.new(
        "vision_msgs/msg/Detection3D",
        header=f.header(t_ns),
        results=[hypothesis],
        bbox=f.new(
            "vision_msgs/msg/BoundingBox3D",
            center=pose,
            size=f.vec(tr.length_m, tr.width_m, tr.height_m),
        ),
        id=str(tr.id),
    )


def objects_message(f: MessageFactory, kind: ObjectsKind, sc: Scenario, k: int, t_ns: int) -> Any:
    """The object list of sample ``k`` (visible actors only) as a ``kind`` message."""
    seq = k // 2
    tracks = [tr for tr in sc.actors if tr.visible[k]]
    header = f.header(t_ns, seq)
    if kind == "object_array":
        objs = [_derived(f, tr, k, t_ns, seq) for tr in tracks]
        return f.new("derived_object_msgs/msg/ObjectArray", header=header, objects=objs)
    if kind == "detection3d":
        dets = [_detection(f, tr, k, t_ns) for tr in tracks]
        return f.new("vision_msgs/msg/Detection3DArray", header=header, detections=dets)
    predicted = kind == "predicted"
    name = "PredictedObjects" if predicted else "TrackedObjects"
    objs = [_autoware(f, tr, k, predicted=predicted) for tr in tracks]
    return f.new(f"autoware_perception_msgs/msg/{name}", header=header, objects=objs)


def plan_indices(sc: Scenario, k: int) -> list[int]:
    """Ego samples used as plan waypoints at sample ``k`` (every 0.25 s, up to 5 s)."""
    last = len(sc.t_s) - 1
    return [k + j * PLAN_STEP for j in range(PLAN_POINTS) if k + j * PLAN_STEP <= last]


def plan_message(f: MessageFactory, kind: PlanKind, sc: Scenario, k: int, t_ns: int) -> Any:
    """The ego plan at sample ``k``: its own future trajectory over the next 5 s."""
    idx = plan_indices(sc, k)
    ego = sc.ego
    if kind == "path":
        poses = [
            f.new(
                "geometry_msgs/msg/PoseStamped",
                header=f.header(t_ns + (i - k) * _NS_PER_SAMPLE, k // 2),
                pose=f.track_pose(ego, i),
            )
            for i in idx
        ]
        return f.new("nav_msgs/msg/Path", header=f.header(t_ns, k // 2), poses=poses)
    points = [
        f.new(
            "autoware_planning_msgs/msg/TrajectoryPoint",
            time_from_start=f.duration((i - k) * _NS_PER_SAMPLE),
            pose=f.track_pose(ego, i),
            longitudinal_velocity_mps=float(ego.motion.speed_mps[i]),
            lateral_velocity_mps=0.0,
            acceleration_mps2=float(ego.accel_mps2[i]),
            heading_rate_rps=float(ego.yaw_rate_radps[i]),
            front_wheel_angle_rad=0.0,
            rear_wheel_angle_rad=0.0,
        )
        for i in idx
    ]
    return f.new("autoware_planning_msgs/msg/Trajectory", header=f.header(t_ns), points=points)
