"""``radar_msgs/RadarTracks`` (ROS 2): radar tracker output as objects.

A ``RadarTrack`` has a UUID, a centre ``position``, a ``velocity`` and a ``size`` in the
frame of the message header, and no orientation. The rows take them as they are (the
workbench reads every object list in the frame it is published in: radar tracks in a sensor
frame are not transformed); the yaw is the direction of the velocity, 0 below
:data:`MIN_HEADING_SPEED_MPS`. ``classification`` follows Autoware's radar convention
(``32000 + ObjectClassification.label``: 32001 car, … 32007 pedestrian); the ``radar_msgs``
values 0 (no classification), 1 (static) and 2 (dynamic) and any other give unknown.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from loaders.message_logs.decoders.ros_objects import AUTOWARE_LABELS
from loaders.message_logs.poses import ros_stamp_ns
from loaders.message_logs.samples import ObjectColumns
from loaders.records import ObjectClass

__all__ = ["AUTOWARE_RADAR_OFFSET", "MIN_HEADING_SPEED_MPS", "decode_radar_tracks"]

#: Autoware's radar classification ids: this offset + ``ObjectClassification.label``.
AUTOWARE_RADAR_OFFSET = 32000
#: Below this speed a track's heading is not defined by its velocity: yaw 0.
MIN_HEADING_SPEED_MPS = 0.1


def _class(value: int) -> ObjectClass:
    return AUTOWARE_LABELS.get(value - AUTOWARE_RADAR_OFFSET, ObjectClass.UNKNOWN)


def decode_radar_tracks(msg: Any) -> ObjectColumns:
    """``radar_msgs/RadarTracks``: UUID → 32-char hex id, yaw from the velocity direction."""
    ids, classes, rows = [], [], []
    for track in msg.tracks:
        p, v, s = track.position, track.velocity, track.size
        vx, vy = float(v.x), float(v.y)
        yaw = math.atan2(vy, vx) if math.hypot(vx, vy) >= MIN_HEADING_SPEED_MPS else 0.0
        ids.append(bytes(np.asarray(track.uuid.uuid, dtype=np.uint8)).hex())
        classes.append(_class(int(track.classification)))
        rows.append(
            (float(p.x), float(p.y), float(p.z), yaw, vx, vy, float(s.x), float(s.y), float(s.z))
        )
    return ObjectColumns.from_rows(ros_stamp_ns(msg.header.stamp), ids, classes, rows)
