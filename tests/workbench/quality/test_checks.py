"""Each data-quality check on a synthetic trace with one defect, and clean data finds nothing."""

from __future__ import annotations

import dataclasses
import math
from typing import TYPE_CHECKING

import numpy as np
import pytest

from tests.workbench.quality.traces import CAR, T0_NS, braking, drive
from workbench.quality import EGO_ID, Finding, Kind, QualityBounds, check_tracks, tracks_from_frames

if TYPE_CHECKING:
    from collections.abc import Sequence


def _kinds(findings: Sequence[Finding], object_id: str = CAR) -> set[Kind]:
    return {f.kind for f in findings if f.object_id == object_id}


def test_clean_braking_and_the_ego_give_no_finding():
    x, v = braking()
    findings = check_tracks(tracks_from_frames(drive(x, v)))
    assert findings == ()


def test_a_teleport_is_found_at_its_step():
    x, v = braking()
    x = x.copy()
    x[30:] += 6.0  # one 0.1 s step of 6 m more than the motion: 60 m/s for a 15 m/s car
    findings = [f for f in check_tracks(tracks_from_frames(drive(x, v))) if f.kind == Kind.TELEPORT]
    assert len(findings) == 1
    jump = findings[0]
    assert (jump.start_frame, jump.end_frame) == (29, 30)
    step = x[30] - x[29]
    assert jump.value == pytest.approx(step, rel=1e-9)
    assert jump.bound < step
    assert jump.start_ns == T0_NS + 29 * 100_000_000


def test_an_id_that_reappears_far_away_is_an_id_jump_not_a_teleport():
    x, v = braking()
    present = np.ones(len(x), dtype=bool)
    present[20:25] = False  # gone for 0.5 s ...
    x = x.copy()
    x[25:] += 40.0  # ... and back 40 m further than it could have driven
    findings = check_tracks(tracks_from_frames(drive(x, v, present=present)))
    jumps = [f for f in findings if f.kind == Kind.ID_JUMP]
    assert [(f.start_frame, f.end_frame) for f in jumps] == [(19, 25)]
    assert Kind.TELEPORT not in _kinds(findings)
    # the same absence without the jump is plausible
    assert check_tracks(tracks_from_frames(drive(*braking(), present=present))) == ()


def test_recorded_speed_against_positions():
    x, v = braking()
    v = v.copy()
    v[10:13] += 3.0  # the speed trace says 18 m/s, the positions 15 m/s
    findings = [
        f for f in check_tracks(tracks_from_frames(drive(x, v))) if f.kind == Kind.SPEED_MISMATCH
    ]
    assert [(f.start_frame, f.end_frame) for f in findings] == [(10, 12)]
    assert findings[0].value == pytest.approx(3.0, abs=0.05)
    bounds = QualityBounds()
    assert findings[0].bound == pytest.approx(bounds.speed_abs_mps + bounds.speed_rel * 15.0)


def test_a_jerk_spike_and_an_implausible_deceleration():
    x, v = braking(brake_mps2=4.0)
    # the speed trace drops by 8 m/s within one sample and recovers (a glitch): the fitted
    # acceleration swings by about +-16 m/s² within 0.4 s
    v = v.copy()
    v[40] -= 8.0
    findings = check_tracks(tracks_from_frames(drive(x, v)))
    assert _kinds(findings) == {Kind.JERK, Kind.ACCEL, Kind.SPEED_MISMATCH}
    jerk = next(f for f in findings if f.kind == Kind.JERK)
    assert jerk.start_frame <= 40 <= jerk.end_frame
    assert jerk.value > jerk.bound == 50.0
    accel = [f for f in findings if f.kind == Kind.ACCEL]
    assert min(f.value for f in accel) < -10.0  # beyond the car's braking limit
    assert all(f.start_frame >= 38 and f.end_frame <= 42 for f in accel)
    # a plausible hard stop (8 m/s²) is not implausible
    assert check_tracks(tracks_from_frames(drive(*braking(brake_mps2=8.0)))) == ()


def test_heading_against_motion_only_when_moving():
    x, v = braking()
    yaw = np.zeros(len(x))
    yaw[5:8] = math.radians(60.0)  # a box turned 60° off a straight path
    findings = check_tracks(tracks_from_frames(drive(x, v, yaw_rad=yaw)))
    heading = [f for f in findings if f.kind == Kind.HEADING]
    assert [(f.start_frame, f.end_frame) for f in heading] == [(5, 7)]
    assert heading[0].value == pytest.approx(60.0, abs=1e-6)
    # reversing is motion along the axis: heading 180° off the motion is not a finding
    assert check_tracks(tracks_from_frames(drive(x, v, yaw_rad=np.full(len(x), math.pi)))) == ()
    # standing (after the stop) with any heading is not checked
    stop = np.zeros(len(x))
    stop[-5:] = 1.0
    assert not [
        f
        for f in check_tracks(tracks_from_frames(drive(x, v, yaw_rad=stop)))
        if f.kind == Kind.HEADING
    ]


def test_the_ego_is_checked_like_any_object():
    frames = drive(*braking())
    frames[20] = dataclasses.replace(
        frames[20], ego=dataclasses.replace(frames[20].ego, speed_mps=14.0)
    )  # 4 m/s above what its positions say
    findings = check_tracks(tracks_from_frames(frames))
    assert {f.kind for f in findings} >= {Kind.SPEED_MISMATCH}
    assert all(f.object_id == EGO_ID for f in findings)
    assert any(f.start_frame <= 20 <= f.end_frame for f in findings)
