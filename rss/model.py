"""Constellation model in ad-rss's constellation-specific lane coordinate system.

One :class:`Constellation` is one ego/other pair with the road area(s) it is judged in::

    road area = ordered road segments along the EGO driving direction (longitudinal axis)

          lon ──────────────────────────────▶ (ego driving direction)
     lat  ┌──────── segment 0 ────────┬──── segment 1 ────┐
      │   │ lane_segments[0] (LEFTMOST)│                   │
      │   │ lane_segments[1]           │                   │
      ▼   │ lane_segments[2]           │                   │
   (right)└────────────────────────────┴───────────────────┘

Lateral metric coordinates start at the left border and grow to the RIGHT; a lateral
speed is positive when moving to the right. Occupied regions are parametric [0, 1]
ranges inside one lane segment (lon along the road area, lat from the lane's left border
to its right border). Speeds are lane-frame intervals; longitudinal speeds are magnitudes
along each object's own driving direction.
"""

from __future__ import annotations

import enum
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from rss.dynamics import RssDynamics

__all__ = [
    "Constellation",
    "ConstellationType",
    "LaneDrivingDirection",
    "LaneObject",
    "LaneSegment",
    "ObjectType",
    "OccupiedRegion",
    "RoadSegment",
    "RoadSegmentType",
    "SpeedInterval",
]


class ConstellationType(enum.IntEnum):
    """ad-rss ``ConstellationType`` (same integer codes)."""

    NotRelevant = 0
    SameDirection = 1
    OppositeDirection = 2
    IntersectionEgoHasPriority = 3
    IntersectionObjectHasPriority = 4
    IntersectionSamePriority = 5
    Unstructured = 6


class LaneDrivingDirection(enum.IntEnum):
    """Driving direction of a lane segment relative to the road-area direction."""

    Bidirectional = 0
    Positive = 1
    Negative = 2


class RoadSegmentType(enum.IntEnum):
    """Kind of a road segment."""

    Normal = 0
    Intersection = 1


class ObjectType(enum.IntEnum):
    """ad-rss ``ObjectType`` (structured checks do not look at it)."""

    Invalid = 0
    EgoVehicle = 1
    OtherVehicle = 2
    Pedestrian = 3
    ArtificialObject = 4
    ArtificialVehicle = 5
    ArtificialPedestrian = 6
    Bicycle = 7
    OtherObject = 8


@dataclass(frozen=True)
class LaneSegment:
    """One lane of one road segment.

    Attributes:
        lane_id: Id referenced by occupied regions (unique within a road area).
        driving_direction: Direction relative to the road area.
        length_min_m: Minimal length (inner curve), > 0... <= length_max_m.
        length_max_m: Maximal length.
        width_min_m: Minimal width, <= width_max_m.
        width_max_m: Maximal width.
    """

    lane_id: int
    driving_direction: LaneDrivingDirection
    length_min_m: float
    length_max_m: float
    width_min_m: float
    width_max_m: float


@dataclass(frozen=True)
class RoadSegment:
    """Lanes side by side, ``lanes[0]`` leftmost.

    Attributes:
        lanes: Lane segments, left to right.
        segment_type: Normal or Intersection.
        min_length_before_intersecting_area_m: Intersection only: lane length before the
            area where the routes intersect.
        min_length_after_intersecting_area_m: Intersection only: length after that area.
    """

    lanes: tuple[LaneSegment, ...]
    segment_type: RoadSegmentType = RoadSegmentType.Normal
    min_length_before_intersecting_area_m: float = 0.0
    min_length_after_intersecting_area_m: float = 0.0


@dataclass(frozen=True)
class OccupiedRegion:
    """Parametric footprint of an object inside one lane segment.

    Attributes:
        lane_id: The lane segment.
        lon_min: Start along the lane in [0, 1].
        lon_max: End along the lane in [0, 1].
        lat_min: Left edge in [0, 1] (0 = lane's left border).
        lat_max: Right edge in [0, 1].
    """

    lane_id: int
    lon_min: float
    lon_max: float
    lat_min: float
    lat_max: float


@dataclass(frozen=True)
class SpeedInterval:
    """Lane-frame speed intervals [m/s]; lateral positive = moving to the right.

    Attributes:
        lon_min_mps: Min longitudinal speed (>= 0).
        lon_max_mps: Max longitudinal speed.
        lat_min_mps: Min lateral speed.
        lat_max_mps: Max lateral speed.
    """

    lon_min_mps: float = 0.0
    lon_max_mps: float = 100.0
    lat_min_mps: float = -100.0
    lat_max_mps: float = 100.0


@dataclass(frozen=True)
class LaneObject:
    """An object placed in a road area.

    Attributes:
        object_id: Id (the ego's and the other's must differ).
        object_type: ad-rss object type.
        regions: Occupied regions (at least one in the relevant road area).
        speed: Lane-frame speed intervals.
    """

    object_id: int
    object_type: ObjectType
    regions: tuple[OccupiedRegion, ...]
    speed: SpeedInterval = field(default_factory=SpeedInterval)


@dataclass(frozen=True)
class Constellation:
    """One ego/other pair (ad-rss ``Constellation``).

    Attributes:
        constellation_type: How the pair is related.
        ego: The ego, placed in ``ego_road``.
        other: The other object, placed in ``ego_road`` (non-intersection) or in
            ``intersecting_road`` (intersection types).
        ego_dynamics: The ego's dynamics for this pair.
        other_dynamics: The other's dynamics.
        ego_road: Road segments along the ego driving direction.
        intersecting_road: The other's road area (intersection types only).
    """

    constellation_type: ConstellationType
    ego: LaneObject
    other: LaneObject
    ego_dynamics: RssDynamics
    other_dynamics: RssDynamics
    ego_road: tuple[RoadSegment, ...]
    intersecting_road: tuple[RoadSegment, ...] = ()
