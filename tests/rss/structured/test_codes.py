"""Every code of :mod:`rss.structured.codes` equals the enum member it stands for."""

from __future__ import annotations

import pytest

from rss.model import ConstellationType, LaneDrivingDirection, ObjectType, RoadSegmentType
from rss.structured import codes
from rss.structured.intersection_checks import IntersectionState
from rss.structured.states import (
    LateralPosition,
    LateralResponse,
    LongitudinalPosition,
    LongitudinalResponse,
    RssStateEvaluator,
)

_E = RssStateEvaluator

#: Each code of ``codes`` and the enum member (or ``IntersectionState`` code) it stands for.
_MEANING: dict[str, int] = {
    "NOT_RELEVANT": ConstellationType.NotRelevant,
    "SAME_DIRECTION": ConstellationType.SameDirection,
    "OPPOSITE_DIRECTION": ConstellationType.OppositeDirection,
    "EGO_PRIORITY": ConstellationType.IntersectionEgoHasPriority,
    "OBJECT_PRIORITY": ConstellationType.IntersectionObjectHasPriority,
    "UNSTRUCTURED": ConstellationType.Unstructured,
    "INVALID_OBJECT": ObjectType.Invalid,
    "EGO_VEHICLE": ObjectType.EgoVehicle,
    "POSITIVE": LaneDrivingDirection.Positive,
    "NEGATIVE": LaneDrivingDirection.Negative,
    "INTERSECTION_SEGMENT": RoadSegmentType.Intersection,
    "IN_FRONT": LongitudinalPosition.InFront,
    "OVERLAP_FRONT": LongitudinalPosition.OverlapFront,
    "OVERLAP": LongitudinalPosition.Overlap,
    "OVERLAP_BACK": LongitudinalPosition.OverlapBack,
    "AT_BACK": LongitudinalPosition.AtBack,
    "AT_LEFT": LateralPosition.AtLeft,
    "OVERLAP_LEFT": LateralPosition.OverlapLeft,
    "OVERLAP_RIGHT": LateralPosition.OverlapRight,
    "AT_RIGHT": LateralPosition.AtRight,
    "BRAKE_MIN_CORRECT": LongitudinalResponse.BrakeMinCorrect,
    "BRAKE_MIN": LongitudinalResponse.BrakeMin,
    "LAT_BRAKE_MIN": LateralResponse.BrakeMin,
    "E_OD_CORRECT": _E.LongitudinalDistanceOppositeDirectionEgoCorrectLane,
    "E_OD": _E.LongitudinalDistanceOppositeDirection,
    "E_SD_EGO_FRONT": _E.LongitudinalDistanceSameDirectionEgoFront,
    "E_SD_OTHER_FRONT": _E.LongitudinalDistanceSameDirectionOtherInFront,
    "E_LAT": _E.LateralDistance,
    "E_I_EGO_STOPS": _E.IntersectionOtherPriorityEgoAbleToStop,
    "E_I_OTHER_STOPS": _E.IntersectionEgoPriorityOtherAbleToStop,
    "E_I_EGO_FRONT": _E.IntersectionEgoInFront,
    "E_I_OTHER_FRONT": _E.IntersectionOtherInFront,
    "E_I_OVERLAP": _E.IntersectionOverlap,
    "I_NONE": IntersectionState.NONE,
    "I_ABLE_TO_BRAKE": IntersectionState.NON_PRIO_ABLE_TO_BREAK,
    "I_SAFE_DISTANCE": IntersectionState.SAFE_LONGITUDINAL_DISTANCE,
    "I_NO_TIME_OVERLAP": IntersectionState.NO_TIME_OVERLAP,
}


@pytest.mark.parametrize("name", sorted(_MEANING))
def test_code_equals_its_enum_member(name: str) -> None:
    value = getattr(codes, name)
    assert type(value) is int
    assert value == int(_MEANING[name])


def test_every_code_has_its_meaning_here() -> None:
    names = {name for name in vars(codes) if name.isupper()}
    assert names == set(_MEANING)


def test_lateral_overlap_is_the_longitudinal_code() -> None:
    assert int(LateralPosition.Overlap) == codes.OVERLAP
