"""Real third-party logs (``shared/external/real_logs``): every frame accounted for.

A Clearpath Jackal ROS 1 bag (odometry logged with repeated millisecond log times) and an
Autoware ego trajectory in a bare rosbag2 ``.db3`` with its Lanelet2 map, each evaluated with
every engine. Skipped with a reason when the external data is absent (failed under CI=true).
"""

from __future__ import annotations

from contextlib import closing
from typing import TYPE_CHECKING

import pytest
from typer.testing import CliRunner

from loaders import open_drive
from loaders.losses import count_frames
from workbench.cli.main import app

if TYPE_CHECKING:
    from pathlib import Path

ENGINES = "rss,unstructured,reachsets"


@pytest.fixture
def real_logs(external_dir: Path) -> Path:
    return external_dir / "real_logs"


def _evaluate(args: list[str], out: Path) -> str:
    result = CliRunner().invoke(
        app, ["evaluate", *args, "--engines", ENGINES, "--per-frame", str(out)]
    )
    assert result.exit_code == 0, result.output
    return result.output


def test_jackal_bag_every_ego_message_accounted_for(real_logs: Path, tmp_path: Path) -> None:
    bag = real_logs / "test2.bag"
    with closing(open_drive(bag)) as drive:
        frames = count_frames(drive)
        dropped = int(drive.info.notes["skipped_out_of_order_ego"])
        assert (frames, dropped, drive.info.frame_count) == (2701, 359, 3060)
    out = tmp_path / "frames.jsonl"
    output = _evaluate([str(bag)], out)
    assert len(out.read_text().splitlines()) == frames
    assert f"{frames} frames evaluated" in output
    assert f"not in any frame: {dropped} ego messages dropped" in output


def test_jackal_bag_on_header_stamps_keeps_every_message(real_logs: Path, tmp_path: Path) -> None:
    profile = tmp_path / "header.toml"
    profile.write_text('[frames]\nclock = "header"\n')
    with closing(open_drive(real_logs / "test2.bag", profile=profile)) as drive:
        assert count_frames(drive) == drive.info.frame_count == 3060
        assert "skipped_out_of_order_ego" not in drive.info.notes


def test_autoware_ego_trajectory_in_a_bare_db3(real_logs: Path, tmp_path: Path) -> None:
    db3 = real_logs / "bag_ego_trajectory.db3"
    osm = real_logs / "cargo_transport_map.osm"
    before = sorted(p.name for p in real_logs.iterdir())
    with closing(open_drive(db3, map=osm)) as drive:
        assert drive.info.source_format == "rosbag2-sqlite3"
        assert drive.lane_map is not None
        assert count_frames(drive) == drive.info.frame_count == 2130
    out = tmp_path / "frames.jsonl"
    output = _evaluate([str(db3), "--map", str(osm)], out)
    assert len(out.read_text().splitlines()) == 2130
    assert "2130 frames evaluated" in output
    assert "not in any frame" not in output
    assert sorted(p.name for p in real_logs.iterdir()) == before  # nothing written beside it
