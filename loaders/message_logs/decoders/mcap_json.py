"""Decoders for our JSON schemas in MCAP (``json`` channels, see ``docs/loaders.md``).

``workbench.EgoState`` (ego), ``workbench.ObjectList`` (objects), ``workbench.Plan`` (plan):
one JSON object per message, units in the key names, ``timestamp_ns`` optional (the log
time is used without it). Missing optional numbers are NaN; the frame assembler derives
missing ego speeds / yaw rates and object velocities by finite differences.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from loaders.message_logs.samples import EgoSample, ObjectColumns, PlanSample, class_from_name
from loaders.records import Plan

__all__ = ["decode_json_ego", "decode_json_objects", "decode_json_plan"]

_NAN = float("nan")


def _stamp(msg: dict[str, Any]) -> int | None:
    stamp = msg.get("timestamp_ns")
    return None if stamp is None else int(stamp)


def _get(obj: dict[str, Any], key: str, default: float = _NAN) -> float:
    value = obj.get(key)
    return default if value is None else float(value)


def decode_json_ego(msg: dict[str, Any]) -> EgoSample:
    """``workbench.EgoState``: pose (``z_m`` default 0), ``speed_mps``, ``yaw_rate_radps``."""
    return EgoSample(
        _stamp(msg),
        _get(msg, "x_m"),
        _get(msg, "y_m"),
        float(msg.get("z_m", 0.0)),
        _get(msg, "yaw_rad"),
        _get(msg, "speed_mps"),
        _get(msg, "yaw_rate_radps"),
    )


def decode_json_objects(msg: dict[str, Any]) -> ObjectColumns:
    """``workbench.ObjectList``: ``objects`` = list of boxes with id, class, pose and size.

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
    return ObjectColumns.from_rows(_stamp(msg), ids, classes, rows, has_velocity=has_velocity)


def decode_json_plan(msg: dict[str, Any]) -> PlanSample:
    """``workbench.Plan``: ``points`` = list of waypoints (``x_m``, ``y_m``, ``yaw_rad``, ...)."""
    pts = msg.get("points", [])

    def col(key: str) -> Any:
        return np.array([np.nan if p.get(key) is None else p[key] for p in pts], dtype=float)

    return PlanSample(
        _stamp(msg),
        Plan(
            x_m=col("x_m"),
            y_m=col("y_m"),
            yaw_rad=col("yaw_rad"),
            t_offset_s=col("t_offset_s"),
            speed_mps=col("speed_mps"),
        ),
    )
