"""Every bad-input class raises its typed error, naming file, topic, time/offset and value."""

from __future__ import annotations

from contextlib import closing
from typing import TYPE_CHECKING

import numpy as np
import pytest

from loaders import open_drive
from loaders.errors import (
    CorruptLogError,
    EmptyLogError,
    InvalidValueError,
    LoaderError,
    LogNotFoundError,
    MissingEgoTopicError,
    ProfileError,
    UnknownMessageTypeError,
    UnsupportedFormatError,
)
from loaders.typestore import typestore
from tests.loaders import rosmsgs
from tests.loaders import synthetic as syn
from tests.loaders.fixtures import (
    ODOM,
    Entry,
    ros_entries,
    write_ros1_bag,
    write_ros2_mcap,
    write_rosbag2,
)

if TYPE_CHECKING:
    from pathlib import Path

    from loaders.records import Frame

CARLA = "derived_object_msgs/msg/ObjectArray"


def _drain(path: Path, **kwargs: object) -> tuple[list[Frame], LoaderError | None]:
    frames: list[Frame] = []
    try:
        with closing(open_drive(path, **kwargs)) as drive:  # type: ignore[arg-type]
            frames.extend(drive.frames())
    except LoaderError as err:
        return frames, err
    return frames, None


@pytest.fixture(scope="module")
def small_chunk_mcap(tmp_path_factory: pytest.TempPathFactory) -> Path:
    entries = ros_entries(2, ODOM, CARLA, "nav_msgs/msg/Path")
    return write_ros2_mcap(tmp_path_factory.mktemp("mcap") / "drive.mcap", entries, chunk_size=4096)


@pytest.mark.parametrize("fraction", [0.02, 0.25, 0.5, 0.75, 0.999])
def test_truncated_mcap_yields_readable_frames_then_corrupt(small_chunk_mcap, tmp_path, fraction):
    data = small_chunk_mcap.read_bytes()
    cut = int(len(data) * fraction)
    truncated = tmp_path / "cut.mcap"
    truncated.write_bytes(data[:cut])
    frames, err = _drain(truncated)
    assert isinstance(err, CorruptLogError)
    assert err.path == truncated
    assert str(truncated) in str(err)
    assert err.offset is not None
    assert 0 < err.offset <= cut
    assert [f.t_ns for f in frames] == syn.ego_times()[: len(frames)]
    if frames:
        assert err.topic is not None
        assert err.t_ns is not None
        assert err.t_ns >= frames[-1].t_ns
    if fraction >= 0.5:
        assert len(frames) >= syn.N_FRAMES // 3


@pytest.mark.parametrize("fraction", [0.1, 0.5, 0.9, 0.999])
def test_truncated_ros1_bag_raises_corrupt_at_open(drive_files, tmp_path, fraction):
    data = drive_files["ros1-bag"].read_bytes()
    cut = int(len(data) * fraction)
    truncated = tmp_path / "cut.bag"
    truncated.write_bytes(data[:cut])
    frames, err = _drain(truncated)
    assert isinstance(err, CorruptLogError)
    assert err.offset == cut
    assert frames == []


@pytest.mark.parametrize("fmt", ["ros2-mcap", "ros1-bag", "mcap-json", "mcap-protobuf"])
def test_corrupted_bytes_raise_corrupt(drive_files, tmp_path, fmt):
    data = bytearray(drive_files[fmt].read_bytes())
    mid = len(data) // 2
    data[mid : mid + 64] = bytes(64)
    damaged = tmp_path / f"damaged{drive_files[fmt].suffix}"
    damaged.write_bytes(bytes(data))
    frames, err = _drain(damaged)
    assert isinstance(err, CorruptLogError)
    assert [f.t_ns for f in frames] == syn.ego_times()[: len(frames)]


def test_empty_file(tmp_path):
    for suffix in (".mcap", ".bag"):
        empty = tmp_path / f"empty{suffix}"
        empty.write_bytes(b"")
        with pytest.raises(EmptyLogError, match="0 bytes"):
            open_drive(empty)


def test_valid_containers_without_messages(tmp_path):
    with pytest.raises(EmptyLogError):
        open_drive(write_ros2_mcap(tmp_path / "none.mcap", []))
    with pytest.raises(EmptyLogError):
        open_drive(write_ros1_bag(tmp_path / "none.bag", []))
    with pytest.raises(EmptyLogError):
        open_drive(write_rosbag2(tmp_path / "none_bag", [], "sqlite3"))


def test_missing_ego_topic_lists_topics(tmp_path):
    entries = [e for e in ros_entries(2, ODOM, CARLA, None) if e.msgtype != ODOM]
    path = write_ros2_mcap(tmp_path / "noego.mcap", entries)
    with pytest.raises(MissingEgoTopicError) as info:
        open_drive(path)
    assert "/perception/objects [derived_object_msgs/ObjectArray]" in str(info.value)


def test_profile_topic_with_unknown_type(tmp_path):
    ts = typestore(2)
    entries = ros_entries(2, ODOM, CARLA, None)
    pc = [
        Entry(
            "/lidar",
            "sensor_msgs/msg/PointCloud2",
            t,
            rosmsgs.pointcloud(ts, t, 64, np.random.default_rng(0)),
        )
        for t in syn.ego_times()[:3]
    ]
    path = write_ros2_mcap(tmp_path / "pc.mcap", sorted(entries + pc, key=lambda e: e.t_ns))
    profile = tmp_path / "p.toml"
    profile.write_text('[topics]\nobjects = ["/lidar"]\n')
    with pytest.raises(UnknownMessageTypeError) as info:
        open_drive(path, profile=profile)
    assert info.value.topic == "/lidar"
    assert info.value.value == "sensor_msgs/PointCloud2"
    profile.write_text('[topics]\nego = "/nope"\n')
    with pytest.raises(ProfileError, match="/nope"):
        open_drive(path, profile=profile)


def _nan_ego_log(tmp_path: Path) -> Path:
    ts = typestore(2)
    entries = ros_entries(2, ODOM, CARLA, None)
    bad_t = syn.ego_times()[7]
    patched = [
        Entry(e.topic, e.msgtype, e.t_ns, rosmsgs.odometry(ts, e.t_ns, x=float("nan")))
        if e.msgtype == ODOM and e.t_ns == bad_t
        else e
        for e in entries
    ]
    return write_ros2_mcap(tmp_path / "nan.mcap", patched)


def test_nan_ego_pose_raises_after_earlier_frames(tmp_path):
    frames, err = _drain(_nan_ego_log(tmp_path))
    assert isinstance(err, InvalidValueError)
    assert err.topic == "/ego/odometry"
    assert err.t_ns == syn.ego_times()[7]
    assert "nan" in str(err)
    assert len(frames) == 7


def test_nan_ego_pose_skip_policy(tmp_path):
    profile = tmp_path / "skip.toml"
    profile.write_text('[frames]\ninvalid_ego = "skip"\n')
    with closing(open_drive(_nan_ego_log(tmp_path), profile=profile)) as drive:
        frames = list(drive.frames())
        assert drive.info.notes["skipped_invalid_ego"] == "1"
    assert len(frames) == syn.N_FRAMES - 1


def test_nan_object_marks_row_invalid(tmp_path):
    bad_t = syn.object_times()[4]
    entries = []
    for e in ros_entries(2, ODOM, CARLA, None):
        if e.msgtype == CARLA and e.t_ns == bad_t:
            e.msg.objects[1].pose.position.x = float("nan")
        entries.append(e)
    frames, err = _drain(write_ros2_mcap(tmp_path / "nanobj.mcap", entries))
    assert err is None
    assert frames[4].actors.valid.tolist() == [True, False, True]
    assert all(f.actors.valid.all() for f in frames if f.index != 4)


def test_unsupported_suffix_and_missing_path(tmp_path):
    other = tmp_path / "drive.csv"
    other.write_text("x")
    with pytest.raises(UnsupportedFormatError, match=r"\.csv"):
        open_drive(other)
    with pytest.raises(LogNotFoundError) as info:
        open_drive(tmp_path / "missing.mcap")
    assert str(tmp_path / "missing.mcap") in str(info.value)
    with pytest.raises(UnsupportedFormatError):
        open_drive(tmp_path)  # a directory that is not a rosbag2 bag
