"""Nothing can collide, nothing is dangerous: two standing vehicles (the review profiles'
standstill rule) and a pair laterally clear and not converging (every profile)."""

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
from rss.profiles import PROFILES
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


_LANE_W = 3.5


def _side_by_side(gap_m: float, ego_lat_mps: float, other_lat_mps: float, profile: str) -> bool:
    """Ego (left lane) beside another car (right lane), ``gap_m`` apart; whether dangerous."""
    road = (
        RoadSegment(
            tuple(
                LaneSegment(k, LaneDrivingDirection.Positive, 100.0, 100.0, _LANE_W, _LANE_W)
                for k in (1, 2)
            )
        ),
    )
    width = 1.8
    # ego flush with the left lane's right border minus half the gap, other mirrored
    ego_right = 1.0 - gap_m / 2 / _LANE_W
    other_left = gap_m / 2 / _LANE_W
    params = rss_params_from_mapping({}, profile=profile)
    constellation = Constellation(
        ConstellationType.SameDirection,
        LaneObject(
            0,
            ObjectType.EgoVehicle,
            (OccupiedRegion(1, 0.4, 0.45, ego_right - width / _LANE_W, ego_right),),
            SpeedInterval(10.0, 10.0, ego_lat_mps, ego_lat_mps),
        ),
        LaneObject(
            7,
            ObjectType.OtherVehicle,
            (OccupiedRegion(2, 0.41, 0.46, other_left, other_left + width / _LANE_W),),
            SpeedInterval(10.0, 10.0, other_lat_mps, other_lat_mps),
        ),
        params.for_class(ObjectClass.EGO),
        params.for_class(ObjectClass.CAR),
        road,
    )
    result, _ = check_frame(
        stack_constellations([constellation]), params.for_class(ObjectClass.EGO)
    )
    return bool(result.dangerous[0])


@pytest.mark.parametrize("profile", sorted(PROFILES))
@pytest.mark.parametrize(("ego_lat", "other_lat"), [(0.0, 0.0), (-0.5, 0.0), (0.0, 0.8)])
def test_clear_and_not_converging_is_not_dangerous(
    profile: str, ego_lat: float, other_lat: float
) -> None:
    # lateral speed > 0 = to the right: the ego (left) keeps still or moves left, the other
    # keeps still or moves right; longitudinally they overlap (lon unsafe)
    assert not _side_by_side(1.5, ego_lat, other_lat, profile)


@pytest.mark.parametrize("profile", ["adrss-5.0", "urban", "highway"])
def test_converging_at_the_same_gap_is_dangerous(profile: str) -> None:
    assert _side_by_side(1.5, 1.0, -1.0, profile)
