"""The engine gives a verdict on every frame of real maps (NGSIM lanelets, Autoware Lanelet2).

Regression for issue 17: seven of the eleven CommonRoad NGSIM scenarios and the Autoware map
have solid lines of different lengths, on which the road geometry used to fail the whole
drive. A few frames of each drive keep this test short.
"""

from __future__ import annotations

import dataclasses
import itertools
import json
import sqlite3
from typing import TYPE_CHECKING

import pytest

from loaders.open import open_drive
from reachsets import ReachParams, evaluate_frames
from workbench.engines.reachsets.adapter import frame_to_reach_inputs, prepare_map

if TYPE_CHECKING:
    from pathlib import Path

pytestmark = pytest.mark.external

#: The CommonRoad NGSIM scenarios in ``shared/external/commonroad_ngsim``.
NGSIM = (
    "USA_Lanker-1_1_T-1",
    "USA_Lanker-1_4_T-1",
    "USA_Lanker-2_23_T-1",
    "USA_Peach-3_1_T-1",
    "USA_Peach-4_8_T-1",
    "USA_US101-23_1_T-1",
    "USA_US101-24_2_T-1",
    "USA_US101-3_1_T-1",
    "USA_US101-3_3_T-1",
    "USA_US101-4_1_T-1",
    "USA_US101-5_1_T-1",
)
#: Frames evaluated per drive (every ``STRIDE``-th from the start; the shortest drive has 16).
FRAMES, STRIDE = 4, 4


def _verdicts(
    drive_path: Path, map_path: Path | None = None, params: ReachParams | None = None
) -> list[bool]:
    """``is_safe`` of ``FRAMES`` frames of the drive, checking that no road element was dropped."""
    drive = open_drive(drive_path, map=map_path)
    try:
        assert drive.lane_map is not None
        reach_map = prepare_map(drive.lane_map)
        assert reach_map.road is not None
        frames = itertools.islice(drive.frames(), 0, FRAMES * STRIDE, STRIDE)
        inputs = [frame_to_reach_inputs(f, reach_map) for f in frames]
    finally:
        drive.close()
    assert len(inputs) == FRAMES
    results, _ = evaluate_frames(inputs, params or ReachParams(), None)
    assert all(r.skipped_road == () for r in results)
    return [r.is_safe for r in results]


@pytest.mark.parametrize("name", NGSIM)
def test_engine_rates_every_frame_of_ngsim(external_dir, name):
    verdicts = _verdicts(external_dir / "commonroad_ngsim" / f"{name}.xml")
    assert len(verdicts) == FRAMES
    assert all(isinstance(v, bool) for v in verdicts)


@pytest.mark.parametrize("name", NGSIM)
def test_lane_rules_rate_every_frame_of_ngsim(external_dir, name):
    """The public-road lane rules build their corridors on every NGSIM lanelet map."""
    base = ReachParams()
    params = dataclasses.replace(base, road=dataclasses.replace(base.road, lane_rules=True))
    verdicts = _verdicts(external_dir / "commonroad_ngsim" / f"{name}.xml", params=params)
    assert len(verdicts) == FRAMES
    assert all(isinstance(v, bool) for v in verdicts)


def _rosbag2_dir(db3: Path, out: Path) -> Path:
    """A rosbag2 directory around a bare sqlite3 file: the file linked, ``metadata.yaml`` written.

    The metadata (JSON, which is YAML) lists the file's topics with their QoS as stored, so
    the reader matches its connections.
    """
    out.mkdir()
    (out / db3.name).symlink_to(db3)
    with sqlite3.connect(f"file:{db3}?mode=ro", uri=True) as db:
        topics = db.execute(
            "SELECT id, name, type, serialization_format, offered_qos_profiles FROM topics"
        ).fetchall()
        counts = dict(db.execute("SELECT topic_id, COUNT(*) FROM messages GROUP BY topic_id"))
        t0, t1, n = db.execute(
            "SELECT MIN(timestamp), MAX(timestamp), COUNT(*) FROM messages"
        ).fetchone()
    span = {"starting_time": {"nanoseconds_since_epoch": t0}, "duration": {"nanoseconds": t1 - t0}}
    info = {
        "version": 5,
        "storage_identifier": "sqlite3",
        **span,
        "message_count": n,
        "topics_with_message_count": [
            {
                "topic_metadata": {
                    "name": name,
                    "type": msgtype,
                    "serialization_format": fmt,
                    "offered_qos_profiles": qos,
                },
                "message_count": counts.get(tid, 0),
            }
            for tid, name, msgtype, fmt, qos in topics
        ],
        "compression_format": "",
        "compression_mode": "",
        "relative_file_paths": [db3.name],
        "files": [{"path": db3.name, **span, "message_count": n}],
    }
    (out / "metadata.yaml").write_text(json.dumps({"rosbag2_bagfile_information": info}))
    return out


def test_engine_rates_every_frame_on_the_autoware_map(external_dir, tmp_path):
    logs = external_dir / "real_logs"
    bag = _rosbag2_dir(logs / "bag_ego_trajectory.db3", tmp_path / "bag")
    verdicts = _verdicts(bag, logs / "cargo_transport_map.osm")
    assert len(verdicts) == FRAMES
    assert all(isinstance(v, bool) for v in verdicts)
