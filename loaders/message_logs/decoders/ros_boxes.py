"""Box-only object decoders: ``visualization_msgs/MarkerArray`` and jsk bounding boxes.

Neither type carries a velocity or a class: the class is unknown and ``has_velocity=False``
lets the assembler estimate the velocity per id by finite differences across messages.
"""

from __future__ import annotations

import logging
from typing import Any

from loaders.message_logs.poses import ros_stamp_ns, yaw_from_quaternion
from loaders.message_logs.samples import ObjectColumns
from loaders.records import ObjectClass

__all__ = ["decode_jsk_boxes", "decode_marker_array"]

_LOG = logging.getLogger(__name__)
_CUBE = 1  # visualization_msgs/Marker.CUBE
_ADD = 0  # visualization_msgs/Marker.ADD (MODIFY has the same value)
_NAN = float("nan")


def _row(pose: Any, size: Any) -> tuple[float, ...]:
    p, q = pose.position, pose.orientation
    yaw = yaw_from_quaternion(q.x, q.y, q.z, q.w)
    dims = (float(size.x), float(size.y), float(size.z))
    return (float(p.x), float(p.y), float(p.z), yaw, _NAN, _NAN, *dims)


def decode_marker_array(msg: Any) -> ObjectColumns:
    """``visualization_msgs/MarkerArray``: every ADD/MODIFY CUBE marker is a box.

    The id is ``<ns>/<id>``, ``scale`` the full box size, the stamp that of the first cube.
    Markers of other types and DELETE/DELETEALL actions are left out and counted
    (``ObjectColumns.ignored`` → the drive note ``ignored_markers``, printed by the CLI; also
    a debug log line); each message is read as the complete object list.
    """
    ids, rows = [], []
    stamp: int | None = None
    ignored = 0
    for marker in msg.markers:
        if int(marker.type) != _CUBE or int(marker.action) != _ADD:
            ignored += 1
            continue
        if stamp is None:
            stamp = ros_stamp_ns(marker.header.stamp)
        ids.append(f"{marker.ns}/{marker.id}")
        rows.append(_row(marker.pose, marker.scale))
    if ignored:
        _LOG.debug("MarkerArray: ignored %d non-cube or delete markers", ignored)
    classes = [ObjectClass.UNKNOWN] * len(ids)
    return ObjectColumns.from_rows(stamp, ids, classes, rows, has_velocity=False, ignored=ignored)


def decode_jsk_boxes(msg: Any) -> ObjectColumns:
    """``jsk_recognition_msgs/BoundingBoxArray``: ``dimensions`` are full sizes.

    The id is the box's ``label`` when the labels of the message are distinct (trackers
    publish the track id there), else ``box<k>`` with the index in the message.
    """
    labels = [int(box.label) for box in msg.boxes]
    distinct = len(set(labels)) == len(labels)
    ids = [str(lab) if distinct else f"box{k}" for k, lab in enumerate(labels)]
    rows = [_row(box.pose, box.dimensions) for box in msg.boxes]
    classes = [ObjectClass.UNKNOWN] * len(ids)
    return ObjectColumns.from_rows(
        ros_stamp_ns(msg.header.stamp), ids, classes, rows, has_velocity=False
    )
