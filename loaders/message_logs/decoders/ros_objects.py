"""Object decoders for ROS message families: CARLA, Autoware, Autoware.AI and vision_msgs.

Frames of the velocities (checked against the publishers):

- ``derived_object_msgs/Object.twist`` from the CARLA ROS bridge is the actor velocity in
  the *map* frame (the bridge converts CARLA's world velocity, it does not rotate it into
  the object frame), so it is used as is.
- Autoware ``kinematics.*twist_with_covariance`` is in the object's *body* frame; it is
  rotated into the map frame by the object yaw.
- Autoware.AI ``autoware_msgs/DetectedObject.velocity`` (``imm_ukf_pda_track``: the speed
  in ``linear.x`` along the object heading) is in the *body* frame too, rotated likewise.
- ``vision_msgs/Detection3D`` has no velocity: ``has_velocity=False`` lets the assembler
  estimate it per id by finite differences across messages.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from loaders.message_logs.poses import body_to_map, ros_stamp_ns, yaw_from_quaternion
from loaders.message_logs.samples import ObjectColumns, class_from_name
from loaders.records import ObjectClass

__all__ = [
    "AUTOWARE_LABELS",
    "CARLA_CLASSES",
    "decode_autoware_ai_objects",
    "decode_autoware_objects",
    "decode_carla_objects",
    "decode_detection3d",
]

#: ``derived_object_msgs/Object.classification`` constants.
CARLA_CLASSES: dict[int, ObjectClass] = {
    4: ObjectClass.PEDESTRIAN,
    5: ObjectClass.BICYCLE,
    6: ObjectClass.CAR,
    7: ObjectClass.TRUCK,
    8: ObjectClass.MOTORCYCLE,
    9: ObjectClass.CAR,
}

#: ``autoware_perception_msgs/ObjectClassification.label`` constants.
AUTOWARE_LABELS: dict[int, ObjectClass] = {
    0: ObjectClass.UNKNOWN,
    1: ObjectClass.CAR,
    2: ObjectClass.TRUCK,
    3: ObjectClass.BUS,
    4: ObjectClass.TRUCK,
    5: ObjectClass.MOTORCYCLE,
    6: ObjectClass.BICYCLE,
    7: ObjectClass.PEDESTRIAN,
}

_BOX, _CYLINDER = 1, 3  # shape_msgs/SolidPrimitive types
_BOX_DIMS, _CYLINDER_DIMS = 3, 2  # dimensions: [x, y, z] and [height, radius]
_NAN = float("nan")


def _pose_row(pose: Any) -> tuple[float, float, float, float]:
    p, q = pose.position, pose.orientation
    return float(p.x), float(p.y), float(p.z), yaw_from_quaternion(q.x, q.y, q.z, q.w)


def _solid_dims(shape: Any) -> tuple[float, float, float]:
    dims = [float(d) for d in shape.dimensions]
    if shape.type == _BOX and len(dims) >= _BOX_DIMS:
        return dims[0], dims[1], dims[2]
    if shape.type == _CYLINDER and len(dims) >= _CYLINDER_DIMS:
        return 2 * dims[1], 2 * dims[1], dims[0]
    return _NAN, _NAN, _NAN


def decode_carla_objects(msg: Any) -> ObjectColumns:
    """``derived_object_msgs/ObjectArray`` (BOX dimensions are full sizes; twist in map frame)."""
    ids, classes, rows = [], [], []
    for obj in msg.objects:
        ids.append(str(obj.id))
        classes.append(CARLA_CLASSES.get(int(obj.classification), ObjectClass.UNKNOWN))
        lin = obj.twist.linear
        rows.append((*_pose_row(obj.pose), float(lin.x), float(lin.y), *_solid_dims(obj.shape)))
    return ObjectColumns.from_rows(ros_stamp_ns(msg.header.stamp), ids, classes, rows)


def _autoware_class(classification: Any) -> ObjectClass:
    if not classification:
        return ObjectClass.UNKNOWN
    best = max(classification, key=lambda c: float(c.probability))
    return AUTOWARE_LABELS.get(int(best.label), ObjectClass.UNKNOWN)


def _autoware_dims(shape: Any) -> tuple[float, float, float]:
    d = shape.dimensions
    length, width, height = float(d.x), float(d.y), float(d.z)
    points = shape.footprint.points
    if (length <= 0 or width <= 0) and points:
        xs = [float(p.x) for p in points]
        ys = [float(p.y) for p in points]
        length, width = max(xs) - min(xs), max(ys) - min(ys)
    return length, width, height


def _autoware_id(obj: Any, index: int) -> str:
    object_id = getattr(obj, "object_id", None)
    if object_id is None:  # DetectedObject: no id, the index within the message
        return f"det{index}"
    return bytes(np.asarray(object_id.uuid, dtype=np.uint8)).hex()


def decode_autoware_objects(msg: Any) -> ObjectColumns:
    """``autoware_(auto_)perception_msgs/{Predicted,Tracked,Detected}Objects``.

    The twist is in the object body frame and is rotated into the map frame; the UUID
    becomes a 32-character hex id. Detected objects have no id: ``det<k>`` is the index
    within the message; their twist is NaN (the row invalid) when ``has_twist`` is false.
    """
    ids, classes, rows = [], [], []
    for k, obj in enumerate(msg.objects):
        kin = obj.kinematics
        pose = getattr(kin, "initial_pose_with_covariance", None) or kin.pose_with_covariance
        twist = getattr(kin, "initial_twist_with_covariance", None) or kin.twist_with_covariance
        ids.append(_autoware_id(obj, k))
        classes.append(_autoware_class(obj.classification))
        x, y, z, yaw = _pose_row(pose.pose)
        lin = twist.twist.linear
        velocity = (float(lin.x), float(lin.y)) if getattr(kin, "has_twist", True) else (_NAN, _NAN)
        rows.append((x, y, z, yaw, *velocity, *_autoware_dims(obj.shape)))
    cols = ObjectColumns.from_rows(ros_stamp_ns(msg.header.stamp), ids, classes, rows)
    vx, vy = body_to_map(cols.vx_mps, cols.vy_mps, cols.yaw_rad)
    object.__setattr__(cols, "vx_mps", vx)
    object.__setattr__(cols, "vy_mps", vy)
    return cols


def decode_autoware_ai_objects(msg: Any) -> ObjectColumns:
    """Autoware.AI ``autoware_msgs/DetectedObjectArray`` (ROS 1 and ROS 2).

    ``pose``, ``dimensions`` (full sizes), class from the free-text ``label``; id = ``id``
    when the ids of the message are distinct (trackers), else ``det<k>`` (the index).
    ``velocity.linear`` is in the object body frame and rotated into the map frame; unless
    every object has ``velocity_reliable`` (detectors leave it false), the velocities of the
    message are estimated per id instead. ``valid`` is not used.
    """
    objs = list(msg.objects)
    raw_ids = [int(obj.id) for obj in objs]
    distinct = len(set(raw_ids)) == len(raw_ids)
    ids = [str(i) if distinct else f"det{k}" for k, i in enumerate(raw_ids)]
    classes = [class_from_name(str(obj.label)) for obj in objs]
    rows = []
    for obj in objs:
        d, lin = obj.dimensions, obj.velocity.linear
        vel = (float(lin.x), float(lin.y))
        rows.append((*_pose_row(obj.pose), *vel, float(d.x), float(d.y), float(d.z)))
    reliable = all(bool(obj.velocity_reliable) for obj in objs)
    cols = ObjectColumns.from_rows(
        ros_stamp_ns(msg.header.stamp), ids, classes, rows, has_velocity=reliable
    )
    if reliable:
        vx, vy = body_to_map(cols.vx_mps, cols.vy_mps, cols.yaw_rad)
        object.__setattr__(cols, "vx_mps", vx)
        object.__setattr__(cols, "vy_mps", vy)
    return cols


def _hypothesis_class(results: Any) -> ObjectClass:
    if not results:
        return ObjectClass.UNKNOWN

    def score(result: Any) -> float:
        return float(getattr(result, "hypothesis", result).score)

    best = max(results, key=score)
    hyp = getattr(best, "hypothesis", None)
    if hyp is not None:
        return class_from_name(str(hyp.class_id))
    raw = best.id  # ROS 1 vision_msgs: integer (or string) id in the result itself
    if isinstance(raw, str):
        return class_from_name(raw)
    value = int(raw)
    return ObjectClass(value) if value in ObjectClass._value2member_map_ else ObjectClass.UNKNOWN


def _detection_id(det: Any, index: int) -> str:
    for name in ("id", "tracking_id"):
        value = getattr(det, name, None)
        if isinstance(value, str) and value:
            return value
    return f"det{index}"


def decode_detection3d(msg: Any) -> ObjectColumns:
    """``vision_msgs/Detection3DArray`` (4.x and the ROS 1 layout with integer result ids)."""
    ids, classes, rows = [], [], []
    for k, det in enumerate(msg.detections):
        ids.append(_detection_id(det, k))
        classes.append(_hypothesis_class(det.results))
        size = det.bbox.size
        rows.append(
            (
                *_pose_row(det.bbox.center),
                _NAN,
                _NAN,
                float(size.x),
                float(size.y),
                float(size.z),
            )
        )
    return ObjectColumns.from_rows(
        ros_stamp_ns(msg.header.stamp), ids, classes, rows, has_velocity=False
    )
