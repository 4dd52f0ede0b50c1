"""Autoware.AI objects in a ROS 1 bag, Autoware.Auto trajectories, and the decoders' edge rules.

- ``autoware_msgs/DetectedObjectArray`` (Autoware.AI) written into the ROS 1
  ``highway_cut_in.bag`` gives that bag's RSS verdicts over 150 frames (exactly).
- ``autoware_auto_planning_msgs/Trajectory`` gives the same plans (exactly) and RSS verdicts
  as the same drive with ``autoware_planning_msgs/Trajectory`` (the type read before).
"""

from __future__ import annotations

import json
from contextlib import closing
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
import pytest
from typer.testing import CliRunner

from loaders import open_drive
from loaders.message_logs.decoders.ros_objects import decode_autoware_ai_objects
from loaders.message_logs.decoders.ros_radar import decode_radar_tracks
from loaders.records import ObjectClass
from loaders.typestore import typestore
from tests.loaders.msgbuild import build, header, pose
from tests.loaders.rewrite import rewrite_objects, rewrite_plan
from workbench.cli.main import app

if TYPE_CHECKING:
    from loaders.records import Frame

SAMPLES = Path(__file__).resolve().parents[2] / "sample_logs"
VERDICT_FRAMES = 150
pytestmark = pytest.mark.skipif(
    not (SAMPLES / "highway_cut_in.bag").is_file(), reason="sample logs not generated"
)


def _verdicts(path: Path, out: Path) -> list[dict[str, Any]]:
    args = ["evaluate", str(path), "--engines", "rss", "--end", str(VERDICT_FRAMES / 20)]
    result = CliRunner().invoke(app, [*args, "--per-frame", str(out)])
    assert result.exit_code == 0, result.output
    return [json.loads(line)["rss"] for line in out.read_text().splitlines()]


def _frames(path: Path) -> list[Frame]:
    with closing(open_drive(path)) as drive:
        return list(drive.frames())


def test_autoware_ai_objects_in_a_ros1_bag_give_the_bag_verdicts(tmp_path: Path) -> None:
    source = SAMPLES / "highway_cut_in.bag"
    path = rewrite_objects(source, tmp_path / "ai.bag", "autoware_msgs/msg/DetectedObjectArray")
    with closing(open_drive(path)) as drive:
        assert drive.info.source_format == "ros1-bag"
        assert drive.info.roles.objects == ("/objects",)
    want = _verdicts(source, tmp_path / "want.jsonl")
    got = _verdicts(path, tmp_path / "got.jsonl")
    assert len(got) == len(want) == VERDICT_FRAMES
    assert got == want
    assert any(not r["is_safe"] for r in want)


def test_autoware_auto_trajectory_is_read_like_the_autoware_one(tmp_path: Path) -> None:
    source = SAMPLES / "highway_cut_in.mcap"
    ref = rewrite_plan(source, tmp_path / "ref.mcap", "autoware_planning_msgs/msg/Trajectory")
    auto = rewrite_plan(
        source, tmp_path / "auto.mcap", "autoware_auto_planning_msgs/msg/Trajectory"
    )
    with closing(open_drive(auto)) as drive:
        assert drive.info.roles.plan == "/planning/path"
    planned = 0
    for a, b in zip(_frames(auto), _frames(ref), strict=True):
        assert (a.plan is None) == (b.plan is None)
        if a.plan is None or b.plan is None:
            continue
        planned += 1
        for name in ("x_m", "y_m", "yaw_rad", "t_offset_s", "speed_mps"):
            np.testing.assert_array_equal(getattr(a.plan, name), getattr(b.plan, name))
        # the written timing and speeds, read back (0.1 s and +0.5 m/s per point)
        k = np.arange(len(a.plan.x_m))
        np.testing.assert_allclose(a.plan.t_offset_s, 0.1 * k, atol=1e-9)
        np.testing.assert_allclose(a.plan.speed_mps, 10.0 + 0.5 * k)
    assert planned > VERDICT_FRAMES
    assert _verdicts(auto, tmp_path / "a.jsonl") == _verdicts(ref, tmp_path / "b.jsonl")


def _ai_object(ts: Any, oid: int, label: str, *, reliable: bool) -> Any:
    velocity = build(
        ts,
        "geometry_msgs/msg/Twist",
        linear=build(ts, "geometry_msgs/msg/Vector3", x=2.0, y=0.0, z=0.0),
    )
    return build(
        ts,
        "autoware_msgs/msg/DetectedObject",
        id=oid,
        label=label,
        pose=pose(ts, 1.0, 2.0, 0.0, np.pi / 2),
        dimensions=build(ts, "geometry_msgs/msg/Vector3", x=4.0, y=2.0, z=1.5),
        velocity=velocity,
        velocity_reliable=reliable,
    )


@pytest.mark.parametrize("ros_version", [1, 2])
def test_autoware_ai_ids_classes_and_velocity_frame(ros_version: int) -> None:
    ts = typestore(ros_version)
    objs = [_ai_object(ts, 7, "person", reliable=True), _ai_object(ts, 9, "Bus", reliable=True)]
    msg = build(
        ts, "autoware_msgs/msg/DetectedObjectArray", header=header(ts, 5 * 10**9), objects=objs
    )
    cols = decode_autoware_ai_objects(msg)
    assert cols.ids == ["7", "9"]
    assert list(cols.object_class) == [ObjectClass.PEDESTRIAN, ObjectClass.BUS]
    assert cols.has_velocity
    # 2 m/s along a heading of +90 degrees: map-frame velocity (0, 2)
    np.testing.assert_allclose(cols.vx_mps, [0.0, 0.0], atol=1e-12)
    np.testing.assert_allclose(cols.vy_mps, [2.0, 2.0])


def test_autoware_ai_detections_without_ids_or_reliable_velocity() -> None:
    ts = typestore(1)
    objs = [_ai_object(ts, 0, "car", reliable=False), _ai_object(ts, 0, "car", reliable=True)]
    msg = build(ts, "autoware_msgs/msg/DetectedObjectArray", header=header(ts, 0), objects=objs)
    cols = decode_autoware_ai_objects(msg)
    assert cols.ids == ["det0", "det1"]
    assert not cols.has_velocity  # one unreliable velocity: the message's are estimated


def test_radar_track_yaw_class_and_id() -> None:
    ts = typestore(2)

    def track(k: int, vx: float, vy: float, classification: int) -> Any:
        return build(
            ts,
            "radar_msgs/msg/RadarTrack",
            uuid=build(ts, "unique_identifier_msgs/msg/UUID", uuid=np.full(16, k, np.uint8)),
            velocity=build(ts, "geometry_msgs/msg/Vector3", x=vx, y=vy, z=0.0),
            classification=classification,
        )

    tracks = [track(1, 0.0, -3.0, 32007), track(2, 0.01, 0.05, 2), track(3, 1.0, 1.0, 32001)]
    msg = build(ts, "radar_msgs/msg/RadarTracks", header=header(ts, 0), tracks=tracks)
    cols = decode_radar_tracks(msg)
    assert cols.ids[0] == "01" * 16
    np.testing.assert_allclose(cols.yaw_rad, [-np.pi / 2, 0.0, np.pi / 4])
    assert list(cols.object_class) == [ObjectClass.PEDESTRIAN, ObjectClass.UNKNOWN, ObjectClass.CAR]
