"""Object footprints in constellation road areas: occupied regions -> metric extents.

ad-rss ``calculateObjectDimensions``, vectorised over ``C`` constellations: a lane table
per road area gives every lane's metric start (sums of min / max segment lengths before
it, sums of min / max column widths left of it); each occupied region is looked up in it
and scaled, and the object's extent is the union over its regions (vehicles are
"stretched" by every length uncertainty before them).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from rss.model import LaneDrivingDirection, RoadSegmentType
from rss.physics import DISTANCE_PRECISION, gt, lt

if TYPE_CHECKING:
    from rss.batch import BoolArray, FloatArray, IntArray, ObjectArrays, RoadAreaArrays

__all__ = ["Extents", "LaneTable", "lane_table", "object_extents", "place"]


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


def _exclusive_cumsum(values: FloatArray, axis: int) -> FloatArray:
    """Sums of the preceding entries along ``axis`` of a ``(C, n)`` array.

    Accumulated left to right exactly as ad-rss does (``cumsum - values`` would differ in
    the last bit and flip 1 mm tolerance decisions).
    """
    out = np.zeros_like(values)
    if values.shape[axis] > 1:
        out[:, 1:] = np.cumsum(values[:, :-1], axis=axis)
    return out


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
    c, r, n_lanes = road.lane_id.shape
    # ad-rss reduces with the tolerant std::min / std::max: lengths lane by lane within a
    # segment, column widths segment by segment (values within 1 mm keep the first one)
    seg_len_min = _reduce(road.length_min_m, lane_ok, smaller=True)  # (C, R)
    seg_len_max = _reduce(road.length_max_m, lane_ok, smaller=False)
    col_w_min = _reduce(
        road.width_min_m.transpose(0, 2, 1), lane_ok.transpose(0, 2, 1), smaller=True
    )
    col_w_max = _reduce(
        road.width_max_m.transpose(0, 2, 1), lane_ok.transpose(0, 2, 1), smaller=False
    )
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
    lane = obj.region_lane_id[:, :, None]  # (C, K, 1)
    match = (table.lane_id[:, None, :] == lane) & (lane >= 0)  # (C, K, RL)
    hit = match.any(axis=2)  # (C, K)
    idx = match.argmax(axis=2)  # (C, K)
    if hit.shape[1] == 1:  # one region per object: no reduction over regions needed
        return _place_single(obj, table, hit[:, 0], idx)

    # ad-rss walks the road area segment by segment, lane by lane, and merges each region
    # with a tolerant std::min / std::max (a region within 1 mm does not widen the extent)
    order = np.argsort(np.where(hit, idx, np.iinfo(np.int64).max), axis=1, kind="stable")
    idx = np.take_along_axis(idx, order, axis=1)
    hit = np.asarray(np.take_along_axis(hit, order, axis=1), dtype=np.bool_)

    def at(values: np.ndarray) -> np.ndarray:
        return np.take_along_axis(values, idx, axis=1)

    def region(values: np.ndarray) -> np.ndarray:
        return np.take_along_axis(values, order, axis=1)

    lon_min = at(table.lon0_min_m) + region(obj.region_lon_min) * at(table.length_min_m)
    lon_max = at(table.lon0_max_m) + region(obj.region_lon_max) * at(table.length_max_m)
    lat_min = at(table.lat0_min_m) + region(obj.region_lat_min) * at(table.width_min_m)
    lat_max = at(table.lat0_max_m) + region(obj.region_lat_max) * at(table.width_max_m)
    direction = at(table.direction)
    return Extents(
        lon_min_m=_merge(lon_min, hit, smaller=True),
        lon_max_m=_merge(lon_max, hit, smaller=False),
        lat_min_m=_merge(lat_min, hit, smaller=True),
        lat_max_m=_merge(lat_max, hit, smaller=False),
        on_positive_lane=(hit & (direction == LaneDrivingDirection.Positive)).any(axis=1),
        on_negative_lane=(hit & (direction == LaneDrivingDirection.Negative)).any(axis=1),
        found=np.asarray(hit.any(axis=1), dtype=np.bool_),
        intersection_min_m=table.intersection_min_m,
        intersection_max_m=table.intersection_max_m,
    )


def _reduce(values: FloatArray, valid: BoolArray, *, smaller: bool) -> FloatArray:
    """Tolerant running min / max over the last axis: ``(C, A, B)`` -> ``(C, A)``.

    Entries where nothing is valid are 0.
    """
    c, a, b = values.shape
    merged = _merge(values.reshape(c * a, b), valid.reshape(c * a, b), smaller=smaller)
    return np.nan_to_num(merged, nan=0.0).reshape(c, a)


def _merge(values: FloatArray, hit: BoolArray, *, smaller: bool) -> FloatArray:
    """Tolerant running min / max over the ``K`` sorted regions (``(C, K)`` -> ``(C,)``).

    The loop runs over the region slots ``K`` (a handful), each step vectorised over ``C``.
    """
    current = np.full(values.shape[0], np.nan)
    for k in range(values.shape[1]):
        value, first = values[:, k], np.isnan(current)
        better = (
            lt(value, current, DISTANCE_PRECISION)
            if smaller
            else gt(value, current, DISTANCE_PRECISION)
        )
        current = np.where(hit[:, k] & (first | better), value, current)
    return current


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
