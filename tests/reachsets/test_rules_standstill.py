"""``road.standstill``: a standing vehicle does not start into the standing ego (public road)."""

from __future__ import annotations

import dataclasses
import math

import pytest

from reachsets.inputs import ReachInputs
from reachsets.params import ReachParams
from reachsets.rules_standstill import STANDSTILL
from tests.reachsets.helpers import evaluate_one, objects, straight_ego
from tests.reachsets.test_rules_lane import LANE_W, three_lanes


def _params(*, lane_rules: bool = True, standstill_mps: float | None = None) -> ReachParams:
    base = ReachParams(full_geometry=False)
    road = dataclasses.replace(base.road, lane_rules=lane_rules)
    if standstill_mps is not None:
        road = dataclasses.replace(road, standstill_speed_mps=standstill_mps)
    return dataclasses.replace(base, road=road)


def _frame(ego_mps: float, *rows: tuple[float, float, float, float]) -> ReachInputs:
    return ReachInputs(
        ego=straight_ego(y0=0.0, speed=ego_mps), objects=objects(*rows), road=three_lanes()
    )


# standing at a red light: a car facing the ego 12 m ahead in its lane (a left-turner waiting
# across the junction, no lane of its direction here) and one ahead in the left lane
_QUEUE = ((12.0, 0.0, math.pi, 0.0), (8.0, LANE_W, 0.0, 0.0))


def test_both_standing_is_no_collision_under_the_public_road_rules() -> None:
    standing = _frame(0.0, *_QUEUE)
    reference, _ = evaluate_one(standing, _params(lane_rules=False))
    assert {c.object_id for c in reference.collisions} == {"o0"}  # 13 m/s^2 from rest
    public_road_without, _ = evaluate_one(standing, _params(standstill_mps=0.0))
    assert "o0" in {c.object_id for c in public_road_without.collisions}
    result, _ = evaluate_one(standing, _params())
    assert result.is_safe
    assert {(p.object_id, p.rule) for p in result.patches if p.rule == STANDSTILL} == {
        ("o0", STANDSTILL),
        ("o1", STANDSTILL),
    }


@pytest.mark.parametrize("creep_mps", [0.2, 0.45])
def test_queue_creep_below_the_threshold_counts_as_standing(creep_mps: float) -> None:
    result, _ = evaluate_one(_frame(0.0, (12.0, 0.0, math.pi, creep_mps)), _params())
    assert result.is_safe
    above, _ = evaluate_one(_frame(0.0, (12.0, 0.0, math.pi, 0.6)), _params())
    assert not above.is_safe


def test_the_rule_needs_both_to_stand() -> None:
    # the ego drives at 5 m/s towards the standing car: its reach still matters
    moving_ego, _ = evaluate_one(_frame(5.0, (12.0, 0.0, 0.0, 0.0)), _params())
    assert STANDSTILL not in {p.rule for p in moving_ego.patches}
    # a car moving towards the standing ego (oncoming in its lane at 3 m/s, 8 m ahead)
    oncoming, _ = evaluate_one(_frame(0.0, (12.7, 0.0, math.pi, 3.0)), _params())
    assert not oncoming.is_safe
    assert STANDSTILL not in {p.rule for p in oncoming.patches}
