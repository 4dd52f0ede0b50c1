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
from rss.physics import DISTANCE_PRECISION

if TYPE_CHECKING:
    from rss.arrays import BoolArray, FloatArray, IntArray
    from rss.structured.batch import ObjectArrays, RoadAreaArrays

__all__ = ["Extents", "LaneTable", "any_column", "lane_table", "object_extents", "place"]


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


#: Per bound column ``lon_min, lon_max, lat_min, lat_max``: -1 = tolerant running min,
#: +1 = max (``sign * (value - current) >= p`` is exactly ``lt`` / ``gt``: negating a
#: rounded difference is exact).
_BOUND_SIGN = np.array([[-1.0], [1.0], [-1.0], [1.0]])


def _exclusive_cumsum(values: FloatArray) -> FloatArray:
    """Sums of the preceding entries along the (short) last axis.

    Accumulated left to right exactly as ad-rss does (``cumsum - values`` would differ in
    the last bit and flip 1 mm tolerance decisions); the same additions as ``np.cumsum``,
    one vectorised step per entry (numpy accumulates a short last axis row by row).
    """
    out = np.zeros_like(values)
    if values.shape[-1] > 1:
        out[..., 1] = values[..., 0]
    for j in range(2, values.shape[-1]):
        out[..., j] = out[..., j - 1] + values[..., j - 1]
    return out


@dataclass(frozen=True)
class LaneTable:
    """Per-lane metric quantities of ``C`` road areas, lanes flattened to ``W = R*L``.

    Attributes:
        lane_id: ``(W, C)`` lane ids (-1 = none), lane-major (each lane slot a
            contiguous row over the road areas).
        direction: ``(C, W)`` :class:`LaneDrivingDirection` codes.
        segment_start_m: ``(2, C, R)`` start of each segment along the road area: sums
            of the min / max segment lengths before it.
        column_start_m: ``(2, C, L)`` start of each lane column from the left border:
            sums of the min / max column widths left of it.
        scale_m: Lane length min / max and width min / max, ``(C * W,)`` each (flat views
            of the road area's arrays), in the order of the extents ``lon_min, lon_max,
            lat_min, lat_max``.
        intersection_min_m: ``(C,)`` entry of the intersecting area (NaN if none).
        intersection_max_m: ``(C,)`` exit of the intersecting area (NaN if none).
    """

    lane_id: IntArray
    direction: IntArray
    segment_start_m: FloatArray
    column_start_m: FloatArray
    scale_m: tuple[FloatArray, FloatArray, FloatArray, FloatArray]
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
    seg_len = _reduce(np.stack([road.length_min_m, road.length_max_m]), lane_ok)  # (2, C, R)
    col_w = _reduce(
        np.stack([road.width_min_m, road.width_max_m]).transpose(0, 1, 3, 2),
        lane_ok.transpose(0, 2, 1),
    )  # (2, C, L)
    seg_start = _exclusive_cumsum(seg_len)  # (2, C, R)
    col_start = _exclusive_cumsum(col_w)  # (2, C, L)

    is_intersection = road.segment_type == RoadSegmentType.Intersection  # (C, R)
    if is_intersection.any():
        i_min, i_max = _intersection_area(road, is_intersection, seg_len, seg_start)
    else:  # no intersecting area in any road area
        i_min, i_max = np.full(c, np.nan), np.full(c, np.nan)
    return LaneTable(
        lane_id=np.ascontiguousarray(road.lane_id.reshape(c, r * n_lanes).T),
        direction=road.driving_direction.reshape(c, r * n_lanes),
        segment_start_m=seg_start,
        column_start_m=col_start,
        scale_m=(
            road.length_min_m.ravel(),
            road.length_max_m.ravel(),
            road.width_min_m.ravel(),
            road.width_max_m.ravel(),
        ),
        intersection_min_m=i_min,
        intersection_max_m=i_max,
    )


def _intersection_area(
    road: RoadAreaArrays, is_intersection: BoolArray, seg_len: FloatArray, seg_start: FloatArray
) -> tuple[FloatArray, FloatArray]:
    """Entry and exit of the first Intersection segment of each road area (NaN if none)."""
    c, r = is_intersection.shape
    first = np.zeros(c, dtype=np.int64)  # is_intersection.argmax(axis=1), slot by slot
    for segment in range(r - 1, -1, -1):
        first[is_intersection[:, segment]] = segment
    rows = np.arange(c)
    has_intersection = is_intersection[rows, first]
    start_min, start_max = seg_start[:, rows, first]
    i_min = start_min + road.before_intersection_m[rows, first]
    i_max = start_max + seg_len[1, rows, first] - road.after_intersection_m[rows, first]
    return np.where(has_intersection, i_min, np.nan), np.where(has_intersection, i_max, np.nan)


def place(obj: ObjectArrays, table: LaneTable) -> Extents:
    """Metric extents of one object per constellation in a road area (its lane table).

    Args:
        obj: Objects with ``(C, K)`` occupied regions.
        table: Lane table of their road areas.

    Returns:
        The extents; ``found`` is False where no region lies in the road area. Regions
        whose lane is not in the road area are ignored (as ad-rss does).
    """
    c, k = obj.region_lane_id.shape
    hit, idx = _find_lanes(obj.region_lane_id, table.lane_id)
    width = table.lane_id.shape[0]
    params: tuple[FloatArray, ...] = (
        obj.region_lon_min,
        obj.region_lon_max,
        obj.region_lat_min,
        obj.region_lat_max,
    )
    rows = np.arange(c)[:, None]
    if k > 1:
        # ad-rss walks the road area segment by segment, lane by lane, and merges each
        # region with a tolerant std::min / std::max (a region within 1 mm does not widen
        # the extent)
        # one stable sort of all regions by (row, slot; regions not found last) gives the
        # flat positions of the sorted regions directly
        key = np.where(hit, idx, width) + rows * (width + 1)
        order = np.argsort(key.ravel(), kind="stable").reshape(c, k)
        idx, hit = idx.ravel()[order], hit.ravel()[order]
        params = tuple(p.ravel()[order] for p in params)
    lane_row = idx + rows * width  # (C, K) flat slot of each region
    n_segments, n_columns = table.segment_start_m.shape[2], table.column_start_m.shape[2]
    segment, column = np.divmod(idx, n_columns)
    segment += rows * n_segments  # flat (row, segment) / (row, column) positions
    column += rows * n_columns
    segment_start = table.segment_start_m.reshape(2, -1)
    column_start = table.column_start_m.reshape(2, -1)
    starts = (segment_start[0], segment_start[1], column_start[0], column_start[1])
    where = (segment, segment, column, column)
    bounds = np.empty((4, c, k))  # start + param * scale per extent, one gather each
    for q in range(4):
        np.multiply(params[q], table.scale_m[q].take(lane_row), out=bounds[q])
        bounds[q] += starts[q].take(where[q])
    direction = table.direction.ravel().take(lane_row)
    if k > 1:
        merged = _merge(bounds, hit, _BOUND_SIGN)
    else:  # one region per object: no reduction over regions needed
        # + 0.0 as the merge's result (-0.0 becomes 0.0), NaN where the region is not found
        merged = bounds[:, :, 0] + (0.0 if hit.all() else np.where(hit[:, 0], 0.0, np.nan))
    return Extents(
        lon_min_m=merged[0],
        lon_max_m=merged[1],
        lat_min_m=merged[2],
        lat_max_m=merged[3],
        on_positive_lane=any_column(hit & (direction == LaneDrivingDirection.Positive)),
        on_negative_lane=any_column(hit & (direction == LaneDrivingDirection.Negative)),
        found=any_column(hit),
        intersection_min_m=table.intersection_min_m,
        intersection_max_m=table.intersection_max_m,
    )


def any_column(flags: BoolArray) -> BoolArray:
    """``flags.any(axis=1)`` of ``(C, K)`` flags, one step per column (K is a handful)."""
    out = flags[:, 0].copy()
    for k in range(1, flags.shape[1]):
        out |= flags[:, k]
    return out


def _find_lanes(lane: IntArray, table_lanes: IntArray) -> tuple[BoolArray, IntArray]:
    """The first lane slot of each region's lane in its road area.

    Args:
        lane: ``(C, K)`` lane id per region (-1 = none).
        table_lanes: ``(W, C)`` lane ids per lane slot of the road areas.

    Returns:
        ``(hit, idx)``, ``(C, K)`` each: found, and the first matching slot (0 if none).
        One vectorised step per slot, over ``(K, C)`` rows (numpy reduces a short last
        axis row by row).
    """
    lanes = np.ascontiguousarray(lane.T)  # (K, C)
    valid = lanes >= 0
    hit = np.zeros(lanes.shape, dtype=np.bool_)
    idx = np.zeros(lanes.shape, dtype=np.int64)
    for slot in range(table_lanes.shape[0] - 1, -1, -1):  # the first match is set last
        same = lanes == table_lanes[slot]
        same &= valid
        idx[same] = slot
        hit |= same
    return hit.T, idx.T


_MIN_MAX_SIGN = np.array([[-1.0], [1.0]])


def _reduce(values: FloatArray, valid: BoolArray) -> FloatArray:
    """Tolerant running min (slot 0) and max (slot 1) over the last axis.

    ``(2, C, A, B)`` values, ``(C, A, B)`` valid -> ``(2, C, A)``; entries where nothing is
    valid are 0.
    """
    _, c, a, b = values.shape
    merged = _merge(values.reshape(2, c * a, b), valid.reshape(c * a, b), _MIN_MAX_SIGN)
    # np.nan_to_num(merged, nan=0.0) with fewer numpy calls: NaN -> 0, +-inf -> +-max
    merged[np.isnan(merged)] = 0.0
    infinite = np.isinf(merged)
    if infinite.any():
        merged[infinite] = np.copysign(np.finfo(np.float64).max, merged[infinite])
    out: FloatArray = merged.reshape(2, c, a)
    return out


def _merge(values: FloatArray, hit: BoolArray, sign: FloatArray) -> FloatArray:
    """Tolerant running min / max over the ``K`` sorted regions.

    Args:
        values: ``(M, N, K)`` values of ``M`` quantities.
        hit: ``(N, K)`` entries that count.
        sign: ``(M, 1)`` -1 = tolerant min (``lt``), +1 = tolerant max (``gt``) per
            quantity.

    Returns:
        ``(M, N)``; NaN where no entry counts. The loop runs over the region slots ``K``
        (a handful), each step vectorised over ``N`` and ``M``.
    """
    # the first slot: every current value is NaN, so a hit is taken
    current = np.where(hit[:, 0], values[:, :, 0], np.nan)
    for k in range(1, values.shape[2]):
        value = values[:, :, k]
        take = np.subtract(value, current)
        take *= sign
        take = take >= DISTANCE_PRECISION
        take |= np.isnan(current)
        take &= hit[:, k]
        np.copyto(current, value, where=take)
    return current


def object_extents(obj: ObjectArrays, road: RoadAreaArrays) -> Extents:
    """Metric extents of one object per constellation in a road area (``(C,)`` each)."""
    return place(obj, lane_table(road))
