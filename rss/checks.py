"""Structured RSS checks of all constellations of a frame, vectorised (no memory yet).

Implements ad-rss' longitudinal same / opposite direction checks, the lateral check with
fluctuation margin and the intersection checks (able to stop, in front, time overlap) on
``(C,)`` arrays. Every branch is computed for every constellation and selected with
``np.where``; the memory-dependent response adjustment is in :mod:`rss.memory`.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from rss.batch import BoolArray, FloatArray, IntArray, take_rows
from rss.model import ConstellationType
from rss.physics import (
    DISTANCE_MAX_M,
    DISTANCE_PRECISION,
    DURATION_MAX_S,
    DURATION_PRECISION,
    eq,
    gt,
    lt,
    stated_braking_lateral,
    stated_braking_longitudinal,
    stopping_distance,
    time_to_cover_distance,
    tmax,
)
from rss.states import (
    LateralPosition,
    LateralResponse,
    LongitudinalPosition,
    LongitudinalResponse,
    RssStateEvaluator,
)

if TYPE_CHECKING:
    from rss.batch import ConstellationBatch, DynamicsArrays
    from rss.extraction import Relative

__all__ = [
    "IntersectionState",
    "LateralSide",
    "RawStates",
    "check_all",
    "safe_lateral_distance",
    "safe_longitudinal_distance_opposite",
    "safe_longitudinal_distance_same",
]

_P = DISTANCE_PRECISION
_E = RssStateEvaluator
_LON = LongitudinalResponse
_LAT = LateralResponse


class IntersectionState:
    """Codes of the intersection check that last made a constellation safe."""

    NONE = 0
    NON_PRIO_ABLE_TO_BREAK = 1
    SAFE_LONGITUDINAL_DISTANCE = 2
    NO_TIME_OVERLAP = 3


@dataclass(frozen=True)
class LateralSide:
    """One lateral side of ``C`` states.

    Attributes:
        is_safe: ``(C,)``.
        response: ``(C,)`` :class:`LateralResponse` codes.
        evaluator: ``(C,)`` :class:`RssStateEvaluator` codes.
        current_distance_m: ``(C,)`` (:data:`DISTANCE_MAX_M` = not evaluated).
        safe_distance_m: ``(C,)``.
    """

    is_safe: BoolArray
    response: IntArray
    evaluator: IntArray
    current_distance_m: FloatArray
    safe_distance_m: FloatArray


@dataclass(frozen=True)
class RawStates:
    """Check results before the memory adjustment (``(C,)`` each).

    Attributes:
        lon_is_safe: Longitudinal verdict.
        lon_response: :class:`LongitudinalResponse` codes when unsafe (None when safe).
        lon_evaluator: :class:`RssStateEvaluator` codes.
        lon_current_distance_m: Current longitudinal distance.
        lon_safe_distance_m: Safe longitudinal distance.
        left: Lateral state on the ego's left.
        right: Lateral state on the ego's right.
        intersection_state: :class:`IntersectionState` of a safe intersection check.
    """

    lon_is_safe: BoolArray
    lon_response: IntArray
    lon_evaluator: IntArray
    lon_current_distance_m: FloatArray
    lon_safe_distance_m: FloatArray
    left: LateralSide
    right: LateralSide
    intersection_state: IntArray


def _pick(mask: BoolArray, a: FloatArray, b: FloatArray) -> FloatArray:
    return np.asarray(np.where(mask, a, b), dtype=np.float64)


def _stated_braking(
    dyn: DynamicsArrays, speed: FloatArray, decel: FloatArray, cap: FloatArray | None = None
) -> FloatArray:
    return stated_braking_longitudinal(
        speed,
        dyn.max_speed_on_acceleration_mps if cap is None else cap,
        dyn.response_time_s,
        dyn.accel_max_mps2,
        decel,
    )


def safe_longitudinal_distance_same(
    follower: DynamicsArrays,
    follower_speed_max: FloatArray,
    leader: DynamicsArrays,
    leader_speed_min: FloatArray,
) -> FloatArray:
    """Safe distance of a follower behind a leader, same direction (``(C,)``, m)."""
    d_follower = _stated_braking(follower, follower_speed_max, follower.brake_min_mps2)
    d_leader = stopping_distance(leader_speed_min, leader.brake_max_mps2)
    return tmax(d_follower - d_leader, 0.0, _P) + follower.min_longitudinal_safety_distance_m


def safe_longitudinal_distance_opposite(
    correct: DynamicsArrays,
    correct_speed_max: FloatArray,
    opposite: DynamicsArrays,
    opposite_speed_max: FloatArray,
) -> FloatArray:
    """Safe distance of two oncoming vehicles (``(C,)``, m).

    The one in its correct lane brakes with ``brake_min_correct``, the other with ``brake_min``.
    """
    d_correct = _stated_braking(correct, correct_speed_max, correct.brake_min_correct_mps2)
    d_opposite = _stated_braking(opposite, opposite_speed_max, opposite.brake_min_mps2)
    margin = tmax(
        correct.min_longitudinal_safety_distance_m, opposite.min_longitudinal_safety_distance_m, _P
    )
    return np.asarray(d_correct + d_opposite + margin, dtype=np.float64)


def safe_lateral_distance(
    left: DynamicsArrays,
    left_speed_max: FloatArray,
    right: DynamicsArrays,
    right_speed_min: FloatArray,
) -> FloatArray:
    """Safe lateral distance between a left and a right vehicle (``(C,)``, m).

    Lateral speeds are positive to the right; the margin is the mean of both fluctuation
    margins.
    """
    d_left = stated_braking_lateral(
        left_speed_max, left.response_time_s, left.lat_accel_max_mps2, left.lat_brake_min_mps2
    )
    d_right = stated_braking_lateral(
        right_speed_min, right.response_time_s, -right.lat_accel_max_mps2, -right.lat_brake_min_mps2
    )
    margin = 0.5 * (left.lateral_fluctuation_margin_m + right.lateral_fluctuation_margin_m)
    return tmax(d_left - d_right + margin, 0.0, _P)


def _longitudinal(
    batch: ConstellationBatch, rel: Relative
) -> tuple[BoolArray, IntArray, IntArray, FloatArray]:
    ego_d, oth_d = batch.ego_dynamics, batch.other_dynamics
    ego, oth = batch.ego, batch.other
    # same direction
    ego_leads = np.isin(
        rel.lon_position, [LongitudinalPosition.InFront, LongitudinalPosition.OverlapFront]
    )
    safe_other_front = safe_longitudinal_distance_same(
        ego_d, ego.speed_lon_max_mps, oth_d, oth.speed_lon_min_mps
    )
    safe_ego_front = safe_longitudinal_distance_same(
        oth_d, oth.speed_lon_max_mps, ego_d, ego.speed_lon_min_mps
    )
    sd_safe_dist = _pick(ego_leads, safe_ego_front, safe_other_front)
    sd_eval = np.where(
        ego_leads,
        _E.LongitudinalDistanceSameDirectionEgoFront,
        _E.LongitudinalDistanceSameDirectionOtherInFront,
    )
    sd_resp = np.where(ego_leads, _LON.None_, _LON.BrakeMin)
    # opposite direction
    ego_correct = rel.ego_in_correct_lane
    safe_ego_correct = safe_longitudinal_distance_opposite(
        ego_d, ego.speed_lon_max_mps, oth_d, oth.speed_lon_max_mps
    )
    safe_other_correct = safe_longitudinal_distance_opposite(
        oth_d, oth.speed_lon_max_mps, ego_d, ego.speed_lon_max_mps
    )
    od_safe_dist = _pick(ego_correct, safe_ego_correct, safe_other_correct)
    od_eval = np.where(
        ego_correct,
        _E.LongitudinalDistanceOppositeDirectionEgoCorrectLane,
        _E.LongitudinalDistanceOppositeDirection,
    )
    od_resp = np.where(ego_correct, _LON.BrakeMinCorrect, _LON.BrakeMin)

    opposite = batch.constellation_type == ConstellationType.OppositeDirection
    safe_dist = _pick(opposite, od_safe_dist, sd_safe_dist)
    is_safe = gt(rel.lon_distance_m, safe_dist, _P)
    response = np.where(is_safe, _LON.None_, np.where(opposite, od_resp, sd_resp)).astype(np.int64)
    evaluator = np.where(opposite, od_eval, sd_eval).astype(np.int64)
    return is_safe, response, evaluator, safe_dist


def _lateral(batch: ConstellationBatch, rel: Relative) -> tuple[LateralSide, LateralSide]:
    ego_d, oth_d = batch.ego_dynamics, batch.other_dynamics
    ego, oth = batch.ego, batch.other
    ego_left = rel.lat_position == LateralPosition.AtLeft
    ego_right = rel.lat_position == LateralPosition.AtRight
    safe_ego_left = safe_lateral_distance(
        ego_d, ego.speed_lat_max_mps, oth_d, oth.speed_lat_min_mps
    )
    safe_ego_right = safe_lateral_distance(
        oth_d, oth.speed_lat_max_mps, ego_d, ego.speed_lat_min_mps
    )
    gap_safe_right = gt(rel.lat_distance_m, safe_ego_left, _P)
    gap_safe_left = gt(rel.lat_distance_m, safe_ego_right, _P)
    overlap = ~(ego_left | ego_right)
    zero = np.zeros_like(rel.lat_distance_m)
    far = np.full_like(zero, DISTANCE_MAX_M)

    def side(
        evaluated: BoolArray, gap_safe: BoolArray, safe_dist: FloatArray, overlap_safe: BoolArray
    ) -> LateralSide:
        is_safe = np.where(evaluated, gap_safe, np.where(overlap, overlap_safe, np.True_))
        return LateralSide(
            is_safe=np.asarray(is_safe, dtype=np.bool_),
            response=np.where(is_safe, _LAT.None_, _LAT.BrakeMin).astype(np.int64),
            evaluator=np.where(evaluated | overlap, _E.LateralDistance, _E.None_).astype(np.int64),
            current_distance_m=np.where(
                evaluated, rel.lat_distance_m, np.where(overlap, zero, far)
            ),
            safe_distance_m=np.where(evaluated, safe_dist, np.where(overlap, zero, far)),
        )

    left = side(
        ego_right, gap_safe_left, safe_ego_right, rel.lat_position == LateralPosition.OverlapLeft
    )
    right = side(
        ego_left, gap_safe_right, safe_ego_left, rel.lat_position == LateralPosition.OverlapRight
    )
    return left, right


def _intersection(
    batch: ConstellationBatch, rel: Relative
) -> tuple[BoolArray, IntArray, FloatArray, FloatArray, IntArray]:
    """Intersection checks in ad-rss' order; the first success wins."""
    ego_d, oth_d = batch.ego_dynamics, batch.other_dynamics
    ego, oth = batch.ego, batch.other
    ctype = batch.constellation_type
    ego_prio = ctype == ConstellationType.IntersectionEgoHasPriority
    other_prio = ctype == ConstellationType.IntersectionObjectHasPriority

    ego_stop = (
        _stated_braking(ego_d, ego.speed_lon_max_mps, ego_d.brake_min_mps2)
        + ego_d.min_longitudinal_safety_distance_m
    )
    other_stop = (
        _stated_braking(oth_d, oth.speed_lon_max_mps, oth_d.brake_min_mps2)
        + oth_d.min_longitudinal_safety_distance_m
    )
    safe1 = ~ego_prio & lt(ego_stop, rel.ego_dist_to_enter_m, _P)
    try2 = ~safe1 & ~other_prio
    safe2 = try2 & lt(other_stop, rel.other_dist_to_enter_m, _P)
    able = safe1 | safe2

    ego_in_front = rel.lon_position == LongitudinalPosition.InFront
    safe_ego_front = safe_longitudinal_distance_same(
        oth_d, oth.speed_lon_max_mps, ego_d, ego.speed_lon_min_mps
    )
    safe_other_front = safe_longitudinal_distance_same(
        ego_d, ego.speed_lon_max_mps, oth_d, oth.speed_lon_min_mps
    )
    front_dist = _pick(ego_in_front, safe_ego_front, safe_other_front)
    safe3 = ~able & gt(rel.lon_distance_m, front_dist, _P)

    cap = ego_d.max_speed_on_acceleration_mps  # ad-rss uses the ego's cap for both vehicles
    reach_ego = time_to_cover_distance(
        ego.speed_lon_max_mps,
        cap,
        ego_d.response_time_s,
        ego_d.accel_max_mps2,
        ego_d.brake_min_mps2,
        rel.ego_dist_to_enter_m,
    )
    leave_ego = time_to_cover_distance(
        ego.speed_lon_min_mps,
        cap,
        ego_d.response_time_s,
        ego_d.brake_max_mps2,
        ego_d.brake_max_mps2,
        rel.ego_dist_to_leave_m,
    )
    reach_oth = time_to_cover_distance(
        oth.speed_lon_max_mps,
        cap,
        oth_d.response_time_s,
        oth_d.accel_max_mps2,
        oth_d.brake_min_mps2,
        rel.other_dist_to_enter_m,
    )
    leave_oth = time_to_cover_distance(
        oth.speed_lon_min_mps,
        cap,
        oth_d.response_time_s,
        oth_d.brake_max_mps2,
        oth_d.brake_max_mps2,
        rel.other_dist_to_leave_m,
    )
    never = eq(reach_ego, DURATION_MAX_S, DURATION_PRECISION) & eq(
        reach_oth, DURATION_MAX_S, DURATION_PRECISION
    )
    no_overlap = (
        gt(reach_ego, leave_oth, DURATION_PRECISION)
        | gt(reach_oth, leave_ego, DURATION_PRECISION)
        | never
    )
    safe4 = ~able & ~safe3 & no_overlap

    overlap = ~able & ~safe3
    in_front_eval = np.where(ego_in_front, _E.IntersectionEgoInFront, _E.IntersectionOtherInFront)
    evaluator = np.select(
        [safe1, safe2, overlap],
        [
            _E.IntersectionOtherPriorityEgoAbleToStop,
            _E.IntersectionEgoPriorityOtherAbleToStop,
            _E.IntersectionOverlap,
        ],
        in_front_eval,
    ).astype(np.int64)
    current = np.select(
        [safe1, safe2, overlap],
        [rel.ego_dist_to_enter_m, rel.other_dist_to_enter_m, 0.0],
        rel.lon_distance_m,
    )
    safe_dist = np.select([safe1, safe2, overlap], [ego_stop, other_stop, 0.0], front_dist)
    state = np.select(
        [able, safe3, safe4],
        [
            IntersectionState.NON_PRIO_ABLE_TO_BREAK,
            IntersectionState.SAFE_LONGITUDINAL_DISTANCE,
            IntersectionState.NO_TIME_OVERLAP,
        ],
        IntersectionState.NONE,
    ).astype(np.int64)
    return able | safe3 | safe4, evaluator, current, safe_dist, state


def _scatter_intersection(
    batch: ConstellationBatch, rel: Relative, intersection: BoolArray
) -> tuple[BoolArray, IntArray, FloatArray, FloatArray, IntArray]:
    """Run the (costly) intersection checks only on intersection constellations."""
    size = batch.size
    out = (
        np.zeros(size, dtype=np.bool_),
        np.zeros(size, dtype=np.int64),
        np.zeros(size),
        np.zeros(size),
        np.zeros(size, dtype=np.int64),
    )
    rows = np.flatnonzero(intersection)
    if rows.size:
        for target, values in zip(
            out, _intersection(take_rows(batch, rows), take_rows(rel, rows)), strict=True
        ):
            target[rows] = values
    return out


def check_all(batch: ConstellationBatch, rel: Relative) -> RawStates:
    """Run every structured check for every constellation.

    Args:
        batch: ``C`` constellations.
        rel: Their extracted relative situation.

    Returns:
        Raw states; NotRelevant constellations are safe with evaluator None.
    """
    lon_safe, lon_resp, lon_eval, lon_safe_dist = _longitudinal(batch, rel)
    left, right = _lateral(batch, rel)
    ctype = batch.constellation_type
    intersection = ctype >= ConstellationType.IntersectionEgoHasPriority
    i_safe, i_eval, i_current, i_safe_dist, i_state = _scatter_intersection(
        batch, rel, intersection
    )
    relevant = ctype != ConstellationType.NotRelevant

    lon_safe = np.where(intersection, i_safe, lon_safe) | ~relevant
    lon_eval = np.where(intersection, i_eval, lon_eval)
    lon_resp = np.where(lon_safe, _LON.None_, np.where(intersection, _LON.BrakeMin, lon_resp))
    lon_current = np.where(intersection, i_current, rel.lon_distance_m)
    lon_safe_dist = np.where(intersection, i_safe_dist, lon_safe_dist)

    zero = np.zeros_like(lon_current)
    far = np.full_like(zero, DISTANCE_MAX_M)
    none_eval = np.zeros(zero.shape, dtype=np.int64)

    def adjust(side: LateralSide) -> LateralSide:
        fixed = intersection | ~relevant
        return LateralSide(
            is_safe=np.where(intersection, np.False_, side.is_safe) | ~relevant,
            response=np.where(fixed, _LAT.None_, side.response).astype(np.int64),
            evaluator=np.select(
                [intersection, ~relevant], [_E.LateralDistance, _E.None_], side.evaluator
            ),
            current_distance_m=np.select(
                [intersection, ~relevant], [zero, far], side.current_distance_m
            ),
            safe_distance_m=np.select([intersection, ~relevant], [zero, far], side.safe_distance_m),
        )

    return RawStates(
        lon_is_safe=np.asarray(lon_safe, dtype=np.bool_),
        lon_response=lon_resp.astype(np.int64),
        lon_evaluator=np.where(relevant, lon_eval, none_eval),
        lon_current_distance_m=np.where(relevant, lon_current, far),
        lon_safe_distance_m=np.where(relevant, lon_safe_dist, far),
        left=adjust(left),
        right=adjust(right),
        intersection_state=np.where(intersection & i_safe, i_state, IntersectionState.NONE).astype(
            np.int64
        ),
    )
