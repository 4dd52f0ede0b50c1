"""Decoder and role-detection details not covered by the contract test."""

from __future__ import annotations

import math
from contextlib import closing
from types import SimpleNamespace

import numpy as np
import pytest

from loaders import ObjectClass, open_drive
from loaders.drive import TopicInfo
from loaders.message_logs.decoders.ros_objects import decode_detection3d
from loaders.message_logs.kinematics import ego_kinematics
from loaders.message_logs.roles import detect_roles
from loaders.message_logs.samples import EgoSample
from loaders.typestore import typestore
from tests.loaders import synthetic as syn
from tests.loaders.fixtures import ODOM, Entry, ros_entries, write_mcap_protobuf, write_ros2_mcap


@pytest.mark.parametrize("kind", ["pose", "transform"])
def test_foxglove_pose_only_ego_uses_finite_differences(tmp_path, kind):
    path = write_mcap_protobuf(tmp_path / f"{kind}.mcap", ego_kind=kind)
    with closing(open_drive(path)) as drive:
        frames = list(drive.frames())
        assert drive.info.topics[0].msgtype in {"foxglove.PoseInFrame", "foxglove.FrameTransform"}
    assert len(frames) == syn.N_FRAMES
    for frame in frames:
        assert frame.ego.speed_mps == pytest.approx(syn.EGO_SPEED, abs=1e-6)
        assert frame.ego.accel_mps2 == pytest.approx(0.0, abs=1e-6)
        assert frame.ego.yaw_rate_radps == pytest.approx(0.0, abs=1e-9)


def test_kinematics_central_differences():
    def s(x: float, yaw: float, v: float = math.nan) -> EgoSample:
        return EgoSample(None, x, 0.0, 0.0, yaw, v)

    # accelerating 1 m/s^2 from 10 m/s, pose only: x = 10 t + t^2 / 2
    prev, cur, nxt = (0, s(0.0, -0.1)), (10**9, s(10.5, 0.0)), (2 * 10**9, s(22.0, 0.1))
    speed, accel, yaw_rate = ego_kinematics(prev, cur, nxt)
    assert speed == pytest.approx(11.0)
    assert accel == pytest.approx(1.0)
    assert yaw_rate == pytest.approx(0.1)
    speed, accel, _ = ego_kinematics(
        (0, s(0, 0, 10.0)), (10**9, s(10, 0, 11.0)), (2 * 10**9, s(21, 0, 12.0))
    )
    assert speed == pytest.approx(11.0)
    assert accel == pytest.approx(1.0)
    assert ego_kinematics(None, (0, s(0, 0)), None) == (0.0, 0.0, 0.0)


def test_detection3d_ros1_variant_with_integer_result_ids():
    center = SimpleNamespace(
        position=SimpleNamespace(x=1.0, y=2.0, z=0.0),
        orientation=SimpleNamespace(x=0.0, y=0.0, z=0.0, w=1.0),
    )
    det = SimpleNamespace(
        results=[SimpleNamespace(id=1, score=0.9), SimpleNamespace(id=6, score=0.2)],
        bbox=SimpleNamespace(center=center, size=SimpleNamespace(x=4.0, y=2.0, z=1.5)),
    )
    msg = SimpleNamespace(
        header=SimpleNamespace(stamp=SimpleNamespace(sec=1, nanosec=5)), detections=[det]
    )
    cols = decode_detection3d(msg)
    assert cols.stamp_ns == 1_000_000_005
    assert cols.ids == ["det0"]
    assert cols.object_class.tolist() == [ObjectClass.CAR]
    assert not cols.has_velocity


def test_detect_roles_prefers_odometry_and_ego_names(tmp_path):
    topics = [
        TopicInfo("/ego/pose", "geometry_msgs/PoseStamped", 10),
        TopicInfo("/other/odom", "nav_msgs/Odometry", 10),
        TopicInfo("/localization/kinematic_state", "nav_msgs/Odometry", 10),
        TopicInfo("/perception/predicted", "autoware_perception_msgs/PredictedObjects", 10),
        TopicInfo("/perception/tracked", "autoware_perception_msgs/TrackedObjects", 10),
        TopicInfo("/debug/path", "nav_msgs/Path", 3),
        TopicInfo("/planning/trajectory", "autoware_planning_msgs/Trajectory", 3),
    ]
    roles = detect_roles(tmp_path, topics, None)
    assert roles.ego == "/localization/kinematic_state"
    assert roles.objects == ("/perception/tracked",)
    assert roles.plan == "/planning/trajectory"


def test_several_object_topics_prefix_ids(tmp_path):
    entries = ros_entries(2, ODOM, "derived_object_msgs/msg/ObjectArray", None)
    second = [
        Entry("/carla/objects", e.msgtype, e.t_ns, e.msg)
        for e in entries
        if e.topic == "/perception/objects"
    ]
    path = write_ros2_mcap(tmp_path / "two.mcap", sorted(entries + second, key=lambda e: e.t_ns))
    profile = tmp_path / "p.toml"
    profile.write_text('[topics]\nobjects = ["/perception/objects", "/carla/objects"]\n')
    with closing(open_drive(path, profile=profile, ego_id="/carla/objects:12")) as drive:
        frame = next(iter(drive.frames()))
    assert sorted(frame.actors.ids.tolist()) == [
        "/carla/objects:11",
        "/carla/objects:13",
        "/perception/objects:11",
        "/perception/objects:12",
        "/perception/objects:13",
    ]


def test_autoware_body_twist_rotated_to_map(drive_files):
    with closing(open_drive(drive_files["rosbag2-sqlite3"])) as drive:
        frame = list(drive.frames())[3]
    truck = int(np.flatnonzero(frame.actors.object_class == ObjectClass.TRUCK)[0])
    assert frame.actors.vx_mps[truck] == pytest.approx(-6.0)  # body +x, yaw = pi
    assert frame.actors.vy_mps[truck] == pytest.approx(0.0, abs=1e-9)


def test_typestore_is_the_default_for_definitionless_bags():
    assert "derived_object_msgs/msg/ObjectArray" in typestore(2).types
