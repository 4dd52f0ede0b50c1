"""Structure-of-arrays form of all constellations of one frame (the engine's input).

Road areas and occupied regions are ragged; they are padded to the largest size in the
frame: ``C`` constellations, ``R`` road segments, ``L`` lanes per segment, ``K`` occupied
regions per object. Absent lanes / regions have id ``-1``.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from typing import TYPE_CHECKING, TypeVar

import numpy as np
import numpy.typing as npt

from rss.dynamics import DYNAMICS_KEYS, RssDynamics
from rss.errors import RssConstellationError
from rss.model import ConstellationType, LaneDrivingDirection, ObjectType, RoadSegmentType

if TYPE_CHECKING:
    from collections.abc import Sequence

    from rss.model import Constellation, LaneObject, RoadSegment

__all__ = [
    "BoolArray",
    "ConstellationBatch",
    "DynamicsArrays",
    "FloatArray",
    "IntArray",
    "ObjectArrays",
    "RoadAreaArrays",
    "stack_constellations",
    "stack_dynamics",
    "take_rows",
]

_T = TypeVar("_T")

BoolArray = npt.NDArray[np.bool_]
FloatArray = npt.NDArray[np.float64]
IntArray = npt.NDArray[np.int64]


def _ints(array: npt.ArrayLike) -> IntArray:
    out: IntArray = np.array(array, dtype=np.int64)
    out.flags.writeable = False
    return out


def _floats(array: npt.ArrayLike) -> FloatArray:
    out: FloatArray = np.array(array, dtype=np.float64)
    out.flags.writeable = False
    return out


@dataclass(frozen=True)
class DynamicsArrays:
    """RSS dynamics of ``C`` participants.

    Every field is ``(C,)`` float64, named and in units as in :class:`rss.dynamics.RssDynamics`.
    """

    accel_max_mps2: FloatArray
    brake_max_mps2: FloatArray
    brake_min_mps2: FloatArray
    brake_min_correct_mps2: FloatArray
    lat_accel_max_mps2: FloatArray
    lat_brake_min_mps2: FloatArray
    lateral_fluctuation_margin_m: FloatArray
    response_time_s: FloatArray
    max_speed_on_acceleration_mps: FloatArray
    min_longitudinal_safety_distance_m: FloatArray


def stack_dynamics(dynamics: Sequence[RssDynamics]) -> DynamicsArrays:
    """Stack validated dynamics into ``(C,)`` arrays."""
    return DynamicsArrays(
        **{name: _floats([getattr(d, name) for d in dynamics]) for name in DYNAMICS_KEYS.values()}
    )


@dataclass(frozen=True)
class RoadAreaArrays:
    """Padded road areas of ``C`` constellations.

    Attributes:
        lane_id: ``(C, R, L)`` int64 lane ids, -1 = no lane.
        driving_direction: ``(C, R, L)`` :class:`LaneDrivingDirection` codes.
        length_min_m: ``(C, R, L)``.
        length_max_m: ``(C, R, L)``.
        width_min_m: ``(C, R, L)``.
        width_max_m: ``(C, R, L)``.
        segment_type: ``(C, R)`` :class:`RoadSegmentType` codes, -1 = no segment.
        before_intersection_m: ``(C, R)`` minimum_length_before_intersecting_area.
        after_intersection_m: ``(C, R)`` minimum_length_after_intersecting_area.
    """

    lane_id: IntArray
    driving_direction: IntArray
    length_min_m: FloatArray
    length_max_m: FloatArray
    width_min_m: FloatArray
    width_max_m: FloatArray
    segment_type: IntArray
    before_intersection_m: FloatArray
    after_intersection_m: FloatArray


@dataclass(frozen=True)
class ObjectArrays:
    """One object per constellation.

    Attributes:
        object_id: ``(C,)`` int64.
        object_type: ``(C,)`` :class:`ObjectType` codes.
        region_lane_id: ``(C, K)`` lane id of each occupied region, -1 = none.
        region_lon_min: ``(C, K)`` parametric [0, 1].
        region_lon_max: ``(C, K)``.
        region_lat_min: ``(C, K)``.
        region_lat_max: ``(C, K)``.
        speed_lon_min_mps: ``(C,)``.
        speed_lon_max_mps: ``(C,)``.
        speed_lat_min_mps: ``(C,)`` lateral positive = to the right.
        speed_lat_max_mps: ``(C,)``.
    """

    object_id: IntArray
    object_type: IntArray
    region_lane_id: IntArray
    region_lon_min: FloatArray
    region_lon_max: FloatArray
    region_lat_min: FloatArray
    region_lat_max: FloatArray
    speed_lon_min_mps: FloatArray
    speed_lon_max_mps: FloatArray
    speed_lat_min_mps: FloatArray
    speed_lat_max_mps: FloatArray


@dataclass(frozen=True)
class ConstellationBatch:
    """All constellations of one frame.

    Attributes:
        constellation_type: ``(C,)`` :class:`ConstellationType` codes.
        ego: The ego of each constellation (in ``ego_road``).
        other: The other object (``ego_road`` or ``intersecting_road``).
        ego_dynamics: ``(C,)`` ego dynamics per constellation.
        other_dynamics: ``(C,)`` other dynamics.
        ego_road: Road area along the ego's driving direction.
        intersecting_road: The other's road area (intersection types; may be empty).
    """

    constellation_type: IntArray
    ego: ObjectArrays
    other: ObjectArrays
    ego_dynamics: DynamicsArrays
    other_dynamics: DynamicsArrays
    ego_road: RoadAreaArrays
    intersecting_road: RoadAreaArrays

    @property
    def size(self) -> int:
        """Number of constellations ``C``."""
        return int(self.constellation_type.shape[0])


def stack_constellations(constellations: Sequence[Constellation]) -> ConstellationBatch:
    """Pad and stack scalar constellations into a :class:`ConstellationBatch`.

    Structural errors raise; value errors of single objects (NaN, negative speed, a region
    outside the road area) do not: the engine flags those constellations invalid.

    Raises:
        RssConstellationError: Unknown constellation type / direction / segment type,
            negative or inverted lane lengths or widths, duplicate lane ids.
    """
    for c in constellations:
        _check_structure(c)
    return ConstellationBatch(
        constellation_type=_ints([int(c.constellation_type) for c in constellations]),
        ego=_stack_objects([c.ego for c in constellations]),
        other=_stack_objects([c.other for c in constellations]),
        ego_dynamics=stack_dynamics([c.ego_dynamics for c in constellations]),
        other_dynamics=stack_dynamics([c.other_dynamics for c in constellations]),
        ego_road=_stack_roads([c.ego_road for c in constellations]),
        intersecting_road=_stack_roads([c.intersecting_road for c in constellations]),
    )


def _check_structure(c: Constellation) -> None:
    try:
        ConstellationType(c.constellation_type)
    except ValueError as err:
        raise RssConstellationError("constellation_type", c.constellation_type, "unknown") from err
    if c.constellation_type == ConstellationType.Unstructured:
        raise RssConstellationError(
            "constellation_type", "Unstructured", "not a structured constellation (issue 6)"
        )
    for obj in (c.ego, c.other):
        try:
            ObjectType(obj.object_type)
        except ValueError as err:
            raise RssConstellationError("object_type", obj.object_type, "unknown") from err
    for road in (c.ego_road, c.intersecting_road):
        _check_road(road)


def _check_road(road: tuple[RoadSegment, ...]) -> None:
    seen: set[int] = set()
    for segment in road:
        try:
            RoadSegmentType(segment.segment_type)
        except ValueError as err:
            raise RssConstellationError("segment_type", segment.segment_type, "unknown") from err
        if not segment.lanes:
            raise RssConstellationError("road segment", segment, "has no lanes")
        for lane in segment.lanes:
            _check_lane(lane.lane_id, "length", lane.length_min_m, lane.length_max_m)
            _check_lane(lane.lane_id, "width", lane.width_min_m, lane.width_max_m)
            try:
                LaneDrivingDirection(lane.driving_direction)
            except ValueError as err:
                raise RssConstellationError(
                    f"lane {lane.lane_id} driving_direction", lane.driving_direction, "unknown"
                ) from err
            if lane.lane_id in seen or lane.lane_id < 0:
                raise RssConstellationError("lane id", lane.lane_id, "duplicate or negative")
            seen.add(lane.lane_id)


def _check_lane(lane_id: int, what: str, low: float, high: float) -> None:
    if not (low >= 0.0 and high >= low and np.isfinite(high)):
        raise RssConstellationError(
            f"lane {lane_id} {what}", (low, high), "needs finite 0 <= min <= max [m]"
        )


def _stack_objects(objects: Sequence[LaneObject]) -> ObjectArrays:
    count = len(objects)
    k = max((len(o.regions) for o in objects), default=0)
    lane = np.full((count, max(k, 1)), -1, dtype=np.int64)
    params = np.zeros((4, count, max(k, 1)))
    for i, obj in enumerate(objects):
        for j, region in enumerate(obj.regions):
            lane[i, j] = region.lane_id
            params[:, i, j] = (region.lon_min, region.lon_max, region.lat_min, region.lat_max)
    speeds = np.array([dataclasses.astuple(o.speed) for o in objects], dtype=np.float64)
    speeds = speeds.reshape(count, 4)
    return ObjectArrays(
        object_id=_ints([o.object_id for o in objects]),
        object_type=_ints([int(o.object_type) for o in objects]),
        region_lane_id=_ints(lane),
        region_lon_min=_floats(params[0]),
        region_lon_max=_floats(params[1]),
        region_lat_min=_floats(params[2]),
        region_lat_max=_floats(params[3]),
        speed_lon_min_mps=_floats(speeds[:, 0]),
        speed_lon_max_mps=_floats(speeds[:, 1]),
        speed_lat_min_mps=_floats(speeds[:, 2]),
        speed_lat_max_mps=_floats(speeds[:, 3]),
    )


def _stack_roads(roads: Sequence[tuple[RoadSegment, ...]]) -> RoadAreaArrays:
    count = len(roads)
    r = max(1, max((len(road) for road in roads), default=0))
    n_lanes = max(1, max((len(s.lanes) for road in roads for s in road), default=0))
    lane_id = np.full((count, r, n_lanes), -1, dtype=np.int64)
    direction = np.zeros((count, r, n_lanes), dtype=np.int64)
    metric = np.zeros((4, count, r, n_lanes))
    segment_type = np.full((count, r), -1, dtype=np.int64)
    lengths = np.zeros((2, count, r))
    for i, road in enumerate(roads):
        for j, segment in enumerate(road):
            segment_type[i, j] = int(segment.segment_type)
            lengths[:, i, j] = (
                segment.min_length_before_intersecting_area_m,
                segment.min_length_after_intersecting_area_m,
            )
            for m, lane in enumerate(segment.lanes):
                lane_id[i, j, m] = lane.lane_id
                direction[i, j, m] = int(lane.driving_direction)
                metric[:, i, j, m] = (
                    lane.length_min_m,
                    lane.length_max_m,
                    lane.width_min_m,
                    lane.width_max_m,
                )
    return RoadAreaArrays(
        lane_id=_ints(lane_id),
        driving_direction=_ints(direction),
        length_min_m=_floats(metric[0]),
        length_max_m=_floats(metric[1]),
        width_min_m=_floats(metric[2]),
        width_max_m=_floats(metric[3]),
        segment_type=_ints(segment_type),
        before_intersection_m=_floats(lengths[0]),
        after_intersection_m=_floats(lengths[1]),
    )


def take_rows(records: _T, rows: IntArray) -> _T:
    """Select constellations ``rows`` from a dataclass of ``(C, ...)`` arrays (recursively)."""
    values = {}
    for f in dataclasses.fields(records):  # type: ignore[arg-type]
        value = getattr(records, f.name)
        values[f.name] = value[rows] if isinstance(value, np.ndarray) else take_rows(value, rows)
    return dataclasses.replace(records, **values)  # type: ignore[type-var]
