"""Scalar twin of the situation extraction (:mod:`rss.structured.extraction`), one row at a time.

Lane table, footprint and relative position of one constellation with plain floats, in the
operation order of :mod:`rss.structured.footprint` and :mod:`rss.structured.extraction`
(tolerant running min / max over lanes and regions, exclusive sums left to right). A row
the batched engine would flag invalid is reported as such (``None``) and the caller hands
the whole frame to the batched engine.

Inputs are flat lists of one row of a :class:`rss.structured.batch.ConstellationBatch`
(its columns concatenated, see :mod:`rss.structured.small`).
"""

from __future__ import annotations

import math
from typing import Final

from rss.physics import DISTANCE_PRECISION
from rss.structured.codes import (
    AT_BACK,
    IN_FRONT,
    INTERSECTION_SEGMENT,
    NEGATIVE,
    OVERLAP,
    OVERLAP_BACK,
    OVERLAP_FRONT,
    POSITIVE,
)

__all__ = ["Placed", "Road", "lane_table", "object_valid", "place", "relative_position"]

_P: Final = DISTANCE_PRECISION
_PARAM_EPS: Final = 1e-9
_SPEED_LIMIT_MPS: Final = 100.0
_FLOAT_MAX: Final = 1.7976931348623157e308


class Road:
    """Lane table of one road area (:class:`rss.structured.footprint.LaneTable`, one row).

    Attributes:
        codes: Lane ids ``(W,)`` of the flattened ``R x L`` slots (-1 = none), then their
            :class:`LaneDrivingDirection` codes ``(W,)`` (and the segment types).
        width: ``W`` (slots).
        n_lanes: ``L`` (slots per segment).
        seg_min_m: ``(R,)`` segment starts, sums of min lengths.
        seg_max_m: ``(R,)`` sums of max lengths.
        col_min_m: ``(L,)`` column starts, sums of min widths.
        col_max_m: ``(L,)`` sums of max widths.
        scale_m: ``(4 W,)`` length min, length max, width min, width max of every slot.
        intersection_min_m: Entry of the intersecting area (NaN if none).
        intersection_max_m: Exit (NaN if none).
        slot_of: First slot of each lane id.
    """

    def __init__(self, codes: list[int], width: int, n_lanes: int, scale_m: list[float]) -> None:
        """The road area's codes and scales; starts and slots are filled by ``lane_table``."""
        self.codes = codes
        self.width = width
        self.n_lanes = n_lanes
        self.scale_m = scale_m
        self.seg_min_m: list[float] = []
        self.seg_max_m: list[float] = []
        self.col_min_m: list[float] = []
        self.col_max_m: list[float] = []
        self.intersection_min_m = math.nan
        self.intersection_max_m = math.nan
        self.slot_of: dict[int, int] = {}

    def direction(self, slot: int) -> int:
        """:class:`LaneDrivingDirection` code of ``slot``."""
        return self.codes[self.width + slot]


class Placed:
    """Metric extents of one object (:class:`rss.structured.footprint.Extents`, one row)."""

    def __init__(  # noqa: PLR0917 - a record of the extents' fields
        self,
        lon_min_m: float,
        lon_max_m: float,
        lat_min_m: float,
        lat_max_m: float,
        on_positive_lane: bool,  # noqa: FBT001
        on_negative_lane: bool,  # noqa: FBT001
        found: bool,  # noqa: FBT001
    ) -> None:
        """Store the fields."""
        self.lon_min_m = lon_min_m
        self.lon_max_m = lon_max_m
        self.lat_min_m = lat_min_m
        self.lat_max_m = lat_max_m
        self.on_positive_lane = on_positive_lane
        self.on_negative_lane = on_negative_lane
        self.found = found


def _tolerant(
    values: list[float], base: int, span: tuple[int, int, int], valid: list[bool], sign: float
) -> float:
    """Tolerant running min (``sign`` -1) or max (+1) of the valid slots of ``span``.

    ``span`` is ``(first slot, end slot, step)``; ``values[base + s]`` is the value of slot
    ``s``; NaN maps to 0 and +-inf to +-max as in ``footprint._reduce``.
    """
    s, end, step = span
    current = math.nan
    while s < end:  # a while loop: mypyc compiles ``range`` with a variable step as a call
        value = values[base + s]
        if valid[s] and (
            current != current  # noqa: PLR0124 - NaN test, native when compiled
            or (value - current) * sign >= _P
        ):
            current = value
        s += step
    if current != current:  # noqa: PLR0124
        return 0.0
    if math.isinf(current):
        return math.copysign(_FLOAT_MAX, current)
    return current


def lane_table(ints: list[int], floats: list[float], n_segments: int, n_lanes: int) -> Road:
    """Lane table of one road area (:func:`rss.structured.footprint.lane_table`, one row).

    Segment starts are the exclusive running sums of the segments' tolerant min / max
    lengths (lane by lane within a segment), column starts those of the columns' widths
    (segment by segment), summed left to right as ``footprint`` does.

    Args:
        ints: lane ids ``(R, L)``, driving directions ``(R, L)`` and segment types ``(R,)``,
            flattened one after the other.
        floats: length min, length max, width min, width max (``(R, L)`` each), then the
            minimum lengths before and after the intersecting area (``(R,)`` each).
        n_segments: ``R``.
        n_lanes: ``L``.
    """
    width = n_segments * n_lanes
    road = Road(ints, width, n_lanes, floats)
    ok = [False] * width
    slot_of = road.slot_of
    for s in range(width):
        lane = ints[s]
        if lane >= 0:
            ok[s] = True
            if lane not in slot_of:
                slot_of[lane] = s
    road.seg_min_m = seg_min = [0.0] * n_segments
    road.seg_max_m = seg_max = [0.0] * n_segments
    sum_min = sum_max = 0.0
    entered = False  # the first intersection segment gives the intersecting area
    for r in range(n_segments):
        span = (r * n_lanes, (r + 1) * n_lanes, 1)
        length_min = _tolerant(floats, 0, span, ok, -1.0)
        length_max = _tolerant(floats, width, span, ok, 1.0)
        seg_min[r], seg_max[r] = sum_min, sum_max
        if not entered and ints[2 * width + r] == INTERSECTION_SEGMENT:
            entered = True
            road.intersection_min_m = sum_min + floats[4 * width + r]
            road.intersection_max_m = sum_max + length_max - floats[4 * width + n_segments + r]
        sum_min = length_min if r == 0 else sum_min + length_min
        sum_max = length_max if r == 0 else sum_max + length_max
    road.col_min_m = col_min = [0.0] * n_lanes
    road.col_max_m = col_max = [0.0] * n_lanes
    sum_min = sum_max = 0.0
    for j in range(n_lanes):
        span = (j, width, n_lanes)
        width_min = _tolerant(floats, 2 * width, span, ok, -1.0)
        width_max = _tolerant(floats, 3 * width, span, ok, 1.0)
        col_min[j], col_max[j] = sum_min, sum_max
        sum_min = width_min if j == 0 else sum_min + width_min
        sum_max = width_max if j == 0 else sum_max + width_max
    return road


_SIGNS: Final = (-1.0, 1.0, -1.0, 1.0)


def place(lanes: list[int], params: list[float], road: Road) -> Placed:
    """Extents of one object in a road area (:func:`rss.structured.footprint.place`, one row).

    Args:
        lanes: ``(K,)`` lane id of each occupied region (-1 = none).
        params: lon min, lon max, lat min, lat max of the regions (``(K,)`` each, flat).
        road: The road area's lane table.
    """
    width, n_regions = road.width, len(lanes)
    if n_regions == 1:
        return _place_one(lanes[0], params, road)
    slots: list[tuple[int, int]] = []  # (sort key, region)
    hits: list[bool] = []
    idx: list[int] = []
    for k, lane in enumerate(lanes):
        slot = road.slot_of.get(lane, -1)
        hits.append(slot >= 0)
        idx.append(max(slot, 0))
        slots.append((slot if slot >= 0 else width, k))
    order = [k for _, k in sorted(slots)]
    current = [math.nan, math.nan, math.nan, math.nan]
    positive = negative = found = False
    for k in order:
        segment, column = divmod(idx[k], road.n_lanes)
        starts = (
            road.seg_min_m[segment],
            road.seg_max_m[segment],
            road.col_min_m[column],
            road.col_max_m[column],
        )
        hit = hits[k]
        for q in range(4):
            value = starts[q] + params[q * n_regions + k] * road.scale_m[q * width + idx[k]]
            if hit and (current[q] != current[q] or (value - current[q]) * _SIGNS[q] >= _P):
                current[q] = value
        if hit:
            found = True
            direction = road.direction(idx[k])
            positive |= direction == POSITIVE
            negative |= direction == NEGATIVE
    return Placed(current[0], current[1], current[2], current[3], positive, negative, found)


def _place_one(lane: int, params: list[float], road: Road) -> Placed:
    """:func:`place` of an object in one region (no running min / max)."""
    slot = road.slot_of.get(lane, -1)
    if slot < 0:
        nan = math.nan
        return Placed(nan, nan, nan, nan, False, False, False)  # noqa: FBT003
    width = road.width
    segment, column = divmod(slot, road.n_lanes)
    scale = road.scale_m
    direction = road.codes[width + slot]
    return Placed(
        road.seg_min_m[segment] + params[0] * scale[slot] + 0.0,
        road.seg_max_m[segment] + params[1] * scale[width + slot] + 0.0,
        road.col_min_m[column] + params[2] * scale[2 * width + slot] + 0.0,
        road.col_max_m[column] + params[3] * scale[3 * width + slot] + 0.0,
        direction == POSITIVE,
        direction == NEGATIVE,
        True,  # noqa: FBT003
    )


def object_valid(lanes: list[int], params: list[float], speeds: list[float]) -> bool:
    """Whether ``extraction._invalid_objects`` does not flag the object (speeds, regions).

    Args:
        lanes: ``(K,)`` lane id of each occupied region (-1 = none).
        params: lon min, lon max, lat min, lat max of the regions (``(K,)`` each, flat).
        speeds: lon min, lon max, lat min, lat max [m/s].
    """
    lon_min, lon_max, lat_min, lat_max = speeds[0], speeds[1], speeds[2], speeds[3]
    for speed in speeds:
        if speed - speed != 0.0:  # not finite (native when compiled)
            return False
    if (
        lon_min < 0.0
        or lon_max < lon_min
        or lon_max > _SPEED_LIMIT_MPS
        or lat_min < -_SPEED_LIMIT_MPS
        or lat_max < lat_min
        or lat_max > _SPEED_LIMIT_MPS
    ):
        return False
    n_regions = len(lanes)
    for k, lane in enumerate(lanes):
        if lane < 0:
            continue
        lon_lo, lon_hi = params[k], params[n_regions + k]
        lat_lo, lat_hi = params[2 * n_regions + k], params[3 * n_regions + k]
        if not (_unit(lon_lo) and _unit(lon_hi) and _unit(lat_lo) and _unit(lat_hi)) or (
            lon_lo > lon_hi or lat_lo > lat_hi
        ):
            return False
    return True


def _unit(value: float) -> bool:
    """Whether a region parameter is finite and within [0, 1] (tolerance 1e-9)."""
    return value - value == 0.0 and -_PARAM_EPS <= value <= 1.0 + _PARAM_EPS


def relative_position(
    ego_min: float, ego_max: float, other_min: float, other_max: float
) -> tuple[int, float]:
    """``(LongitudinalPosition code, distance)`` (:func:`extraction.relative_position`)."""
    if ego_min - other_max >= _P:
        return IN_FRONT, ego_min - other_max
    if other_min - ego_max >= _P:
        return AT_BACK, other_min - ego_max
    if ego_min - other_min >= _P and ego_max - other_max >= _P:
        return OVERLAP_FRONT, 0.0
    if other_min - ego_min >= _P and other_max - ego_max >= _P:
        return OVERLAP_BACK, 0.0
    return OVERLAP, 0.0
