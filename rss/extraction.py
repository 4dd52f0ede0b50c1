"""Situation extraction: metric extents and relative positions of all pairs, vectorised.

Implements ad-rss ``RssSituationExtraction`` for structured constellations: every object's
occupied regions are turned into metric longitudinal / lateral extents in the
constellation's lane frame (vehicles are "stretched" by every length uncertainty before
them), then the ego is positioned relative to the other. All comparisons are ad-physics
tolerant (1 mm).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from rss.batch import BoolArray, FloatArray, IntArray, take_rows
from rss.model import ConstellationType, LaneDrivingDirection, ObjectType, RoadSegmentType
from rss.physics import DISTANCE_PRECISION, gt, lt
from rss.states import InvalidReason, LateralPosition, LongitudinalPosition

if TYPE_CHECKING:
    from rss.batch import ConstellationBatch, ObjectArrays, RoadAreaArrays

__all__ = [
    "Extents",
    "LaneTable",
    "Relative",
    "extract",
    "lane_table",
    "object_extents",
    "place",
    "relative_position",
]

_P = DISTANCE_PRECISION
#: Rounding slack of parametric region bounds.
_PARAM_EPS = 1e-9
#: ad-rss input range of lane-frame speeds [m/s].
_SPEED_LIMIT_MPS = 100.0


@dataclass(frozen=True)
class Extents:
    """Metric footprint of ``C`` objects in their road areas (lane frame, m).

    Attributes:
        lon_min_m: ``(C,)`` rear end along the road area.
        lon_max_m: ``(C,)`` front end.
        lat_min_m: ``(C,)`` left edge (lateral grows to the right).
        lat_max_m: ``(C,)`` right edge.
        on_positive_lane: ``(C,)`` touches a lane with direction Positive.
        on_negative_lane: ``(C,)`` touches a lane with direction Negative.
        found: ``(C,)`` at least one occupied region lies in the road area.
        intersection_min_m: ``(C,)`` entry of the intersecting area (NaN if none).
        intersection_max_m: ``(C,)`` exit of the intersecting area (NaN if none).
    """

    lon_min_m: FloatArray
    lon_max_m: FloatArray
    lat_min_m: FloatArray
    lat_max_m: FloatArray
    on_positive_lane: BoolArray
    on_negative_lane: BoolArray
    found: BoolArray
    intersection_min_m: FloatArray
    intersection_max_m: FloatArray


@dataclass(frozen=True)
class Relative:
    """Relative situation of every constellation (ad-rss ``RelativeConstellation``).

    Attributes:
        lon_position: ``(C,)`` :class:`LongitudinalPosition` of the ego w.r.t. the other.
        lon_distance_m: ``(C,)`` gap, 0 when overlapping.
        lat_position: ``(C,)`` :class:`LateralPosition`.
        lat_distance_m: ``(C,)``.
        ego_in_correct_lane: ``(C,)``.
        other_in_correct_lane: ``(C,)``.
        ego_dist_to_enter_m: ``(C,)`` intersection types: front bumper to entry (else 0).
        ego_dist_to_leave_m: ``(C,)`` rear bumper to exit.
        other_dist_to_enter_m: ``(C,)``.
        other_dist_to_leave_m: ``(C,)``.
        invalid: ``(C,)`` :class:`InvalidReason` codes (0 = valid).
    """

    lon_position: IntArray
    lon_distance_m: FloatArray
    lat_position: IntArray
    lat_distance_m: FloatArray
    ego_in_correct_lane: BoolArray
    other_in_correct_lane: BoolArray
    ego_dist_to_enter_m: FloatArray
    ego_dist_to_leave_m: FloatArray
    other_dist_to_enter_m: FloatArray
    other_dist_to_leave_m: FloatArray
    invalid: IntArray


def _exclusive_cumsum(values: FloatArray, axis: int) -> FloatArray:
    if values.shape[axis] == 1:
        return np.zeros_like(values)
    total = np.cumsum(values, axis=axis)
    return np.asarray(total - values, dtype=np.float64)


@dataclass(frozen=True)
class LaneTable:
    """Per-lane metric quantities of ``C`` road areas, lanes flattened to ``(C, R*L)``.

    Attributes:
        lane_id: Lane ids (-1 = none).
        direction: :class:`LaneDrivingDirection` codes.
        lon0_min_m: Start of the lane's segment along the road area (min lengths before it).
        lon0_max_m: Same with max lengths.
        length_min_m: Lane length (min).
        length_max_m: Lane length (max).
        lat0_min_m: Start of the lane's column from the left border (min widths left of it).
        lat0_max_m: Same with max widths.
        width_min_m: Lane width (min).
        width_max_m: Lane width (max).
        intersection_min_m: ``(C,)`` entry of the intersecting area (NaN if none).
        intersection_max_m: ``(C,)`` exit of the intersecting area (NaN if none).
    """

    lane_id: IntArray
    direction: IntArray
    lon0_min_m: FloatArray
    lon0_max_m: FloatArray
    length_min_m: FloatArray
    length_max_m: FloatArray
    lat0_min_m: FloatArray
    lat0_max_m: FloatArray
    width_min_m: FloatArray
    width_max_m: FloatArray
    intersection_min_m: FloatArray
    intersection_max_m: FloatArray


def lane_table(road: RoadAreaArrays) -> LaneTable:
    """Lane table of ``C`` road areas.

    Segment starts are sums of min / max segment lengths, lane-column starts sums of the
    min / max column widths over all segments.
    """
    lane_ok = road.lane_id >= 0  # (C, R, L)
    inf = np.inf
    c, r, n_lanes = road.lane_id.shape
    if lane_ok.all():  # no padding: plain reductions
        seg_len_min, seg_len_max = road.length_min_m.min(axis=2), road.length_max_m.max(axis=2)
        col_w_min, col_w_max = road.width_min_m.min(axis=1), road.width_max_m.max(axis=1)
    else:
        seg_ok = lane_ok.any(axis=2)
        seg_len_min = np.where(seg_ok, np.where(lane_ok, road.length_min_m, inf).min(axis=2), 0.0)
        seg_len_max = np.where(seg_ok, np.where(lane_ok, road.length_max_m, -inf).max(axis=2), 0.0)
        col_ok = lane_ok.any(axis=1)  # (C, L)
        col_w_min = np.where(col_ok, np.where(lane_ok, road.width_min_m, inf).min(axis=1), 0.0)
        col_w_max = np.where(col_ok, np.where(lane_ok, road.width_max_m, -inf).max(axis=1), 0.0)
    start_min = _exclusive_cumsum(seg_len_min, axis=1)  # (C, R)
    start_max = _exclusive_cumsum(seg_len_max, axis=1)
    lat_start_min = _exclusive_cumsum(col_w_min, axis=1)  # (C, L)
    lat_start_max = _exclusive_cumsum(col_w_max, axis=1)

    is_intersection = road.segment_type == RoadSegmentType.Intersection  # (C, R)
    has_intersection = is_intersection.any(axis=1)
    first = is_intersection.argmax(axis=1)
    rows = np.arange(c)
    i_min = start_min[rows, first] + road.before_intersection_m[rows, first]
    i_max = (
        start_max[rows, first] + seg_len_max[rows, first] - road.after_intersection_m[rows, first]
    )

    def flat(values: np.ndarray) -> np.ndarray:
        return np.broadcast_to(values, (c, r, n_lanes)).reshape(c, r * n_lanes)

    return LaneTable(
        lane_id=road.lane_id.reshape(c, r * n_lanes),
        direction=road.driving_direction.reshape(c, r * n_lanes),
        lon0_min_m=flat(start_min[:, :, None]),
        lon0_max_m=flat(start_max[:, :, None]),
        length_min_m=road.length_min_m.reshape(c, r * n_lanes),
        length_max_m=road.length_max_m.reshape(c, r * n_lanes),
        lat0_min_m=flat(lat_start_min[:, None, :]),
        lat0_max_m=flat(lat_start_max[:, None, :]),
        width_min_m=road.width_min_m.reshape(c, r * n_lanes),
        width_max_m=road.width_max_m.reshape(c, r * n_lanes),
        intersection_min_m=np.where(has_intersection, i_min, np.nan),
        intersection_max_m=np.where(has_intersection, i_max, np.nan),
    )


def place(obj: ObjectArrays, table: LaneTable) -> Extents:
    """Metric extents of one object per constellation in a road area (its lane table).

    Args:
        obj: Objects with ``(C, K)`` occupied regions.
        table: Lane table of their road areas.

    Returns:
        The extents; ``found`` is False where no region lies in the road area. Regions
        whose lane is not in the road area are ignored (as ad-rss does).
    """
    inf = np.inf
    region = obj.region_lane_id[:, :, None]  # (C, K, 1)
    match = (table.lane_id[:, None, :] == region) & (region >= 0)  # (C, K, RL)
    hit = match.any(axis=2)  # (C, K)
    idx = match.argmax(axis=2)  # (C, K)
    if hit.shape[1] == 1:  # one region per object: no reduction over regions needed
        return _place_single(obj, table, hit[:, 0], idx)

    def at(values: np.ndarray) -> np.ndarray:
        return np.take_along_axis(values, idx, axis=1)

    lon_min = at(table.lon0_min_m) + obj.region_lon_min * at(table.length_min_m)
    lon_max = at(table.lon0_max_m) + obj.region_lon_max * at(table.length_max_m)
    lat_min = at(table.lat0_min_m) + obj.region_lat_min * at(table.width_min_m)
    lat_max = at(table.lat0_max_m) + obj.region_lat_max * at(table.width_max_m)
    direction = at(table.direction)
    return Extents(
        lon_min_m=np.where(hit, lon_min, inf).min(axis=1),
        lon_max_m=np.where(hit, lon_max, -inf).max(axis=1),
        lat_min_m=np.where(hit, lat_min, inf).min(axis=1),
        lat_max_m=np.where(hit, lat_max, -inf).max(axis=1),
        on_positive_lane=(hit & (direction == LaneDrivingDirection.Positive)).any(axis=1),
        on_negative_lane=(hit & (direction == LaneDrivingDirection.Negative)).any(axis=1),
        found=hit.any(axis=1),
        intersection_min_m=table.intersection_min_m,
        intersection_max_m=table.intersection_max_m,
    )


def _place_single(obj: ObjectArrays, table: LaneTable, hit: BoolArray, idx: IntArray) -> Extents:
    rows = np.arange(hit.shape[0])
    lane = idx[:, 0]
    direction = table.direction[rows, lane]
    nan = np.where(hit, 0.0, np.nan)
    return Extents(
        lon_min_m=table.lon0_min_m[rows, lane]
        + obj.region_lon_min[:, 0] * table.length_min_m[rows, lane]
        + nan,
        lon_max_m=table.lon0_max_m[rows, lane]
        + obj.region_lon_max[:, 0] * table.length_max_m[rows, lane]
        + nan,
        lat_min_m=table.lat0_min_m[rows, lane]
        + obj.region_lat_min[:, 0] * table.width_min_m[rows, lane]
        + nan,
        lat_max_m=table.lat0_max_m[rows, lane]
        + obj.region_lat_max[:, 0] * table.width_max_m[rows, lane]
        + nan,
        on_positive_lane=hit & (direction == LaneDrivingDirection.Positive),
        on_negative_lane=hit & (direction == LaneDrivingDirection.Negative),
        found=hit,
        intersection_min_m=table.intersection_min_m,
        intersection_max_m=table.intersection_max_m,
    )


def object_extents(obj: ObjectArrays, road: RoadAreaArrays) -> Extents:
    """Metric extents of one object per constellation in a road area (``(C,)`` each)."""
    return place(obj, lane_table(road))


def relative_position(
    ego_min: FloatArray, ego_max: FloatArray, other_min: FloatArray, other_max: FloatArray
) -> tuple[IntArray, FloatArray]:
    """Position of the ego interval relative to the other one.

    Codes of :class:`LongitudinalPosition`; lateral uses the same codes (InFront <-> AtRight).

    Args:
        ego_min: ``(C,)`` ego interval start (larger = further ahead / right).
        ego_max: ``(C,)`` ego interval end.
        other_min: ``(C,)``.
        other_max: ``(C,)``.

    Returns:
        ``(position, distance)``; distance 0 for overlaps.
    """
    ahead = gt(ego_min, other_max, _P)
    behind = ~ahead & gt(other_min, ego_max, _P)
    overlap_front = gt(ego_min, other_min, _P) & gt(ego_max, other_max, _P)
    overlap_back = lt(ego_min, other_min, _P) & lt(ego_max, other_max, _P)
    position = np.select(
        [ahead, behind, overlap_front, overlap_back],
        [
            LongitudinalPosition.InFront,
            LongitudinalPosition.AtBack,
            LongitudinalPosition.OverlapFront,
            LongitudinalPosition.OverlapBack,
        ],
        LongitudinalPosition.Overlap,
    ).astype(np.int64)
    distance = np.select([ahead, behind], [ego_min - other_max, other_min - ego_max], 0.0)
    return position, distance


_LAT_FROM_LON = np.array(
    [
        LateralPosition.AtRight,  # InFront: ego.min > other.max
        LateralPosition.OverlapRight,
        LateralPosition.Overlap,
        LateralPosition.OverlapLeft,
        LateralPosition.AtLeft,
    ],
    dtype=np.int64,
)


def _distances_to_intersection(ext: Extents) -> tuple[FloatArray, FloatArray]:
    enter = np.where(
        gt(ext.intersection_min_m, ext.lon_max_m, _P), ext.intersection_min_m - ext.lon_max_m, 0.0
    )
    leave = np.where(
        gt(ext.intersection_max_m, ext.lon_min_m, _P), ext.intersection_max_m - ext.lon_min_m, 0.0
    )
    return enter, leave


def _invalid_objects(batch: ConstellationBatch) -> IntArray:
    reason = np.zeros(batch.size, dtype=np.int64)
    for obj in (batch.other, batch.ego):
        speeds = np.stack(
            [
                obj.speed_lon_min_mps,
                obj.speed_lon_max_mps,
                obj.speed_lat_min_mps,
                obj.speed_lat_max_mps,
            ]
        )
        used = obj.region_lane_id >= 0
        params = np.stack(
            [obj.region_lon_min, obj.region_lon_max, obj.region_lat_min, obj.region_lat_max]
        )
        params = np.where(used, params, 0.5)
        with np.errstate(invalid="ignore"):
            bad_speed = (
                (obj.speed_lon_min_mps < 0.0)
                | (obj.speed_lon_max_mps < obj.speed_lon_min_mps)
                | (obj.speed_lon_max_mps > _SPEED_LIMIT_MPS)
                | (obj.speed_lat_min_mps < -_SPEED_LIMIT_MPS)
                | (obj.speed_lat_max_mps < obj.speed_lat_min_mps)
                | (obj.speed_lat_max_mps > _SPEED_LIMIT_MPS)
            )
            bad_region = (
                ((params < -_PARAM_EPS) | (params > 1.0 + _PARAM_EPS)).any(axis=0)
                | (params[0] > params[1])
                | (params[2] > params[3])
            ).any(axis=1)
        reason = np.where(bad_region, InvalidReason.RegionOutOfRange, reason)
        reason = np.where(bad_speed, InvalidReason.SpeedOutOfRange, reason)
        finite = np.isfinite(speeds).all(axis=0) & np.isfinite(params).all(axis=(0, 2))
        reason = np.where(~finite, InvalidReason.NonFiniteValue, reason)
    bad_type = (batch.ego.object_type != ObjectType.EgoVehicle) | np.isin(
        batch.other.object_type, [ObjectType.Invalid, ObjectType.EgoVehicle]
    )
    reason = np.where(bad_type & (reason == 0), InvalidReason.InvalidObjectType, reason)
    same = batch.ego.object_id == batch.other.object_id
    return np.where(same & (reason == 0), InvalidReason.SameObjectIds, reason).astype(np.int64)


def _other_extents(
    batch: ConstellationBatch, intersection: BoolArray, ego_table: LaneTable
) -> Extents:
    """The other object in the ego road (non-intersection) or its own road (intersection).

    Each is computed only for the constellations that need it.
    """
    if not intersection.any():
        return place(batch.other, ego_table)
    if intersection.all():
        return object_extents(batch.other, batch.intersecting_road)
    cross_rows, same_rows = np.flatnonzero(intersection), np.flatnonzero(~intersection)
    cross = object_extents(
        take_rows(batch.other, cross_rows), take_rows(batch.intersecting_road, cross_rows)
    )
    same = object_extents(take_rows(batch.other, same_rows), take_rows(batch.ego_road, same_rows))
    fields = {}
    for name in Extents.__dataclass_fields__:
        a = getattr(same, name)
        merged = np.empty(batch.size, dtype=a.dtype)
        merged[same_rows], merged[cross_rows] = a, getattr(cross, name)
        fields[name] = merged
    return Extents(**fields)


def extract(batch: ConstellationBatch) -> Relative:
    """Relative situation of all constellations of a frame.

    Args:
        batch: ``C`` constellations.

    Returns:
        Relative positions, distances and lane flags; invalid constellations are flagged
        (their other fields are meaningless).
    """
    ctype = batch.constellation_type
    intersection = ctype >= ConstellationType.IntersectionEgoHasPriority
    ego_table = lane_table(batch.ego_road)
    ego = place(batch.ego, ego_table)
    other = _other_extents(batch, intersection, ego_table)
    lon_pos, lon_dist = relative_position(
        ego.lon_min_m, ego.lon_max_m, other.lon_min_m, other.lon_max_m
    )
    lat_code, lat_dist = relative_position(
        ego.lat_min_m, ego.lat_max_m, other.lat_min_m, other.lat_max_m
    )
    lat_pos = _LAT_FROM_LON[lat_code]

    ego_enter, ego_leave = _distances_to_intersection(ego)
    other_enter, other_leave = _distances_to_intersection(other)
    # intersection-centric frame: smaller "distance to the entry" = further ahead
    int_pos, int_dist = relative_position(
        -(ego.intersection_min_m - ego.lon_min_m),
        -(ego.intersection_min_m - ego.lon_max_m),
        -(other.intersection_min_m - other.lon_min_m),
        -(other.intersection_min_m - other.lon_max_m),
    )
    lon_pos = np.where(intersection, int_pos, lon_pos)
    lon_dist = np.where(intersection, int_dist, lon_dist)
    lat_pos = np.where(intersection, LateralPosition.Overlap, lat_pos)
    lat_dist = np.where(intersection, 0.0, lat_dist)
    zero = np.zeros(batch.size)

    invalid = _invalid_objects(batch)
    not_found = ~(ego.found & other.found)
    invalid = np.where((invalid == 0) & not_found, InvalidReason.NotInRoadArea, invalid)
    no_area = intersection & ~(
        np.isfinite(ego.intersection_min_m) & np.isfinite(other.intersection_min_m)
    )
    invalid = np.where((invalid == 0) & no_area, InvalidReason.NoIntersection, invalid)
    opposite = ctype == ConstellationType.OppositeDirection
    return Relative(
        lon_position=lon_pos.astype(np.int64),
        lon_distance_m=lon_dist,
        lat_position=lat_pos.astype(np.int64),
        lat_distance_m=lat_dist,
        ego_in_correct_lane=~ego.on_negative_lane,
        other_in_correct_lane=np.where(opposite, ~other.on_positive_lane, ~other.on_negative_lane),
        ego_dist_to_enter_m=np.where(intersection, ego_enter, zero),
        ego_dist_to_leave_m=np.where(intersection, ego_leave, zero),
        other_dist_to_enter_m=np.where(intersection, other_enter, zero),
        other_dist_to_leave_m=np.where(intersection, other_leave, zero),
        invalid=invalid.astype(np.int64),
    )
