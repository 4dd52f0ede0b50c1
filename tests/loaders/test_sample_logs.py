"""Contract over whatever ``sample_logs/`` holds (``*.mcap``, ``*.bag``, rosbag2 dirs).

Collected at import time, so the test covers the samples as soon as they are generated;
with no samples it reports one skip.
"""

from __future__ import annotations

from contextlib import closing
from pathlib import Path

import numpy as np
import pytest

from loaders import open_drive

SAMPLE_DIR = Path(__file__).resolve().parents[2] / "sample_logs"


def _samples() -> list[Path]:
    if not SAMPLE_DIR.is_dir():
        return []
    found = sorted(SAMPLE_DIR.glob("*.mcap")) + sorted(SAMPLE_DIR.glob("*.bag"))
    found += sorted(p for p in SAMPLE_DIR.iterdir() if (p / "metadata.yaml").is_file())
    return found


SAMPLES = _samples()


@pytest.mark.skipif(not SAMPLES, reason=f"no sample logs in {SAMPLE_DIR}")
@pytest.mark.parametrize("path", SAMPLES, ids=lambda p: p.name)
def test_sample_log_contract(path: Path):
    with closing(open_drive(path)) as drive:
        info = drive.info
        frames = list(drive.frames())
        lane_map = drive.lane_map
    assert len(frames) == info.frame_count > 0
    times = np.array([f.t_ns for f in frames])
    assert (np.diff(times) > 0).all()
    assert [f.index for f in frames] == list(range(len(frames)))
    for frame in frames:
        assert np.isfinite([frame.ego.x_m, frame.ego.y_m, frame.ego.yaw_rad]).all()
        assert not frame.actors.x_m.flags.writeable
        assert (frame.actors.match_dt_ns >= 0).all()
        assert (frame.actors.match_dt_ns <= info.match_tolerance_ns).all()
    assert any(len(f.actors) for f in frames)
    assert lane_map is not None, "map not found (attachment or sidecar .osm)"
    assert len(lane_map.lanes) > 0
