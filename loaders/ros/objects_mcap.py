"""Object decoders for non-ROS MCAP channels: ``foxglove.SceneUpdate`` and our JSON schema.

A ``SceneUpdate`` message is read as the complete object list at its time: every entity
with at least one cube becomes a row (the first cube is the box; its size is the full box),
the entity id is the object id and the metadata key ``class`` the class name. Deletions and
lifetimes are not replayed. Neither carries a velocity, so ``has_velocity=False``.
"""

from __future__ import annotations

from typing import Any

from loaders.ros.poses import protobuf_stamp_ns, yaw_from_quaternion
from loaders.ros.samples import ObjectColumns, class_from_name

__all__ = ["decode_json_objects", "decode_scene_update"]

_NAN = float("nan")


def _metadata_class(entity: Any) -> str:
    for pair in entity.metadata:
        if pair.key == "class":
            return str(pair.value)
    return ""


def decode_scene_update(msg: Any) -> ObjectColumns:
    """``foxglove.SceneUpdate``: cubes → boxes, entity id → id, metadata ``class`` → class."""
    ids, classes, rows = [], [], []
    stamp: int | None = None
    for entity in msg.entities:
        if not entity.cubes:
            continue
        cube = entity.cubes[0]
        p, q, s = cube.pose.position, cube.pose.orientation, cube.size
        if stamp is None and entity.HasField("timestamp"):
            stamp = protobuf_stamp_ns(entity.timestamp)
        ids.append(str(entity.id))
        classes.append(class_from_name(_metadata_class(entity)))
        yaw = yaw_from_quaternion(q.x, q.y, q.z, q.w)
        rows.append((p.x, p.y, p.z, yaw, _NAN, _NAN, s.x, s.y, s.z))
    return ObjectColumns.from_rows(stamp, ids, classes, rows, has_velocity=False)


def _get(obj: dict[str, Any], key: str, default: float = _NAN) -> float:
    value = obj.get(key)
    return default if value is None else float(value)


def decode_json_objects(msg: dict[str, Any]) -> ObjectColumns:
    """Our JSON object schema ``workbench.ObjectList`` (see ``docs/loaders.md``).

    Velocities are optional; when no object of the message has ``vx_mps`` the assembler
    estimates them by finite differences.
    """
    objects = msg.get("objects", [])
    has_velocity = any("vx_mps" in o for o in objects)
    ids, classes, rows = [], [], []
    for obj in objects:
        ids.append(str(obj["id"]))
        classes.append(class_from_name(str(obj.get("class", ""))))
        rows.append(
            (
                _get(obj, "x_m"),
                _get(obj, "y_m"),
                _get(obj, "z_m", 0.0),
                _get(obj, "yaw_rad"),
                _get(obj, "vx_mps"),
                _get(obj, "vy_mps"),
                _get(obj, "length_m"),
                _get(obj, "width_m"),
                _get(obj, "height_m", 1.5),
            )
        )
    stamp = msg.get("timestamp_ns")
    return ObjectColumns.from_rows(
        None if stamp is None else int(stamp), ids, classes, rows, has_velocity=has_velocity
    )
