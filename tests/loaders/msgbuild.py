"""Build rosbags message objects from keyword overrides, filling every other field with defaults.

``build(ts, "nav_msgs/msg/Odometry", pose=...)`` works on both the ROS 1 and ROS 2 stores,
so fixtures need not care about version differences (``Header.seq``, ``SolidPrimitive``).
"""

from __future__ import annotations

from typing import Any

import numpy as np

__all__ = ["build", "header", "pose", "quat"]

_BASE, _NAME, _ARRAY, _SEQUENCE = 1, 2, 3, 4
_NUMPY = {
    "bool": np.bool_,
    "int8": np.int8,
    "uint8": np.uint8,
    "byte": np.uint8,
    "char": np.uint8,
    "int16": np.int16,
    "uint16": np.uint16,
    "int32": np.int32,
    "uint32": np.uint32,
    "int64": np.int64,
    "uint64": np.uint64,
    "float32": np.float32,
    "float64": np.float64,
}


def _default(ts: Any, desc: tuple[int, Any]) -> Any:
    kind, detail = desc
    if kind == _BASE:
        name = detail[0]
        return {"string": "", "bool": False}.get(name, 0.0 if name.startswith("float") else 0)
    if kind == _NAME:
        return build(ts, detail)
    sub, length = detail
    if sub[0] == _BASE and sub[1][0] in _NUMPY:
        return np.zeros(length if kind == _ARRAY else 0, dtype=_NUMPY[sub[1][0]])
    if kind == _ARRAY:
        return [_default(ts, sub) for _ in range(length)]
    return []


def build(ts: Any, msgtype: str, **fields: Any) -> Any:
    """Instantiate ``msgtype`` from ``ts`` with ``fields``; missing fields get defaults."""
    _, defs = ts.fielddefs[msgtype]
    values = {name: fields[name] if name in fields else _default(ts, desc) for name, desc in defs}
    if unknown := set(fields) - {name for name, _ in defs}:
        msg = f"{msgtype} has no fields {sorted(unknown)}"
        raise TypeError(msg)
    return ts.types[msgtype](**values)


def header(ts: Any, t_ns: int, frame_id: str = "map") -> Any:
    """A ``std_msgs/Header`` stamped ``t_ns``."""
    stamp = build(ts, "builtin_interfaces/msg/Time", sec=t_ns // 10**9, nanosec=t_ns % 10**9)
    return build(ts, "std_msgs/msg/Header", stamp=stamp, frame_id=frame_id)


def quat(ts: Any, yaw: float) -> Any:
    """A yaw-only ``geometry_msgs/Quaternion``."""
    return build(
        ts, "geometry_msgs/msg/Quaternion", z=float(np.sin(yaw / 2)), w=float(np.cos(yaw / 2))
    )


def pose(ts: Any, x: float, y: float, z: float, yaw: float) -> Any:
    """A ``geometry_msgs/Pose``."""
    point = build(ts, "geometry_msgs/msg/Point", x=float(x), y=float(y), z=float(z))
    return build(ts, "geometry_msgs/msg/Pose", position=point, orientation=quat(ts, yaw))
