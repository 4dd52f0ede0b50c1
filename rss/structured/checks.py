"""Structured RSS checks of all constellations of a frame, vectorised (no memory yet).

Implements ad-rss' longitudinal same / opposite direction checks, the lateral check with
fluctuation margin and the intersection checks (able to stop, in front, time overlap) on
``(C,)`` arrays. Every branch is computed for every constellation and selected with
``np.where``; the memory-dependent response adjustment is in :mod:`rss.structured.memory`.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from rss.model import ConstellationType
from rss.physics import DISTANCE_MAX_M, DISTANCE_PRECISION, gt
from rss.structured.formulas import (
    LATERAL_FIELDS,
    OPPOSITE_FIELDS,
    SAME_FOLLOWER_FIELDS,
    SAME_LEADER_FIELDS,
    pick,
    pick_fields,
    safe_lateral_distance,
    safe_longitudinal_distance_opposite,
    safe_longitudinal_distance_same,
)
from rss.structured.intersection_checks import IntersectionState, intersection_checks
from rss.structured.states import (
    LateralPosition,
    LateralResponse,
    LongitudinalPosition,
    LongitudinalResponse,
    RssStateEvaluator,
)

if TYPE_CHECKING:
    from rss.arrays import BoolArray, FloatArray, IntArray
    from rss.structured.batch import ConstellationBatch, DynamicsArrays
    from rss.structured.extraction import Relative

__all__ = ["IntersectionState", "LateralSide", "RawStates", "check_all"]

_P = DISTANCE_PRECISION
_E = RssStateEvaluator
_LON = LongitudinalResponse
_LAT = LateralResponse


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


def _longitudinal(
    batch: ConstellationBatch, rel: Relative, ego_d: DynamicsArrays, oth_d: DynamicsArrays
) -> tuple[BoolArray, IntArray, IntArray, FloatArray]:
    ego, oth = batch.ego, batch.other
    # same direction
    ego_leads = rel.lon_position <= int(LongitudinalPosition.OverlapFront)  # InFront, OverlapFront
    sd_safe_dist = safe_longitudinal_distance_same(
        pick_fields(ego_leads, oth_d, ego_d, SAME_FOLLOWER_FIELDS),
        pick(ego_leads, oth.speed_lon_max_mps, ego.speed_lon_max_mps),
        pick_fields(ego_leads, ego_d, oth_d, SAME_LEADER_FIELDS),
        pick(ego_leads, ego.speed_lon_min_mps, oth.speed_lon_min_mps),
    )
    sd_eval = np.where(
        ego_leads,
        _E.LongitudinalDistanceSameDirectionEgoFront,
        _E.LongitudinalDistanceSameDirectionOtherInFront,
    )
    sd_resp = np.where(ego_leads, _LON.None_, _LON.BrakeMin)
    # opposite direction
    ego_correct = rel.ego_in_correct_lane
    opposite = batch.constellation_type == ConstellationType.OppositeDirection
    od_safe_dist = sd_safe_dist
    if opposite.any():
        od_safe_dist = safe_longitudinal_distance_opposite(
            pick_fields(ego_correct, ego_d, oth_d, OPPOSITE_FIELDS),
            pick(ego_correct, ego.speed_lon_max_mps, oth.speed_lon_max_mps),
            pick_fields(ego_correct, oth_d, ego_d, OPPOSITE_FIELDS),
            pick(ego_correct, oth.speed_lon_max_mps, ego.speed_lon_max_mps),
        )
    od_eval = np.where(
        ego_correct,
        _E.LongitudinalDistanceOppositeDirectionEgoCorrectLane,
        _E.LongitudinalDistanceOppositeDirection,
    )
    od_resp = np.where(ego_correct, _LON.BrakeMinCorrect, _LON.BrakeMin)
    safe_dist = pick(opposite, od_safe_dist, sd_safe_dist)
    is_safe = gt(rel.lon_distance_m, safe_dist, _P)
    response = np.where(is_safe, _LON.None_, np.where(opposite, od_resp, sd_resp)).astype(np.int64)
    evaluator = np.where(opposite, od_eval, sd_eval).astype(np.int64)
    return is_safe, response, evaluator, safe_dist


def _lateral(
    batch: ConstellationBatch, rel: Relative, ego_d: DynamicsArrays, oth_d: DynamicsArrays
) -> tuple[LateralSide, LateralSide]:
    ego, oth = batch.ego, batch.other
    ego_left = rel.lat_position == LateralPosition.AtLeft
    ego_right = rel.lat_position == LateralPosition.AtRight
    # only one side is evaluated per pair: left vehicle = ego if it is AtLeft, else the other
    safe_dist = safe_lateral_distance(
        pick_fields(ego_left, ego_d, oth_d, LATERAL_FIELDS),
        pick(ego_left, ego.speed_lat_max_mps, oth.speed_lat_max_mps),
        pick_fields(ego_left, oth_d, ego_d, LATERAL_FIELDS),
        pick(ego_left, oth.speed_lat_min_mps, ego.speed_lat_min_mps),
    )
    gap_safe = gt(rel.lat_distance_m, safe_dist, _P)
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

    left = side(ego_right, gap_safe, safe_dist, rel.lat_position == LateralPosition.OverlapLeft)
    right = side(ego_left, gap_safe, safe_dist, rel.lat_position == LateralPosition.OverlapRight)
    return left, right


def check_all(batch: ConstellationBatch, rel: Relative) -> RawStates:
    """Run every structured check for every constellation.

    Args:
        batch: ``C`` constellations.
        rel: Their extracted relative situation.

    Returns:
        Raw states; NotRelevant constellations are safe with evaluator None.
    """
    ego_d, oth_d = batch.ego_dynamics, batch.other_dynamics
    lon_safe, lon_resp, lon_eval, lon_safe_dist = _longitudinal(batch, rel, ego_d, oth_d)
    left, right = _lateral(batch, rel, ego_d, oth_d)
    ctype = batch.constellation_type
    intersection = ctype >= ConstellationType.IntersectionEgoHasPriority
    i_safe, i_eval, i_current, i_safe_dist, i_state = intersection_checks(batch, rel, intersection)
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
            evaluator=np.where(
                intersection,
                int(_E.LateralDistance),
                np.where(relevant, side.evaluator, int(_E.None_)),
            ),
            current_distance_m=np.where(
                intersection, zero, np.where(relevant, side.current_distance_m, far)
            ),
            safe_distance_m=np.where(
                intersection, zero, np.where(relevant, side.safe_distance_m, far)
            ),
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
