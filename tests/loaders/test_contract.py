"""Contract test: every reader yields the same frames for the same synthetic drive."""

from __future__ import annotations

import math
from contextlib import closing

import numpy as np
import pytest

from loaders import ObjectClass, open_drive
from tests.loaders import synthetic as syn
from tests.loaders.fixtures import FORMATS, expected_id

CLASSES = {"car": ObjectClass.CAR, "truck": ObjectClass.TRUCK, "pedestrian": ObjectClass.PEDESTRIAN}
POSE_TOL_M = 0.2  # first sighting of formats without velocity extrapolates with v = 0


@pytest.fixture(params=sorted(FORMATS))
def fmt(request: pytest.FixtureRequest) -> str:
    return str(request.param)


def test_frames_match_the_synthetic_drive(fmt, drive_files):
    with closing(open_drive(drive_files[fmt])) as drive:
        frames = list(drive.frames())
        info = drive.info
    assert info.source_format == fmt
    assert len(frames) == info.frame_count == syn.N_FRAMES
    assert [f.t_ns for f in frames] == syn.ego_times()
    assert [f.index for f in frames] == list(range(syn.N_FRAMES))
    for frame in frames:
        x, y, yaw = syn.ego_state(frame.t_ns)
        assert frame.ego.x_m == pytest.approx(x, abs=1e-6)
        assert frame.ego.y_m == pytest.approx(y, abs=1e-6)
        assert frame.ego.yaw_rad == pytest.approx(yaw, abs=1e-6)
        assert frame.ego.speed_mps == pytest.approx(syn.EGO_SPEED, abs=1e-3)
        assert frame.ego.accel_mps2 == pytest.approx(0.0, abs=1e-3)
        actors = frame.actors
        assert len(actors) == len(syn.ACTORS)
        assert actors.valid.all()
        assert (actors.match_dt_ns == syn.OBJECT_LEAD_NS).all()
        for actor in syn.ACTORS:
            (k,) = np.flatnonzero(actors.ids == expected_id(fmt, actor.id))
            ax, ay = syn.actor_state(actor, frame.t_ns)
            assert actors.object_class[k] == CLASSES[actor.cls]
            assert actors.x_m[k] == pytest.approx(ax, abs=POSE_TOL_M)
            assert actors.y_m[k] == pytest.approx(ay, abs=POSE_TOL_M)
            assert math.cos(actors.yaw_rad[k] - actor.yaw) == pytest.approx(1.0, abs=1e-6)
            assert actors.length_m[k] == pytest.approx(actor.length, rel=1e-5)
            assert actors.width_m[k] == pytest.approx(actor.width, rel=1e-5)
            assert actors.height_m[k] == pytest.approx(actor.height, rel=1e-5)
            if frame.index > 0:
                assert actors.vx_mps[k] == pytest.approx(actor.vx, abs=1e-3)
                assert actors.vy_mps[k] == pytest.approx(actor.vy, abs=1e-3)
                assert actors.x_m[k] == pytest.approx(ax, abs=1e-3)


def test_monotonic_readonly_and_roles(fmt, drive_files):
    with closing(open_drive(drive_files[fmt])) as drive:
        frames = list(drive.frames())
        roles = {t.topic: t.role for t in drive.info.topics}
        assert roles[drive.info.roles.ego] == "ego"
    times = np.array([f.t_ns for f in frames])
    assert (np.diff(times) > 0).all()
    frame = frames[5]
    for name in ("ids", "x_m", "vx_mps", "valid", "match_dt_ns"):
        array = getattr(frame.actors, name)
        assert not array.flags.writeable
        with pytest.raises(ValueError, match="read-only"):
            array[0] = array[0]


def test_plan_is_latest_at_or_before_frame(fmt, drive_files):
    with closing(open_drive(drive_files[fmt])) as drive:
        frames = list(drive.frames())
    if fmt == "mcap-protobuf":
        assert all(f.plan is None for f in frames)
        return
    plan_times = syn.plan_times()
    for frame in frames:
        latest = max(t for t in plan_times if t <= frame.t_ns)
        assert frame.plan is not None
        assert frame.plan.x_m[0] == pytest.approx(syn.ego_state(latest)[0])
        assert not frame.plan.x_m.flags.writeable
        if fmt in {"ros1-bag", "rosbag2-mcap"}:  # nav_msgs/Path: no timing
            assert np.isnan(frame.plan.t_offset_s).all()
        else:
            assert frame.plan.t_offset_s[1] == pytest.approx(1.0)
            assert frame.plan.speed_mps[1] == pytest.approx(syn.EGO_SPEED)


def test_window_bounds_frames(fmt, drive_files):
    times = syn.ego_times()
    with closing(open_drive(drive_files[fmt], window=(times[10], times[20]))) as drive:
        frames = list(drive.frames())
    assert [f.t_ns for f in frames] == times[10:20]
    assert len(frames[0].actors) == len(syn.ACTORS)
    assert frames[0].ego.speed_mps == pytest.approx(syn.EGO_SPEED, abs=1e-3)
