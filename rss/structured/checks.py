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


#: Codes as plain ints (an enum member costs an attribute look-up and a conversion per use).
_SD_EGO_FRONT = int(_E.LongitudinalDistanceSameDirectionEgoFront)
_SD_OTHER_FRONT = int(_E.LongitudinalDistanceSameDirectionOtherInFront)
_OD_CORRECT = int(_E.LongitudinalDistanceOppositeDirectionEgoCorrectLane)
_OD = int(_E.LongitudinalDistanceOppositeDirection)
_LAT_EVAL = int(_E.LateralDistance)
_BRAKE_MIN = int(_LON.BrakeMin)
_BRAKE_MIN_CORRECT = int(_LON.BrakeMinCorrect)
_LAT_BRAKE_MIN = int(_LAT.BrakeMin)


def _longitudinal(
    batch: ConstellationBatch, rel: Relative, ego_d: DynamicsArrays, oth_d: DynamicsArrays
) -> tuple[BoolArray, IntArray, IntArray, FloatArray]:
    ego, oth = batch.ego, batch.other
    # same direction
    ego_leads = rel.lon_position <= int(LongitudinalPosition.OverlapFront)  # InFront, OverlapFront
    safe_dist = safe_longitudinal_distance_same(
        pick_fields(ego_leads, oth_d, ego_d, SAME_FOLLOWER_FIELDS),
        pick(ego_leads, oth.speed_lon_max_mps, ego.speed_lon_max_mps),
        pick_fields(ego_leads, ego_d, oth_d, SAME_LEADER_FIELDS),
        pick(ego_leads, ego.speed_lon_min_mps, oth.speed_lon_min_mps),
    )
    evaluator = np.where(ego_leads, _SD_EGO_FRONT, _SD_OTHER_FRONT)
    response = np.where(ego_leads, 0, _BRAKE_MIN)
    # opposite direction (only computed when a constellation is of that type)
    opposite = batch.constellation_type == ConstellationType.OppositeDirection
    if opposite.any():
        ego_correct = rel.ego_in_correct_lane
        od_safe_dist = safe_longitudinal_distance_opposite(
            pick_fields(ego_correct, ego_d, oth_d, OPPOSITE_FIELDS),
            pick(ego_correct, ego.speed_lon_max_mps, oth.speed_lon_max_mps),
            pick_fields(ego_correct, oth_d, ego_d, OPPOSITE_FIELDS),
            pick(ego_correct, oth.speed_lon_max_mps, ego.speed_lon_max_mps),
        )
        np.copyto(safe_dist, od_safe_dist, where=opposite)
        np.copyto(evaluator, np.where(ego_correct, _OD_CORRECT, _OD), where=opposite)
        np.copyto(response, np.where(ego_correct, _BRAKE_MIN_CORRECT, _BRAKE_MIN), where=opposite)
    is_safe = gt(rel.lon_distance_m, safe_dist, _P)
    response[is_safe] = 0
    return (
        is_safe,
        response.astype(np.int64, copy=False),
        evaluator.astype(np.int64, copy=False),
        safe_dist,
    )


def _lateral(
    batch: ConstellationBatch, rel: Relative, ego_d: DynamicsArrays, oth_d: DynamicsArrays
) -> tuple[LateralSide, LateralSide]:
    ego, oth = batch.ego, batch.other
    lat_position = rel.lat_position
    ego_left = lat_position == LateralPosition.AtLeft
    ego_right = lat_position == LateralPosition.AtRight
    # only one side is evaluated per pair: left vehicle = ego if it is AtLeft, else the other
    safe_dist = safe_lateral_distance(
        pick_fields(ego_left, ego_d, oth_d, LATERAL_FIELDS),
        pick(ego_left, ego.speed_lat_max_mps, oth.speed_lat_max_mps),
        pick_fields(ego_left, oth_d, ego_d, LATERAL_FIELDS),
        pick(ego_left, oth.speed_lat_min_mps, ego.speed_lat_min_mps),
    )
    gap_safe = gt(rel.lat_distance_m, safe_dist, _P)
    overlap = ~(ego_left | ego_right)
    # distances of an overlap are 0, of a side not evaluated "max"
    unevaluated = np.where(overlap, 0.0, DISTANCE_MAX_M)
    evaluator = np.where(overlap, _LAT_EVAL, 0)

    def side(evaluated: BoolArray, overlap_code: int) -> LateralSide:
        # evaluated and overlap exclude each other
        is_safe = lat_position == overlap_code  # an overlap is safe on its own side
        is_safe |= ~overlap
        np.copyto(is_safe, gap_safe, where=evaluated)
        side_evaluator = evaluator.copy()
        side_evaluator[evaluated] = _LAT_EVAL
        current = unevaluated.copy()
        np.copyto(current, rel.lat_distance_m, where=evaluated)
        safe = unevaluated.copy()
        np.copyto(safe, safe_dist, where=evaluated)
        return LateralSide(
            is_safe=is_safe,
            response=np.where(is_safe, 0, _LAT_BRAKE_MIN).astype(np.int64, copy=False),
            evaluator=side_evaluator.astype(np.int64, copy=False),
            current_distance_m=current,
            safe_distance_m=safe,
        )

    left = side(ego_right, int(LateralPosition.OverlapLeft))
    right = side(ego_left, int(LateralPosition.OverlapRight))
    return left, right


def _fixed(
    side: LateralSide, rows: BoolArray, *, safe: bool, distance_m: float, evaluator: int
) -> None:
    """Set ``rows`` of ``side`` in place: no response, the given verdict, distance, evaluator."""
    if safe:
        side.is_safe[rows] = True
    else:
        side.is_safe[rows] = False
    side.response[rows] = 0
    side.evaluator[rows] = evaluator
    side.current_distance_m[rows] = distance_m
    side.safe_distance_m[rows] = distance_m


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
    lon_current = rel.lon_distance_m.copy()
    state = np.zeros(batch.size, dtype=np.int64)
    # the arrays above are this call's own: intersection and NotRelevant rows are
    # overwritten in place (the two kinds exclude each other)
    intersection = ctype >= ConstellationType.IntersectionEgoHasPriority
    if intersection.any():
        i_safe, i_eval, i_current, i_safe_dist, i_state = intersection_checks(
            batch, rel, intersection
        )
        np.copyto(lon_safe, i_safe, where=intersection)
        np.copyto(lon_eval, i_eval, where=intersection)
        lon_resp[intersection] = _BRAKE_MIN
        np.copyto(lon_current, i_current, where=intersection)
        np.copyto(lon_safe_dist, i_safe_dist, where=intersection)
        np.copyto(state, i_state, where=intersection & i_safe)
        for side in (left, right):
            _fixed(side, intersection, safe=False, distance_m=0.0, evaluator=_LAT_EVAL)
    irrelevant = ctype == ConstellationType.NotRelevant
    if irrelevant.any():
        lon_safe |= irrelevant
        lon_eval[irrelevant] = 0
        lon_current[irrelevant] = DISTANCE_MAX_M
        lon_safe_dist[irrelevant] = DISTANCE_MAX_M
        for side in (left, right):
            _fixed(side, irrelevant, safe=True, distance_m=DISTANCE_MAX_M, evaluator=0)
    lon_resp[lon_safe] = 0
    return RawStates(
        lon_is_safe=lon_safe,
        lon_response=lon_resp,
        lon_evaluator=lon_eval,
        lon_current_distance_m=lon_current,
        lon_safe_distance_m=lon_safe_dist,
        left=left,
        right=right,
        intersection_state=state,
    )
