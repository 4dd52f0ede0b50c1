"""Worst-case merging of similar constellations (ad-rss ``RssSituationExtraction``).

ad-rss gives every constellation an id (``RssConstellationIdProvider``): constellations
of one ego/object pair with the same type get the same id — for intersection types only
if their intersection lanes are the same (a subset, in ad-rss) — and
``extractSituation`` merges relative constellations of one id into their worst case::

    longitudinal / lateral distance      min        (contradicting sides -> Overlap, 0 m)
    ego in correct lane                  all        other in correct lane   any
    distance to enter the intersection   min        distance to leave       max
    speed intervals                      union

Here the rows stay (the engine's outputs keep one row per constellation): every row of a
group gets the merged values, so the group is checked once as its worst case. Rows whose
dynamics differ are not merged (ad-rss fails the whole extraction then).
"""

from __future__ import annotations

import dataclasses
from typing import TYPE_CHECKING

import numpy as np

from rss.model import ConstellationType, RoadSegmentType
from rss.states import InvalidReason

if TYPE_CHECKING:
    from rss.batch import (
        ConstellationBatch,
        DynamicsArrays,
        IntArray,
        ObjectArrays,
        RoadAreaArrays,
    )
    from rss.extraction import Relative

__all__ = ["merge_positions", "merge_similar"]

_OVERLAP = 2
_INTERSECTION_TYPES = frozenset(
    {
        int(ConstellationType.IntersectionEgoHasPriority),
        int(ConstellationType.IntersectionObjectHasPriority),
        int(ConstellationType.IntersectionSamePriority),
    }
)


def merge_positions(a: int, b: int, dist_a: float, dist_b: float) -> tuple[int, float]:
    """Worst case of two relative positions (longitudinal or lateral codes) and distances.

    Codes 0..4 with 2 = Overlap, 1 / 3 the overlapping sides (as both position enums).
    """
    dist = min(dist_a, dist_b)
    if a == b:
        return a, dist
    if _OVERLAP in {a, b} or (a < _OVERLAP) != (b < _OVERLAP):
        return _OVERLAP, 0.0
    side = {a, b} & {_OVERLAP - 1, _OVERLAP + 1}
    return (side.pop(), dist) if side else (_OVERLAP, 0.0)


def _lane_keys(road: RoadAreaArrays, kinds: IntArray) -> IntArray:
    """``(C, R * L)`` sorted lane ids of the Intersection segments of intersection types.

    -1 pads; rows of other types are all -1.
    """
    c = road.lane_id.shape[0]
    inter = road.segment_type == int(RoadSegmentType.Intersection)
    lanes = np.where(inter[:, :, None], road.lane_id, -1).reshape(c, -1)
    lanes[~np.isin(kinds, list(_INTERSECTION_TYPES))] = -1
    out: IntArray = np.sort(lanes, axis=1)
    return out


_DYNAMICS: list[str] = []


def _dynamics_keys(dyn: DynamicsArrays) -> IntArray:
    if not _DYNAMICS:
        _DYNAMICS.extend(f.name for f in dataclasses.fields(dyn))
    values = np.stack([getattr(dyn, name) for name in _DYNAMICS], axis=1)
    out: IntArray = np.ascontiguousarray(values, dtype=np.float64).view(np.int64)
    return out


def _groups(batch: ConstellationBatch, rel: Relative, frame: IntArray) -> list[list[int]]:
    """Rows to merge: valid, same frame, ids, type (and intersection lanes), dynamics."""
    valid = np.flatnonzero(rel.invalid == int(InvalidReason.Valid))
    if len(valid) < 2:  # noqa: PLR2004 - a group needs two rows
        return []
    kinds = batch.constellation_type
    ids = np.stack([frame, batch.ego.object_id, batch.other.object_id, kinds], axis=1)
    ids = ids.astype(np.int64)
    # Only rows sharing (frame, pair, type) can merge: find them vectorised first, so a
    # batch of many frames without similar constellations costs one sort.
    sub = ids[valid]
    order = np.lexsort(sub.T[::-1])
    same = np.all(sub[order[1:]] == sub[order[:-1]], axis=1)
    if not same.any():
        return []
    shared = np.zeros(len(valid), dtype=bool)
    shared[order[1:][same]] = True
    shared[order[:-1][same]] = True
    candidates = valid[shared]
    keys = np.concatenate(
        [
            ids[candidates],
            _lane_keys(batch.ego_road, kinds)[candidates],
            _lane_keys(batch.intersecting_road, kinds)[candidates],
            _dynamics_keys(batch.ego_dynamics)[candidates],
            _dynamics_keys(batch.other_dynamics)[candidates],
        ],
        axis=1,
    )
    found: dict[tuple[int, ...], list[int]] = {}
    for row, key in zip(candidates.tolist(), keys.tolist(), strict=True):
        found.setdefault(tuple(key), []).append(row)
    return [rows for rows in found.values() if len(rows) > 1]


_SPEEDS = ("speed_lon_min_mps", "speed_lon_max_mps", "speed_lat_min_mps", "speed_lat_max_mps")


@dataclasses.dataclass(frozen=True)
class _Layout:
    """Groups as one row list: ``rows`` concatenated, ``starts`` / ``sizes`` per group."""

    rows: IntArray
    starts: IntArray
    sizes: IntArray

    def reduce(self, values: np.ndarray, op: np.ufunc) -> np.ndarray:
        """``values`` with every group's rows set to ``op`` over the group."""
        out = values.copy()
        out[self.rows] = np.repeat(op.reduceat(values[self.rows], self.starts), self.sizes)
        return out

    def fill(self, values: np.ndarray, per_group: list[float] | list[int]) -> np.ndarray:
        """``values`` with every group's rows set to its entry of ``per_group``."""
        out = values.copy()
        out[self.rows] = np.repeat(np.asarray(per_group, dtype=values.dtype), self.sizes)
        return out


def _layout(groups: list[list[int]]) -> _Layout:
    sizes = np.array([len(g) for g in groups], dtype=np.int64)
    starts = np.concatenate([[0], np.cumsum(sizes)[:-1]]).astype(np.int64)
    return _Layout(np.array([r for g in groups for r in g], dtype=np.int64), starts, sizes)


def _union_speeds(obj: ObjectArrays, layout: _Layout) -> ObjectArrays:
    fields = {
        name: layout.reduce(getattr(obj, name), np.minimum if "min" in name else np.maximum)
        for name in _SPEEDS
    }
    return dataclasses.replace(obj, **fields)


def merge_similar(
    batch: ConstellationBatch, rel: Relative, frame: IntArray
) -> tuple[ConstellationBatch, Relative]:
    """Give every group of similar constellations its worst case (see module docstring).

    Args:
        batch: ``C`` constellations.
        rel: Their extracted relative situations.
        frame: ``(C,)`` frame number of each constellation.

    Returns:
        ``(batch, rel)`` with merged speed intervals and relative situations.
    """
    groups = _groups(batch, rel, frame)
    if not groups:
        return batch, rel
    layout = _layout(groups)
    lon, lon_d = rel.lon_position.tolist(), rel.lon_distance_m.tolist()
    lat, lat_d = rel.lat_position.tolist(), rel.lat_distance_m.tolist()
    merged: list[list[float]] = [[], [], [], []]
    for rows in groups:
        first = rows[0]
        m = [lon[first], lon_d[first], lat[first], lat_d[first]]
        for row in rows[1:]:
            m[0], m[1] = merge_positions(int(m[0]), lon[row], m[1], lon_d[row])
            m[2], m[3] = merge_positions(int(m[2]), lat[row], m[3], lat_d[row])
        for column, value in zip(merged, m, strict=True):
            column.append(value)
    new_rel = type(rel)(
        lon_position=layout.fill(rel.lon_position, merged[0]),
        lon_distance_m=layout.fill(rel.lon_distance_m, merged[1]),
        lat_position=layout.fill(rel.lat_position, merged[2]),
        lat_distance_m=layout.fill(rel.lat_distance_m, merged[3]),
        ego_in_correct_lane=layout.reduce(rel.ego_in_correct_lane, np.logical_and),
        other_in_correct_lane=layout.reduce(rel.other_in_correct_lane, np.logical_or),
        ego_dist_to_enter_m=layout.reduce(rel.ego_dist_to_enter_m, np.minimum),
        ego_dist_to_leave_m=layout.reduce(rel.ego_dist_to_leave_m, np.maximum),
        other_dist_to_enter_m=layout.reduce(rel.other_dist_to_enter_m, np.minimum),
        other_dist_to_leave_m=layout.reduce(rel.other_dist_to_leave_m, np.maximum),
        invalid=rel.invalid,
    )
    merged_batch = dataclasses.replace(
        batch, ego=_union_speeds(batch.ego, layout), other=_union_speeds(batch.other, layout)
    )
    return merged_batch, new_rel
