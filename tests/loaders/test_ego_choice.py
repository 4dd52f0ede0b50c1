"""Which topic is the ego: ground truth over estimates, the rule `info` shows, `--ego-topic`."""

from __future__ import annotations

from contextlib import closing
from typing import TYPE_CHECKING

import pytest
from typer.testing import CliRunner

from loaders import open_drive
from loaders.errors import ProfileError
from loaders.typestore import typestore
from tests.loaders import rosmsgs
from tests.loaders import synthetic as syn
from tests.loaders.fixtures import Entry, write_rosbag2
from workbench.cli.main import app

if TYPE_CHECKING:
    from pathlib import Path

POSE = "geometry_msgs/msg/PoseStamped"
TOPICS = ("/ORB_SLAM/pose", "/groundtruth/pose", "/odom/pose")


def _three_poses(tmp_path: Path) -> Path:
    ts = typestore(2)
    entries = [
        Entry(topic, POSE, t, rosmsgs.pose_stamped(ts, t))
        for t in syn.ego_times()
        for topic in TOPICS
    ]
    return write_rosbag2(tmp_path / "three_poses", sorted(entries, key=lambda e: e.t_ns), "sqlite3")


def test_ground_truth_wins_over_estimates(tmp_path: Path) -> None:
    with closing(open_drive(_three_poses(tmp_path))) as drive:
        roles = drive.info.roles
    assert roles.ego == "/groundtruth/pose"
    assert roles.ego_rule == "ground truth before estimates"
    assert roles.ego_candidates == ("/groundtruth/pose", "/ORB_SLAM/pose", "/odom/pose")


def test_ego_topic_chooses(tmp_path: Path) -> None:
    bag = _three_poses(tmp_path)
    with closing(open_drive(bag, ego_topic="/odom/pose")) as drive:
        assert drive.info.roles.ego == "/odom/pose"
        assert drive.info.roles.ego_rule == "--ego-topic"
        assert len(list(drive.frames())) == syn.N_FRAMES
    with pytest.raises(ProfileError, match="not in the log"):
        open_drive(bag, ego_topic="/nope")


def test_single_candidate_rule(drive_files: dict[str, Path]) -> None:
    with closing(open_drive(drive_files["ros1-bag"])) as drive:
        assert drive.info.roles.ego_candidates == ("/ego/odometry",)
        assert drive.info.roles.ego_rule == "only candidate"


def test_info_lists_candidates_and_rule(tmp_path: Path) -> None:
    bag = _three_poses(tmp_path)
    result = CliRunner().invoke(app, ["info", str(bag)])
    assert result.exit_code == 0, result.output
    assert "ego         /groundtruth/pose (rule: ground truth before estimates)" in result.output
    assert "candidates  /groundtruth/pose, /ORB_SLAM/pose, /odom/pose" in result.output
    result = CliRunner().invoke(app, ["info", str(bag), "--ego-topic", "/ORB_SLAM/pose"])
    assert result.exit_code == 0, result.output
    assert "ego         /ORB_SLAM/pose (rule: --ego-topic)" in result.output
