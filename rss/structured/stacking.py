"""Stacking of scalar :mod:`rss.model` constellations into a :class:`ConstellationBatch`.

One validating pass over the constellations collects flat rows (each distinct object and
road segment read once), then the padded arrays of :mod:`rss.structured.batch` are filled
with one indexed assignment per field. For a small frame the same rows are kept for the
record-oriented input of the row path (:mod:`rss.structured.small_input`, packed on
first use).
"""

from __future__ import annotations

import functools
import math
import operator
from typing import TYPE_CHECKING, Any

import numpy as np

from rss.errors import RssConstellationError
from rss.model import ConstellationType, LaneDrivingDirection, ObjectType, RoadSegmentType
from rss.structured.batch import (
    ConstellationBatch,
    ObjectArrays,
    RoadAreaArrays,
    int_array,
    readonly_floats,
    readonly_ints,
    stack_dynamics,
)
from rss.structured.small_input import SMALL_FRAME_MAX, pack, remember

if TYPE_CHECKING:
    from collections.abc import Sequence

    from rss.arrays import IntArray
    from rss.model import Constellation, LaneObject, LaneSegment, RoadSegment

__all__ = ["stack_constellations"]

# multi-attribute getters return the attribute objects as they are (compiled code would
# unbox and box again each float read through the typed model)
_LANE = operator.attrgetter(
    "lane_id", "driving_direction", "length_min_m", "length_max_m", "width_min_m", "width_max_m"
)
_LENGTHS = operator.attrgetter(
    "min_length_before_intersecting_area_m", "min_length_after_intersecting_area_m"
)
_REGION = operator.attrgetter("lon_min", "lon_max", "lat_min", "lat_max")
_SPEED = operator.attrgetter("lon_min_mps", "lon_max_mps", "lat_min_mps", "lat_max_mps")
_CONSTELLATION_CODES = frozenset(int(v) for v in ConstellationType)
_OBJECT_CODES = frozenset(int(v) for v in ObjectType)
_SEGMENT_CODES = frozenset(int(v) for v in RoadSegmentType)
_DIRECTION_CODES = frozenset(int(v) for v in LaneDrivingDirection)


def stack_constellations(constellations: Sequence[Constellation]) -> ConstellationBatch:
    """Pad and stack scalar constellations into a :class:`ConstellationBatch`.

    One pass over the constellations validates them and collects flat rows; the padded
    arrays are filled by one indexed assignment per field and searched for lane ids
    repeated within a road area. On any structural error the constellations are checked
    again one by one (:func:`_check_in_order`), so the first error in their order is the
    one raised. Structural errors raise; value
    errors of single objects (NaN, negative speed, a region outside the road area) do not:
    the engine flags those constellations invalid.

    Raises:
        RssConstellationError: Unknown constellation type / direction / segment type,
            negative or inverted lane lengths or widths, duplicate lane ids.
    """
    types: list[int] = []
    ego, other = _ObjectRows(), _ObjectRows()
    ego_road, intersecting_road = _RoadRows(), _RoadRows()
    try:
        for c in constellations:
            kind = c.constellation_type
            _check_kind(kind)
            ego.add(c.ego)
            other.add(c.other)
            ego_road.add(c.ego_road)
            intersecting_road.add(c.intersecting_road)
            types.append(int(kind))
    except RssConstellationError:
        _check_in_order(constellations)
        raise
    roads = ego_road.arrays(), intersecting_road.arrays()
    if any(_repeats_lane(road.lane_id) for road in roads):
        _check_in_order(constellations)
    dynamics = [c.ego_dynamics for c in constellations], [c.other_dynamics for c in constellations]
    batch = ConstellationBatch(
        constellation_type=readonly_ints(types),
        ego=ego.arrays(),
        other=other.arrays(),
        ego_dynamics=stack_dynamics(dynamics[0]),
        other_dynamics=stack_dynamics(dynamics[1]),
        ego_road=roads[0],
        intersecting_road=roads[1],
    )
    if 0 < len(types) <= SMALL_FRAME_MAX:  # the row path's input, from the same rows
        rows = (ego, other), (ego_road, intersecting_road)
        remember(batch, functools.partial(pack, types, *rows, dynamics))
    return batch


def _check_kind(kind: object) -> None:
    """Raise unless ``kind`` is a known structured constellation type."""
    if not _known(kind, _CONSTELLATION_CODES):
        raise RssConstellationError("constellation_type", kind, "unknown")
    if kind == ConstellationType.Unstructured:
        raise RssConstellationError(
            "constellation_type", "Unstructured", "not a structured constellation (issue 6)"
        )


def _check_object(obj: LaneObject) -> None:
    """Raise unless ``obj`` has a known object type."""
    if not _known(obj.object_type, _OBJECT_CODES):
        raise RssConstellationError("object_type", obj.object_type, "unknown")


def _check_in_order(constellations: Sequence[Constellation]) -> None:
    """Raise the first structural error of ``constellations`` (the exact, slow checks).

    Per constellation in order: its type, the ego's and the other's object type, then
    the ego road and the intersecting road in road order (:func:`_check_road`).
    """
    for c in constellations:
        _check_kind(c.constellation_type)
        _check_object(c.ego)
        _check_object(c.other)
        _check_road(c.ego_road)
        _check_road(c.intersecting_road)


def _repeats_lane(lane_id: IntArray) -> bool:
    """Whether a lane id occurs twice in one road area.

    Args:
        lane_id: ``(C, R, L)`` lane ids, -1 = no lane (valid ids are >= 0).
    """
    count, segments, lanes = lane_id.shape
    ids = np.sort(lane_id.reshape(count, segments * lanes), axis=1)
    return bool(((ids[:, 1:] == ids[:, :-1]) & (ids[:, 1:] >= 0)).any())


def _known(code: object, codes: frozenset[int]) -> bool:
    try:
        return code in codes
    except TypeError:  # unhashable
        return False


class _ObjectRows:
    """Objects of ``C`` constellations as flat rows.

    Each distinct :class:`LaneObject` (a frame's placed objects are shared by many
    constellations) is validated and read once, on first sight; its regions are spread to
    every use in :meth:`arrays`.
    """

    def __init__(self) -> None:
        self.uses: list[int] = []  # distinct object per row
        self._known: dict[int, int] = {}
        self._distinct: list[LaneObject] = []
        self.ids: list[int] = []
        self.types: list[int] = []
        self.speeds: list[float] = []  # 4 per distinct object
        self.counts: list[int] = []  # regions per distinct object
        self.lanes: list[int] = []  # 1 per region
        self.params: list[float] = []  # 4 per region

    def add(self, obj: LaneObject) -> None:
        """Add the object of the next row.

        Raises:
            RssConstellationError: Unknown object type.
        """
        k = self._known.get(id(obj))
        if k is None:
            k = self._first(obj)
        self.uses.append(k)

    def _first(self, obj: LaneObject) -> int:
        _check_object(obj)
        kind = obj.object_type
        k = self._known[id(obj)] = len(self._distinct)
        self._distinct.append(obj)
        self.ids.append(obj.object_id)
        self.types.append(int(kind))
        self.speeds.extend(_SPEED(obj.speed))
        regions = obj.regions
        self.counts.append(len(regions))
        for r in regions:
            self.lanes.append(r.lane_id)
            self.params.extend(_REGION(r))
        return k

    def arrays(self) -> ObjectArrays:
        use = int_array(self.uses)
        width = max(1, max(self.counts, default=0))
        lane = np.full((len(use), width), -1, dtype=np.int64)
        params = np.zeros((len(use), width, 4))
        if self.lanes:
            rows, k, src = _spread(int_array(self.counts), use)
            lane[rows, k] = np.array(self.lanes, dtype=np.int64)[src]
            params[rows, k] = np.array(self.params, dtype=np.float64).reshape(-1, 4)[src]
        speeds = np.array(self.speeds, dtype=np.float64).reshape(-1, 4)[use]
        return ObjectArrays(
            object_id=readonly_ints(np.array(self.ids, dtype=np.int64)[use]),
            object_type=readonly_ints(np.array(self.types, dtype=np.int64)[use]),
            region_lane_id=readonly_ints(lane),
            region_lon_min=readonly_floats(params[:, :, 0]),
            region_lon_max=readonly_floats(params[:, :, 1]),
            region_lat_min=readonly_floats(params[:, :, 2]),
            region_lat_max=readonly_floats(params[:, :, 3]),
            speed_lon_min_mps=readonly_floats(speeds[:, 0]),
            speed_lon_max_mps=readonly_floats(speeds[:, 1]),
            speed_lat_min_mps=readonly_floats(speeds[:, 2]),
            speed_lat_max_mps=readonly_floats(speeds[:, 3]),
        )


def _spread(counts: IntArray, use: IntArray) -> tuple[IntArray, IntArray, IntArray]:
    """Spread the sub-rows of distinct items to each of their uses.

    Args:
        counts: ``(D,)`` sub-rows (lanes, regions) of each distinct item, stored one item
            after the other.
        use: ``(U,)`` distinct item of each use.

    Returns:
        Per spread sub-row: the use it belongs to, its position within the item, and the
        stored sub-row it copies.
    """
    n = counts[use]
    offset = np.arange(int(n.sum())) - np.repeat(np.cumsum(n) - n, n)
    first = np.cumsum(counts) - counts
    return np.repeat(np.arange(len(use)), n), offset, np.repeat(first[use], n) + offset


class _RoadRows:
    """Road areas of ``C`` constellations as validated, flat segment rows.

    Each distinct :class:`RoadSegment` object (whole segments are shared by many road
    areas, a frame's cut ones by several) is validated and read once per stacking, in one
    pass over its lanes; its lanes are spread to every use by a few numpy calls in
    :meth:`arrays`. A road that fails validation is re-checked lane by lane
    (:func:`_check_road`) for the exact error. Lane ids repeated within a road area are
    not checked here but in the padded arrays (:func:`stack_constellations`).
    """

    def __init__(self) -> None:
        self.sizes: list[int] = []  # segments per row
        self.uses: list[int] = []  # distinct segment per segment of each row, flat
        self.lanes = 1  # L
        self._known: dict[int, int] = {}
        self._distinct: list[RoadSegment] = []
        self.kinds: list[int] = []
        self.lengths: list[float] = []  # before, after per distinct segment
        self.counts: list[int] = []  # lanes per distinct segment
        self.codes: list[int] = []  # lane id, driving direction per lane
        self.values: list[float] = []  # length min, max, width min, max per lane

    def add(self, road: tuple[RoadSegment, ...]) -> None:
        """Add the road area of the next row.

        Raises:
            RssConstellationError: The first invalid segment or lane of ``road`` (repeated
                lane ids are not checked here).
        """
        self.sizes.append(len(road))
        known, uses = self._known, self.uses
        for segment in road:
            k = known.get(id(segment))
            if k is None:
                k = self._distinct_segment(segment, road)
            uses.append(k)

    def _distinct_segment(self, segment: RoadSegment, road: tuple[RoadSegment, ...]) -> int:
        lanes = segment.lanes
        kind = segment.segment_type
        ok = _known(kind, _SEGMENT_CODES) and bool(lanes)
        codes, values = self.codes, self.values
        for lane in lanes if ok else ():
            row = _lane_row(lane)
            if row is None:
                ok = False
                break
            codes.extend(row[:2])
            values.extend(row[2:])
        if not ok:
            _check_road(road)
        self.lanes = max(self.lanes, len(lanes))
        self.kinds.append(int(kind))
        self.lengths.extend(_LENGTHS(segment))
        self.counts.append(len(lanes))
        k = self._known[id(segment)] = len(self._distinct)
        self._distinct.append(segment)
        return k

    def arrays(self) -> RoadAreaArrays:
        sizes = int_array(self.sizes)
        shape = (len(self.sizes), max(1, int(sizes.max(initial=0))), self.lanes)
        lane_id = np.full(shape, -1, dtype=np.int64)
        direction = np.zeros(shape, dtype=np.int64)
        metric = np.zeros((*shape, 4))
        segment_type = np.full(shape[:2], -1, dtype=np.int64)
        lengths = np.zeros((*shape[:2], 2))
        if self.uses:
            use = int_array(self.uses)
            row, position, _ = _spread(sizes, np.arange(len(sizes)))
            segment_type[row, position] = int_array(self.kinds)[use]
            lengths[row, position] = np.array(self.lengths, dtype=np.float64).reshape(-1, 2)[use]
            lanes, m, src = _spread(int_array(self.counts), use)
            at = (row[lanes], position[lanes], m)
            codes = int_array(self.codes).reshape(-1, 2)
            lane_id[at] = codes[src, 0]
            direction[at] = codes[src, 1]
            metric[at] = np.fromiter(self.values, np.float64, len(self.values)).reshape(-1, 4)[src]
        return RoadAreaArrays(
            lane_id=readonly_ints(lane_id),
            driving_direction=readonly_ints(direction),
            length_min_m=readonly_floats(metric[..., 0]),
            length_max_m=readonly_floats(metric[..., 1]),
            width_min_m=readonly_floats(metric[..., 2]),
            width_max_m=readonly_floats(metric[..., 3]),
            segment_type=readonly_ints(segment_type),
            before_intersection_m=readonly_floats(lengths[..., 0]),
            after_intersection_m=readonly_floats(lengths[..., 1]),
        )


def _lane_row(lane: LaneSegment) -> tuple[Any, ...] | None:
    """A lane's id, direction code, length min, max and width min, max [m] if they are valid.

    Returns:
        The row, or None if a length, width, direction or id is invalid (its uniqueness is
        not checked).
    """
    row: tuple[Any, ...] = _LANE(lane)
    lane_id, direction, low, high, wide_low, wide_high = row
    try:
        ok = (
            0.0 <= low <= high < math.inf
            and 0.0 <= wide_low <= wide_high < math.inf
            and direction in _DIRECTION_CODES
            and lane_id >= 0
        )
    except TypeError:
        return None
    return row if ok else None


def _check_road(road: tuple[RoadSegment, ...]) -> None:
    """Raise the error of the first invalid segment or lane of ``road`` (in road order)."""
    seen: set[int] = set()
    for segment in road:
        kind = segment.segment_type
        if not _known(kind, _SEGMENT_CODES):
            raise RssConstellationError("segment_type", kind, "unknown")
        if not segment.lanes:
            raise RssConstellationError("road segment", segment, "has no lanes")
        for lane in segment.lanes:
            try:
                ok = _lane_row(lane) is not None and lane.lane_id not in seen
            except TypeError:
                ok = False
            if not ok:
                _raise_lane(lane)
            seen.add(lane.lane_id)


def _raise_lane(lane: LaneSegment) -> None:
    """Raise the error of an invalid lane (checks in the documented order)."""
    lane_id = lane.lane_id
    for what, low, high in (
        ("length", lane.length_min_m, lane.length_max_m),
        ("width", lane.width_min_m, lane.width_max_m),
    ):
        if not (low >= 0.0 and high >= low and math.isfinite(high)):
            raise RssConstellationError(
                f"lane {lane_id} {what}", (low, high), "needs finite 0 <= min <= max [m]"
            )
    if not _known(lane.driving_direction, _DIRECTION_CODES):
        raise RssConstellationError(
            f"lane {lane_id} driving_direction", lane.driving_direction, "unknown"
        )
    raise RssConstellationError("lane id", lane_id, "duplicate or negative")
