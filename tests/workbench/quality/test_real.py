"""Data quality on real NGSIM data: the Peach-4_8 ego's recorded speed against its positions."""

from __future__ import annotations

import itertools

import numpy as np
import pytest

from loaders.open import open_drive
from workbench.quality import EGO_ID, Kind, check_tracks, tracks_from_frames

PEACH = "commonroad_ngsim/USA_Peach-4_8_T-1.xml"


@pytest.fixture(scope="module")
def peach(external_dir):
    drive = open_drive(external_dir / PEACH)
    try:
        return list(drive.frames())
    finally:
        drive.close()


def test_peach_ego_speed_disagrees_with_its_positions_at_frame_22(peach):
    findings = [f for f in check_tracks(tracks_from_frames(peach)) if f.object_id == EGO_ID]
    mismatch = [f for f in findings if f.kind == Kind.SPEED_MISMATCH]
    assert any(f.start_frame <= 22 <= f.end_frame for f in mismatch)
    # what the finding says, recomputed from the frames: recorded 8.73 m/s, positions 6.9
    ego = [f.ego for f in peach]
    step = [np.hypot(b.x_m - a.x_m, b.y_m - a.y_m) / 0.1 for a, b in itertools.pairwise(ego[21:24])]
    worst = max(f.value for f in mismatch)
    assert worst == pytest.approx(ego[22].speed_mps - max(step), abs=0.01)
    assert ego[22].speed_mps == pytest.approx(8.73, abs=0.01)
    # then 6.9 -> 0.45 m/s within 0.5 s: a deceleration beyond any car's
    accel = [f for f in findings if f.kind == Kind.ACCEL]
    assert accel
    assert min(f.value for f in accel) < -10.0
    assert all(f.start_frame >= 22 and f.end_frame <= 30 for f in accel)


def test_peach_findings_name_existing_objects_and_frames(peach):
    findings = check_tracks(tracks_from_frames(peach))
    ids = {EGO_ID} | {i for f in peach for i in f.actors.ids.tolist()}
    assert findings
    for f in findings:
        assert f.object_id in ids
        assert 0 <= f.start_frame <= f.end_frame < len(peach)
        assert abs(f.value) > abs(f.bound)
