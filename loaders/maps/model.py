"""One lane-graph model for every map format (Lanelet2, CommonRoad, OpenDRIVE, racing bounds).

Borders are polylines in the map frame (ENU, metres), ordered along the lane's reference
direction. ``LaneDirection`` says which way traffic flows relative to that order::

      left border   o----o----o----o---->   (reference direction)
      centre line   o----o----o----o
      right border  o----o----o----o
"""

from __future__ import annotations

import enum
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

from loaders.records import freeze

if TYPE_CHECKING:
    from numpy.typing import NDArray

__all__ = [
    "DRIVABLE_LANE_KINDS",
    "Lane",
    "LaneDirection",
    "LaneKind",
    "LaneMap",
    "LineType",
    "RightOfWay",
    "TrafficLight",
]


class LaneDirection(enum.Enum):
    """Driving direction relative to the border point order."""

    POSITIVE = "positive"
    NEGATIVE = "negative"
    BIDIRECTIONAL = "bidirectional"


class LaneKind(enum.Enum):
    """What a lane is for."""

    ROAD = "road"
    INTERSECTION = "intersection"
    CROSSWALK = "crosswalk"
    SIDEWALK = "sidewalk"
    PARKING = "parking"
    TRACK = "track"
    BICYCLE = "bicycle"
    RAIL = "rail"


#: Lanes a vehicle may drive on (RSS scene creation and unstructured checks use these; the
#: reach-set road layout takes the motor-vehicle ones, without BICYCLE).
DRIVABLE_LANE_KINDS = frozenset({LaneKind.ROAD, LaneKind.INTERSECTION, LaneKind.BICYCLE})


class LineType(enum.Enum):
    """Marking of a lane border."""

    UNKNOWN = "unknown"
    SOLID = "solid"
    DASHED = "dashed"
    ROAD_BORDER = "road_border"
    VIRTUAL = "virtual"


@dataclass(frozen=True, slots=True)
class Lane:
    """One lane (lanelet).

    Attributes:
        id: Stable id from the source map.
        left_m: Left border, ``(K, 2)``.
        right_m: Right border, ``(M, 2)``.
        centre_m: Centre line, ``(C, 2)``.
        direction: Driving direction relative to the point order.
        kind: What the lane is for.
        speed_limit_mps: Speed limit; NaN where the map gives none.
        predecessors: Ids of lanes that lead into this one.
        successors: Ids of lanes this one leads into.
        left_neighbour: Adjacent lane on the left, if any.
        right_neighbour: Adjacent lane on the right, if any.
        left_line: Marking of the left border.
        right_line: Marking of the right border.
        left_neighbour_opposite: The left neighbour runs against this lane's reference
            direction (its border order is reversed), e.g. the oncoming lane.
        right_neighbour_opposite: The right neighbour runs against this lane's reference
            direction.
        admap_reversed: ad-map's reader (the reference implementation of RSS scene
            creation) holds this lane's points in the opposite order (OpenDRIVE only;
            its nearest-segment tie rule scans a border in its own point order).
    """

    id: str
    left_m: NDArray[np.float64]
    right_m: NDArray[np.float64]
    centre_m: NDArray[np.float64]
    direction: LaneDirection = LaneDirection.POSITIVE
    kind: LaneKind = LaneKind.ROAD
    speed_limit_mps: float = float("nan")
    predecessors: tuple[str, ...] = ()
    successors: tuple[str, ...] = ()
    left_neighbour: str | None = None
    right_neighbour: str | None = None
    left_line: LineType = LineType.UNKNOWN
    right_line: LineType = LineType.UNKNOWN
    left_neighbour_opposite: bool = False
    right_neighbour_opposite: bool = False
    admap_reversed: bool = False

    def __post_init__(self) -> None:
        """Freeze the border arrays."""
        for name in ("left_m", "right_m", "centre_m"):
            object.__setattr__(self, name, freeze(getattr(self, name), np.float64))

    @property
    def outline_m(self) -> NDArray[np.float64]:
        """The lane's outline ring: left border forward, right border back, ``(L + R, 2)``."""
        return np.vstack([self.left_m, self.right_m[::-1]])

    @property
    def length_m(self) -> float:
        """Length of the centre line."""
        steps = np.diff(self.centre_m, axis=0)
        return float(np.hypot(steps[:, 0], steps[:, 1]).sum())


@dataclass(frozen=True, slots=True)
class RightOfWay:
    """A right-of-way rule: lanes with priority over yielding lanes."""

    id: str
    priority_lanes: tuple[str, ...]
    yield_lanes: tuple[str, ...]


@dataclass(frozen=True, slots=True)
class TrafficLight:
    """A traffic light controlling lanes; its state comes from the log, not the map."""

    id: str
    controlled_lanes: tuple[str, ...]


@dataclass(frozen=True, slots=True)
class LaneMap:
    """A lane graph.

    Attributes:
        lanes: All lanes, keyed by id.
        source: Where the map came from (file path or ``attachment:NAME``).
        format: ``lanelet2``, ``commonroad``, ``opendrive`` or ``track``.
        right_of_way: Right-of-way rules.
        traffic_lights: Traffic lights.
        intersections: Groups of lane ids forming one intersection.
        boundaries_m: Extra polylines (road/track boundaries), each ``(K, 2)``.
        origin_deg: WGS-84 ``(lat, lon)`` of the map frame's origin when the map was
            projected from latitude/longitude (Lanelet2 without ``local_x``/``local_y``);
            GNSS egos are projected about it.
    """

    lanes: dict[str, Lane]
    source: str
    format: str
    right_of_way: tuple[RightOfWay, ...] = ()
    traffic_lights: tuple[TrafficLight, ...] = ()
    intersections: tuple[tuple[str, ...], ...] = ()
    boundaries_m: tuple[NDArray[np.float64], ...] = field(default_factory=tuple)
    origin_deg: tuple[float, float] | None = None

    def __len__(self) -> int:
        """Number of lanes."""
        return len(self.lanes)

    def bounds_m(self) -> tuple[float, float, float, float]:
        """Axis-aligned bounds ``(min_x, min_y, max_x, max_y)`` over all borders."""
        pts = [lane.left_m for lane in self.lanes.values()]
        pts += [lane.right_m for lane in self.lanes.values()]
        pts += list(self.boundaries_m)
        if not pts:
            return (0.0, 0.0, 0.0, 0.0)
        allpts = np.concatenate(pts)
        lo = allpts.min(axis=0)
        hi = allpts.max(axis=0)
        return (float(lo[0]), float(lo[1]), float(hi[0]), float(hi[1]))
