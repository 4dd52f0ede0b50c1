"""Enumerations of relative positions, evaluators and responses (ad-rss integer codes)."""

from __future__ import annotations

import enum

__all__ = [
    "InvalidReason",
    "LateralPosition",
    "LateralResponse",
    "LongitudinalPosition",
    "LongitudinalResponse",
    "RssStateEvaluator",
]


class LongitudinalPosition(enum.IntEnum):
    """Position of the EGO relative to the other along the road area."""

    InFront = 0
    OverlapFront = 1
    Overlap = 2
    OverlapBack = 3
    AtBack = 4


class LateralPosition(enum.IntEnum):
    """Position of the EGO relative to the other across the road area."""

    AtLeft = 0
    OverlapLeft = 1
    Overlap = 2
    OverlapRight = 3
    AtRight = 4


class LongitudinalResponse(enum.IntEnum):
    """Longitudinal response, ordered by severity."""

    None_ = 0
    BrakeMinCorrect = 1
    BrakeMin = 2

    def __str__(self) -> str:
        """ad-rss spelling (``None`` for :attr:`None_`)."""
        return self.name.rstrip("_")


class LateralResponse(enum.IntEnum):
    """Lateral response, ordered by severity."""

    None_ = 0
    BrakeMin = 1

    def __str__(self) -> str:
        """ad-rss spelling (``None`` for :attr:`None_`)."""
        return self.name.rstrip("_")


class RssStateEvaluator(enum.IntEnum):
    """Which check produced a state's distances."""

    None_ = 0
    LongitudinalDistanceOppositeDirectionEgoCorrectLane = 1
    LongitudinalDistanceOppositeDirection = 2
    LongitudinalDistanceSameDirectionEgoFront = 3
    LongitudinalDistanceSameDirectionOtherInFront = 4
    LateralDistance = 5
    IntersectionOtherPriorityEgoAbleToStop = 6
    IntersectionEgoPriorityOtherAbleToStop = 7
    IntersectionEgoInFront = 8
    IntersectionOtherInFront = 9
    IntersectionOverlap = 10

    def __str__(self) -> str:
        """ad-rss spelling (``None`` for :attr:`None_`)."""
        return self.name.rstrip("_")


class InvalidReason(enum.IntEnum):
    """Why a constellation was skipped (0 = valid)."""

    Valid = 0
    NonFiniteValue = 1
    SpeedOutOfRange = 2
    RegionOutOfRange = 3
    NotInRoadArea = 4
    SameObjectIds = 5
    InvalidObjectType = 6
    NoIntersection = 7
    Unsupported = 8
