"""Situation extraction: relative positions of all pairs, vectorised.

Implements ad-rss ``RssSituationExtraction`` for structured constellations: with the
metric footprints of :mod:`rss.structured.footprint`, the ego is positioned relative to the other
(longitudinally, laterally, or relative to their intersection entries), lane flags and
distances to the intersection are derived and invalid objects flagged. All comparisons
are ad-physics tolerant (1 mm).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from rss.model import ConstellationType, ObjectType
from rss.physics import DISTANCE_PRECISION, gt
from rss.structured.batch import take_rows
from rss.structured.footprint import (
    Extents,
    LaneTable,
    any_column,
    lane_table,
    object_extents,
    place,
)
from rss.structured.states import InvalidReason, LateralPosition, LongitudinalPosition

if TYPE_CHECKING:
    from rss.arrays import BoolArray, FloatArray, IntArray
    from rss.structured.batch import ConstellationBatch, ObjectArrays

__all__ = ["Relative", "extract", "relative_position"]

_P = DISTANCE_PRECISION
#: Rounding slack of parametric region bounds.
_PARAM_EPS = 1e-9
#: ad-rss input range of lane-frame speeds [m/s].
_SPEED_LIMIT_MPS = 100.0
_IN_FRONT = int(LongitudinalPosition.InFront)
_OVERLAP_FRONT = int(LongitudinalPosition.OverlapFront)
_OVERLAP = int(LongitudinalPosition.Overlap)
_OVERLAP_BACK = int(LongitudinalPosition.OverlapBack)
_AT_BACK = int(LongitudinalPosition.AtBack)


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


def relative_position(
    ego_min: FloatArray, ego_max: FloatArray, other_min: FloatArray, other_max: FloatArray
) -> tuple[IntArray, FloatArray]:
    """Position of the ego interval relative to the other one.

    Codes of :class:`LongitudinalPosition`; lateral uses the same codes (InFront <-> AtRight).

    Args:
        ego_min: ``(...)`` ego interval start (larger = further ahead / right).
        ego_max: ``(...)`` ego interval end.
        other_min: ``(...)``.
        other_max: ``(...)``.

    Returns:
        ``(position, distance)``; distance 0 for overlaps.
    """
    ahead_gap = np.subtract(ego_min, other_max)
    ahead = ahead_gap >= _P  # gt(ego_min, other_max)
    behind_gap = np.subtract(other_min, ego_max)
    behind = behind_gap >= _P
    behind &= ~ahead
    # gt(a, b) is a - b >= p and lt(a, b) is -(a - b) >= p (negation is exact): one
    # difference per bound; overlap front and back exclude each other
    low, high = np.subtract(ego_min, other_min), np.subtract(ego_max, other_max)
    overlap_front = low >= _P
    overlap_front &= high >= _P
    overlap_back = low <= -_P
    overlap_back &= high <= -_P
    position = overlap_back.astype(np.int64)
    position += _OVERLAP
    position -= overlap_front
    np.copyto(position, _IN_FRONT, where=ahead)
    np.copyto(position, _AT_BACK, where=behind)
    distance = np.zeros(position.shape)
    np.copyto(distance, ahead_gap, where=ahead)
    np.copyto(distance, behind_gap, where=behind)
    return position, distance


def _distances_to_intersection(ext: Extents) -> tuple[FloatArray, FloatArray]:
    enter = np.where(
        gt(ext.intersection_min_m, ext.lon_max_m, _P), ext.intersection_min_m - ext.lon_max_m, 0.0
    )
    leave = np.where(
        gt(ext.intersection_max_m, ext.lon_min_m, _P), ext.intersection_max_m - ext.lon_min_m, 0.0
    )
    return enter, leave


def _object_problems(obj: ObjectArrays) -> tuple[BoolArray, BoolArray, BoolArray]:
    """``(bad region, bad speed, not finite)`` per object, ``(C,)`` each."""
    speeds = (
        obj.speed_lon_min_mps,
        obj.speed_lon_max_mps,
        obj.speed_lat_min_mps,
        obj.speed_lat_max_mps,
    )
    used = obj.region_lane_id >= 0
    params = [obj.region_lon_min, obj.region_lon_max, obj.region_lat_min, obj.region_lat_max]
    if not used.all():  # unused region slots count as 0.5 (in range, finite)
        params = [np.where(used, p, 0.5) for p in params]
    with np.errstate(invalid="ignore"):
        bad_speed = obj.speed_lon_min_mps < 0.0
        bad_speed |= obj.speed_lon_max_mps < obj.speed_lon_min_mps
        bad_speed |= obj.speed_lon_max_mps > _SPEED_LIMIT_MPS
        bad_speed |= obj.speed_lat_min_mps < -_SPEED_LIMIT_MPS
        bad_speed |= obj.speed_lat_max_mps < obj.speed_lat_min_mps
        bad_speed |= obj.speed_lat_max_mps > _SPEED_LIMIT_MPS
        bad = params[0] > params[1]
        bad |= params[2] > params[3]
        finite = np.isfinite(params[0])
        for p in params:
            bad |= p < -_PARAM_EPS
            bad |= p > 1.0 + _PARAM_EPS
            finite &= np.isfinite(p)
    not_finite = any_column(~finite)
    for v in speeds:
        not_finite |= ~np.isfinite(v)
    return any_column(bad), bad_speed, not_finite


def _invalid_objects(batch: ConstellationBatch) -> IntArray:
    reason = np.zeros(batch.size, dtype=np.int64)
    # the other object's problems first, the ego's override them; within an object a
    # non-finite value overrides a bad speed, which overrides a bad region
    for obj in (batch.other, batch.ego):
        for flags, code in zip(
            _object_problems(obj),
            (
                InvalidReason.RegionOutOfRange,
                InvalidReason.SpeedOutOfRange,
                InvalidReason.NonFiniteValue,
            ),
            strict=True,
        ):
            if flags.any():
                reason[flags] = code
    other_type = batch.other.object_type
    bad_type = batch.ego.object_type != ObjectType.EgoVehicle
    bad_type |= other_type == ObjectType.Invalid
    bad_type |= other_type == ObjectType.EgoVehicle
    unset = reason == 0
    if bad_type.any():
        bad_type &= unset
        reason[bad_type] = InvalidReason.InvalidObjectType
        unset &= ~bad_type
    same = batch.ego.object_id == batch.other.object_id
    same &= unset
    if same.any():
        reason[same] = InvalidReason.SameObjectIds
    return reason


def _other_extents(
    batch: ConstellationBatch, intersection: BoolArray, ego_table: LaneTable
) -> Extents:
    """The other object in the ego road (non-intersection) or its own road (intersection).

    The intersecting road areas are computed only for the constellations that need them.
    """
    if not intersection.any():
        return place(batch.other, ego_table)
    if intersection.all():
        return object_extents(batch.other, batch.intersecting_road)
    cross_rows = np.flatnonzero(intersection)
    cross = object_extents(
        take_rows(batch.other, cross_rows), take_rows(batch.intersecting_road, cross_rows)
    )
    same = place(batch.other, ego_table)  # row by row, so its cross rows can be replaced
    fields = {}
    for name in Extents.__dataclass_fields__:
        merged = getattr(same, name).copy()
        merged[cross_rows] = getattr(cross, name)
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
    # lateral: the same codes mirrored (ego.min > other.max is AtRight = 4 - InFront, ...)
    lat_code, lat_dist = relative_position(
        ego.lat_min_m, ego.lat_max_m, other.lat_min_m, other.lat_max_m
    )
    lat_pos = _AT_BACK - lat_code
    invalid = _invalid_objects(batch)
    not_found = ~(ego.found & other.found)
    not_found &= invalid == 0
    invalid[not_found] = InvalidReason.NotInRoadArea
    zero = np.zeros(batch.size)
    distances = [np.zeros(batch.size) for _ in range(4)]
    if intersection.any():
        # intersection types: longitudinal relative to the own intersection entry
        i_pos, i_dist = relative_position(
            ego.lon_min_m - ego.intersection_min_m,
            ego.lon_max_m - ego.intersection_min_m,
            other.lon_min_m - other.intersection_min_m,
            other.lon_max_m - other.intersection_min_m,
        )
        np.copyto(lon_pos, i_pos, where=intersection)
        np.copyto(lon_dist, i_dist, where=intersection)
        np.copyto(lat_pos, int(LateralPosition.Overlap), where=intersection)
        np.copyto(lat_dist, 0.0, where=intersection)
        distances = [
            np.where(intersection, d, zero)
            for d in (*_distances_to_intersection(ego), *_distances_to_intersection(other))
        ]
        no_area = intersection & ~(
            np.isfinite(ego.intersection_min_m) & np.isfinite(other.intersection_min_m)
        )
        no_area &= invalid == 0
        invalid[no_area] = InvalidReason.NoIntersection
    opposite = ctype == ConstellationType.OppositeDirection
    other_correct = ~other.on_negative_lane
    if opposite.any():
        other_correct = np.where(opposite, ~other.on_positive_lane, other_correct)
    return Relative(
        lon_position=lon_pos,
        lon_distance_m=lon_dist,
        lat_position=lat_pos,
        lat_distance_m=lat_dist,
        ego_in_correct_lane=~ego.on_negative_lane,
        other_in_correct_lane=other_correct,
        ego_dist_to_enter_m=distances[0],
        ego_dist_to_leave_m=distances[1],
        other_dist_to_enter_m=distances[2],
        other_dist_to_leave_m=distances[3],
        invalid=invalid,
    )
