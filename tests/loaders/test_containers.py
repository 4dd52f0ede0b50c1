"""Containers beyond the samples' own: ROS 1 MCAP, bare ``.db3``, split rosbag2, service events.

Each is written from a sample log and must read into the same frames as that sample.
"""

from __future__ import annotations

import shutil
from contextlib import closing
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np
import pytest

from loaders import open_drive
from loaders.errors import UnsupportedFormatError
from tests.loaders import containers

if TYPE_CHECKING:
    from loaders.records import Frame

SAMPLES = Path(__file__).resolve().parents[2] / "sample_logs"


def _frames(path: Path) -> tuple[list[Frame], dict[str, str], str]:
    with closing(open_drive(path)) as drive:
        frames = list(drive.frames())
        return frames, dict(drive.info.notes), drive.info.source_format


def _same(a: list[Frame], b: list[Frame]) -> None:
    assert len(a) == len(b) > 0
    for fa, fb in zip(a, b, strict=True):
        assert fa.t_ns == fb.t_ns
        assert (fa.ego.x_m, fa.ego.y_m, fa.ego.yaw_rad, fa.ego.speed_mps) == (
            fb.ego.x_m,
            fb.ego.y_m,
            fb.ego.yaw_rad,
            fb.ego.speed_mps,
        )
        np.testing.assert_array_equal(fa.actors.ids, fb.actors.ids)
        np.testing.assert_array_equal(fa.actors.x_m, fb.actors.x_m)


def test_ros1_mcap_reads_like_its_bag(tmp_path: Path) -> None:
    bag = SAMPLES / "highway_cut_in.bag"
    frames, _, fmt = _frames(containers.ros1_mcap(bag, tmp_path / "drive.mcap"))
    assert fmt == "ros1-mcap"
    _same(frames, _frames(bag)[0])


def test_bare_db3_reads_like_its_rosbag2_directory(tmp_path: Path) -> None:
    bag = SAMPLES / "highway_cut_in_rosbag2"
    db3 = containers.bare_db3(bag, tmp_path)
    before = sorted(p.name for p in tmp_path.iterdir())
    frames, _, fmt = _frames(db3)
    assert fmt == "rosbag2-sqlite3"
    _same(frames, _frames(bag)[0])
    assert sorted(p.name for p in tmp_path.iterdir()) == before  # nothing written beside it


def test_split_rosbag2_is_read_whole(tmp_path: Path) -> None:
    bag = SAMPLES / "highway_cut_in_rosbag2"
    split = containers.split_rosbag2(bag, tmp_path)
    assert len(list(split.glob("*.db3"))) == 2
    _same(_frames(split)[0], _frames(bag)[0])


def test_service_event_channels_are_ignored_with_a_note(tmp_path: Path) -> None:
    mcap = SAMPLES / "highway_cut_in.mcap"
    frames, notes, _ = _frames(containers.with_service_events(mcap, tmp_path / "jazzy.mcap"))
    _same(frames, _frames(mcap)[0])
    assert notes["ignored_service_channels"] == "/set_flag/_service_event"


def test_wrong_serialization_format_is_named(tmp_path: Path) -> None:
    bag = shutil.copytree(SAMPLES / "highway_cut_in_rosbag2", tmp_path / "bag")
    meta = bag / "metadata.yaml"
    meta.write_text(
        meta.read_text().replace("serialization_format: cdr", "serialization_format: ros1", 1)
    )
    with pytest.raises(UnsupportedFormatError, match=r"serialization format \{'ros1'\}; only cdr"):
        open_drive(bag)
