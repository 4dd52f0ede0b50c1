"""The review camera frames the ego and the actors of an incident."""

from __future__ import annotations

import math

import pytest

from workbench.replay.blueprint import incident_eye


def _ground_distance(position, target) -> float:
    return math.hypot(position[0] - target[0], position[1] - target[1])


def test_alone_the_eye_keeps_the_replay_offset_behind_the_ego() -> None:
    position, target = incident_eye((100.0, 50.0))
    assert target == (100.0, 50.0, 0.0)
    assert position == (75.0, 50.0, 60.0)


def test_a_near_actor_moves_the_target_to_the_middle() -> None:
    position, target = incident_eye((0.0, 0.0), [(10.0, 0.0)])
    assert target == (5.0, 0.0, 0.0)
    assert position == (-20.0, 0.0, 60.0)  # 5 m apart: no need to pull back


@pytest.mark.parametrize("gap_m", [80.0, 200.0])
def test_far_actors_pull_the_eye_back_in_proportion(gap_m: float) -> None:
    near_pos, near_target = incident_eye((0.0, 0.0))
    position, target = incident_eye((0.0, 0.0), [(gap_m, 0.0), (0.0, gap_m)])
    assert target[:2] == pytest.approx((gap_m / 3, gap_m / 3))
    height_ratio = position[2] / near_pos[2]
    assert height_ratio > 1.0
    assert _ground_distance(position, target) / _ground_distance(near_pos, near_target) == (
        pytest.approx(height_ratio)
    )
    spread = max(
        math.hypot(x - target[0], y - target[1]) for x, y in [(0, 0), (gap_m, 0), (0, gap_m)]
    )
    assert height_ratio == pytest.approx((spread + 10.0) / 30.0)
