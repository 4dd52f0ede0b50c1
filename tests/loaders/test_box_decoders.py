"""Decoders of the box-only types and Autoware detected objects, on hand-built messages."""

from __future__ import annotations

import logging
import math
from types import SimpleNamespace as Ns
from typing import Any

import numpy as np
import pytest

from loaders.drive import TopicInfo
from loaders.message_logs.decoders.ros_boxes import decode_jsk_boxes, decode_marker_array
from loaders.message_logs.decoders.ros_objects import decode_autoware_objects
from loaders.message_logs.registry import family_of
from loaders.message_logs.roles import detect_roles
from loaders.records import ObjectClass

STAMP = Ns(sec=2, nanosec=7)


def _pose(x: float, y: float, yaw: float) -> Ns:
    q = Ns(x=0.0, y=0.0, z=math.sin(yaw / 2), w=math.cos(yaw / 2))
    return Ns(position=Ns(x=x, y=y, z=0.5), orientation=q)


def _vec(x: float, y: float, z: float) -> Ns:
    return Ns(x=x, y=y, z=z)


def _marker(ns: str, mid: int, mtype: int = 1, action: int = 0) -> Ns:
    return Ns(
        header=Ns(stamp=STAMP),
        ns=ns,
        id=mid,
        type=mtype,
        action=action,
        pose=_pose(1.0, 2.0, 0.5),
        scale=_vec(4.0, 2.0, 1.5),
    )


def test_marker_array_reads_cubes_and_ignores_the_rest(caplog: pytest.LogCaptureFixture):
    msg = Ns(markers=[_marker("cars", 3), _marker("text", 1, mtype=9), _marker("x", 0, action=3)])
    with caplog.at_level(logging.DEBUG, logger="loaders.message_logs.decoders.ros_boxes"):
        cols = decode_marker_array(msg)
    assert cols.ids == ["cars/3"]
    assert cols.stamp_ns == 2_000_000_007
    assert cols.yaw_rad[0] == pytest.approx(0.5)
    assert (cols.length_m[0], cols.width_m[0], cols.height_m[0]) == (4.0, 2.0, 1.5)
    assert cols.object_class.tolist() == [ObjectClass.UNKNOWN]
    assert not cols.has_velocity
    assert "ignored 2" in caplog.text
    assert cols.ignored == 2  # counted into the drive's notes (ignored_markers)


def test_empty_marker_array_has_no_stamp():
    cols = decode_marker_array(Ns(markers=[_marker("x", 0, action=3)]))
    assert cols.ids == []
    assert cols.stamp_ns is None


def _box(label: int) -> Ns:
    return Ns(pose=_pose(0.0, 0.0, 0.0), dimensions=_vec(4.0, 2.0, 1.5), label=label, value=1.0)


def test_jsk_ids_from_distinct_labels_else_index():
    header = Ns(stamp=STAMP)
    assert decode_jsk_boxes(Ns(header=header, boxes=[_box(7), _box(9)])).ids == ["7", "9"]
    assert decode_jsk_boxes(Ns(header=header, boxes=[_box(0), _box(0)])).ids == ["box0", "box1"]


def _detected(*, has_twist: bool) -> Ns:
    twist = Ns(twist=Ns(linear=_vec(5.0, 0.0, 0.0)))
    kin = Ns(
        pose_with_covariance=Ns(pose=_pose(10.0, 0.0, math.pi / 2)),
        twist_with_covariance=twist,
        has_twist=has_twist,
    )
    shape = Ns(dimensions=_vec(4.0, 2.0, 1.5), footprint=Ns(points=[]))
    return Ns(classification=[Ns(label=1, probability=0.7)], kinematics=kin, shape=shape)


def test_detected_objects_index_ids_and_invalid_without_twist():
    msg: Any = Ns(
        header=Ns(stamp=STAMP), objects=[_detected(has_twist=True), _detected(has_twist=False)]
    )
    cols = decode_autoware_objects(msg)
    assert cols.ids == ["det0", "det1"]
    assert cols.vx_mps[0] == pytest.approx(0.0, abs=1e-9)
    assert cols.vy_mps[0] == pytest.approx(5.0)  # body +x, yaw = pi/2
    assert np.isnan([cols.vx_mps[1], cols.vy_mps[1]]).all()  # -> row invalid, not dropped
    assert cols.object_class.tolist() == [ObjectClass.CAR, ObjectClass.CAR]


@pytest.mark.parametrize(
    ("msgtype", "rank"),
    [
        ("autoware_auto_perception_msgs/msg/TrackedObjects", 0),
        ("autoware_auto_perception_msgs/msg/PredictedObjects", 1),
        ("autoware_auto_perception_msgs/msg/DetectedObjects", 2),
        ("autoware_perception_msgs/msg/DetectedObjects", 2),
        ("jsk_recognition_msgs/msg/BoundingBoxArray", 2),
        ("visualization_msgs/msg/MarkerArray", 3),
    ],
)
def test_new_types_are_objects(msgtype: str, rank: int):
    family = family_of(msgtype)
    assert family is not None
    assert (family.role, family.rank) == ("objects", rank)


def test_markers_lose_to_real_object_topics(tmp_path):
    topics = [
        TopicInfo("/odom", "nav_msgs/Odometry", 10),
        TopicInfo("/viz/boxes", "visualization_msgs/MarkerArray", 10),
        TopicInfo("/lidar/boxes", "jsk_recognition_msgs/BoundingBoxArray", 10),
        TopicInfo("/perception/detected", "autoware_auto_perception_msgs/DetectedObjects", 10),
        TopicInfo("/perception/tracked", "autoware_auto_perception_msgs/TrackedObjects", 10),
    ]
    assert detect_roles(tmp_path, topics, None).objects == ("/perception/tracked",)
    assert detect_roles(tmp_path, topics[:3], None).objects == ("/lidar/boxes",)
    assert detect_roles(tmp_path, topics[:2], None).objects == ("/viz/boxes",)
