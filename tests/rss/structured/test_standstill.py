"""The review profiles' standstill rule: two standing vehicles in a queue are not a danger."""

from __future__ import annotations

import pytest

from rss.model import (
    Constellation,
    ConstellationType,
    LaneDrivingDirection,
    LaneObject,
    LaneSegment,
    ObjectType,
    OccupiedRegion,
    RoadSegment,
    SpeedInterval,
)
from rss.params import ObjectClass, rss_params_from_mapping
from rss.structured.engine import check_frame
from rss.structured.stacking import stack_constellations
from rss.structured.standstill import apply_standstill

_LANE_M = 100.0
_CAR_M = 4.5


def _queue(
    gap_m: float, ego_mps: float, other_mps: float, *, other_ahead: bool, profile: str = "urban"
) -> Constellation:
    """Ego and another car in one 100 m lane, ``gap_m`` bumper to bumper."""
    road = (
        RoadSegment((LaneSegment(1, LaneDrivingDirection.Positive, _LANE_M, _LANE_M, 3.5, 3.5),)),
    )
    rear, front = 40.0, 40.0 + _CAR_M + gap_m

    def region(start_m: float) -> OccupiedRegion:
        return OccupiedRegion(1, start_m / _LANE_M, (start_m + _CAR_M) / _LANE_M, 0.2, 0.8)

    ego_at, other_at = (rear, front) if other_ahead else (front, rear)
    params = rss_params_from_mapping({}, profile=profile)
    return Constellation(
        ConstellationType.SameDirection,
        LaneObject(
            0, ObjectType.EgoVehicle, (region(ego_at),), SpeedInterval(ego_mps, ego_mps, 0.0, 0.0)
        ),
        LaneObject(
            7,
            ObjectType.OtherVehicle,
            (region(other_at),),
            SpeedInterval(other_mps, other_mps, 0.0, 0.0),
        ),
        params.for_class(ObjectClass.EGO),
        params.for_class(ObjectClass.CAR),
        road,
    )


def _dangerous(constellation: Constellation, standstill_mps: float) -> bool:
    batch = apply_standstill(stack_constellations([constellation]), standstill_mps)
    ego = rss_params_from_mapping({}, profile="urban").for_class(ObjectClass.EGO)
    result, _ = check_frame(batch, ego, None)
    return bool(result.dangerous[0])


@pytest.mark.parametrize("other_ahead", [True, False])
@pytest.mark.parametrize("gap_m", [0.23, 1.0, 2.5])
def test_both_standing_at_a_queue_gap_is_not_dangerous(gap_m: float, other_ahead: bool) -> None:
    # the ad-rss assumption: a standing car may start with accel_max during rho (ego 1 s:
    # 3.28 m needed behind a standing leader; another car 2 s: 13.1 m behind the ego)
    assert _dangerous(_queue(gap_m, 0.0, 0.0, other_ahead=other_ahead, profile="adrss-5.0"), 0.0)
    for profile in ("adrss-5.0", "urban", "highway"):
        queue = _queue(gap_m, 0.0, 0.0, other_ahead=other_ahead, profile=profile)
        assert not _dangerous(queue, 0.1)


def test_both_standing_pair_becomes_not_relevant_and_others_keep_their_type() -> None:
    pairs = [_queue(1.0, 0.0, 0.0, other_ahead=True), _queue(1.0, 5.0, 0.0, other_ahead=True)]
    batch = apply_standstill(stack_constellations(pairs), 0.1)
    assert batch.constellation_type.tolist() == [
        int(ConstellationType.NotRelevant),
        int(ConstellationType.SameDirection),
    ]
    # the standing leader keeps standing during its response time; the moving ego keeps its
    assert batch.other_dynamics.accel_max_mps2.tolist() == [0.0, 0.0]
    assert batch.ego_dynamics.accel_max_mps2.tolist() == [0.0, 2.0]
    assert apply_standstill(stack_constellations(pairs), 0.0) is not batch


def test_moving_follower_approaching_a_standing_ego_stays_dangerous() -> None:
    # 3 m/s, 1 m behind a standing ego: it cannot stop in time whatever the rule says
    assert _dangerous(_queue(1.0, 0.0, 3.0, other_ahead=False), 0.1)
    # the ego creeping at 0.5 m/s (above the threshold) towards a standing car 0.3 m ahead
    assert _dangerous(_queue(0.3, 0.5, 0.0, other_ahead=True), 0.1)


def test_standing_follower_behind_a_moving_ego_is_safe_when_the_ego_pulls_away() -> None:
    # the standing car 1 m behind may not be assumed to start at accel_max (CARLA's rule)
    pulling_away = _queue(1.0, 2.0, 0.0, other_ahead=False)
    assert _dangerous(pulling_away, 0.0)
    assert not _dangerous(pulling_away, 0.1)
