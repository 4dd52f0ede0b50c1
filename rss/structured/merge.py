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
from rss.structured.states import InvalidReason

if TYPE_CHECKING:
    from rss.arrays import BoolArray, FloatArray, IntArray
    from rss.structured.batch import (
        ConstellationBatch,
        DynamicsArrays,
        ObjectArrays,
        RoadAreaArrays,
    )
    from rss.structured.extraction import Relative

__all__ = ["merge_position_groups", "merge_positions", "merge_similar"]

_OVERLAP = 2


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


def _lane_keys(road: RoadAreaArrays, rows: IntArray, inter_type: BoolArray) -> IntArray:
    """``(n, R * L)`` sorted lane ids of the Intersection segments of ``rows``.

    -1 pads; rows not of an intersection type (``inter_type`` False) are all -1.
    """
    inter = (road.segment_type[rows] == int(RoadSegmentType.Intersection)) & inter_type[:, None]
    lanes: IntArray = np.where(inter[:, :, None], road.lane_id[rows], -1).reshape(rows.size, -1)
    lanes.sort(axis=1)
    return lanes


_DYNAMICS: list[str] = []


def _dynamics_keys(dyn: DynamicsArrays, rows: IntArray) -> IntArray:
    """``(n, D)`` bit patterns of the dynamics of ``rows``."""
    if not _DYNAMICS:
        _DYNAMICS.extend(f.name for f in dataclasses.fields(dyn))
    values = np.stack([getattr(dyn, name) for name in _DYNAMICS], axis=1)[rows]
    out: IntArray = values.view(np.int64)
    return out


#: Odd 64-bit multipliers mixing the parts of a row's key into one word (any odd
#: constants do: a collision only costs the exact comparison that follows).
_MIX = (0x9E3779B97F4A7C15, 0xC2B2AE3D27D4EB4F, 0x165667B19E3779F9, 0xD6E8FEB86659FD93)


def _may_share(frame: IntArray, batch: ConstellationBatch, rows: IntArray) -> bool:
    """Whether two of ``rows`` may share (frame, ego id, object id, type).

    One sort of a 64-bit mix of the four: equal keys give equal mixes, so False is exact;
    True only asks for the exact comparison.
    """
    columns: tuple[IntArray, ...] = (
        batch.ego.object_id,
        batch.other.object_id,
        batch.constellation_type,
    )
    if rows.size < batch.size:
        columns = tuple(column[rows] for column in columns)
    parts = (frame, columns[0], columns[1])
    mixed = columns[2].astype(np.uint64) * np.uint64(_MIX[3])
    for part, factor in zip(parts, _MIX, strict=False):
        term = part.astype(np.uint64)
        term *= np.uint64(factor)
        mixed ^= term
    mixed.sort()
    return bool((mixed[1:] == mixed[:-1]).any())


@dataclasses.dataclass(frozen=True)
class _Layout:
    """Groups as one row list: ``rows`` concatenated group by group, ``starts`` per group.

    Attributes:
        rows: ``(n,)`` rows of all groups (ascending within a group).
        starts: ``(G,)`` position of each group's first row in ``rows``.
        group: ``(n,)`` group number of each entry of ``rows``.
    """

    rows: IntArray
    starts: IntArray
    group: IntArray


def _groups(batch: ConstellationBatch, rel: Relative, frame: IntArray) -> _Layout | None:
    """Rows to merge: valid, same frame, ids, type (and intersection lanes), dynamics.

    ``None`` when no two rows merge.
    """
    valid = np.flatnonzero(rel.invalid == int(InvalidReason.Valid))
    if valid.size < 2:  # noqa: PLR2004 - a group needs two rows
        return None
    kinds = batch.constellation_type
    if not _may_share(frame[valid], batch, valid):
        return None
    # (4, C): comparisons reduce over the leading axis (numpy reduces a short last axis
    # row by row)
    ids = np.stack([frame, batch.ego.object_id, batch.other.object_id, kinds])
    ids = ids.astype(np.int64, copy=False)
    # Only rows sharing (frame, pair, type) can merge: find them vectorised first, so a
    # batch of many frames without similar constellations costs one sort.
    sub = ids[:, valid]
    order = np.lexsort(sub[::-1])
    ordered = sub[:, order]
    same = (ordered[:, 1:] == ordered[:, :-1]).all(axis=0)
    if not same.any():
        return None
    shared = np.zeros(valid.size, dtype=np.bool_)
    shared[order[1:][same]] = True
    shared[order[:-1][same]] = True
    candidates = valid[shared]
    inter_type = kinds[candidates] >= int(ConstellationType.IntersectionEgoHasPriority)
    inter_type &= kinds[candidates] <= int(ConstellationType.IntersectionSamePriority)
    keys = np.concatenate(
        [
            ids[:, candidates].T,
            _lane_keys(batch.ego_road, candidates, inter_type),
            _lane_keys(batch.intersecting_road, candidates, inter_type),
            _dynamics_keys(batch.ego_dynamics, candidates),
            _dynamics_keys(batch.other_dynamics, candidates),
        ],
        axis=1,
    )
    # one stable sort of the whole keys as byte strings: equal keys become neighbours,
    # rows of a group stay ascending
    whole = keys.view(np.dtype((np.void, keys.shape[1] * keys.itemsize))).ravel()
    order = np.argsort(whole, kind="stable")
    sorted_keys = whole[order]
    first = np.ones(order.size, dtype=np.bool_)
    first[1:] = sorted_keys[1:] != sorted_keys[:-1]
    group = np.cumsum(first) - 1
    size = np.bincount(group)
    in_group = size[group] > 1
    if not in_group.any():
        return None
    group = group[in_group]
    new = np.ones(group.size, dtype=np.bool_)
    new[1:] = group[1:] != group[:-1]
    return _Layout(candidates[order[in_group]], np.flatnonzero(new), np.cumsum(new) - 1)


_SPEEDS_MIN = ("speed_lon_min_mps", "speed_lat_min_mps")
_SPEEDS_MAX = ("speed_lon_max_mps", "speed_lat_max_mps")
_REL_MIN = ("ego_dist_to_enter_m", "other_dist_to_enter_m")
_REL_MAX = ("ego_dist_to_leave_m", "other_dist_to_leave_m")


def merge_position_groups(
    codes: IntArray, distances: FloatArray, starts: IntArray
) -> tuple[IntArray, FloatArray]:
    """Per group the fold of :func:`merge_positions` over its rows, vectorised.

    Args:
        codes: ``(n, k)`` position codes, rows grouped.
        distances: ``(n, k)`` their distances [m] (>= 0; 0 for the Overlap codes 1..3).
        starts: ``(G,)`` first row of each group (ascending, groups not empty).

    Returns:
        ``(codes, distances)``, ``(G, k)`` each: Overlap and 0 m where a group holds
        Overlap or codes on both sides of it, else the code nearest to Overlap (on the
        group's one side) and the smallest distance.
    """
    high = np.maximum.reduceat(codes, starts)
    low = np.minimum.reduceat(codes, starts)
    overlap = (high >= _OVERLAP) & (low <= _OVERLAP)
    merged: IntArray = np.where(overlap, _OVERLAP, np.where(high < _OVERLAP, high, low))
    nearest: FloatArray = np.minimum.reduceat(distances, starts)
    nearest[overlap] = 0.0
    return merged, nearest


def _filled(values: np.ndarray, rows: IntArray, per_row: np.ndarray) -> np.ndarray:
    """``values`` with ``rows`` set to ``per_row``."""
    out = values.copy()
    out[rows] = per_row
    return out


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
    layout = _groups(batch, rel, frame)
    if layout is None:
        return batch, rel
    rows, starts, group = layout.rows, layout.starts, layout.group
    codes, distances = merge_position_groups(
        np.stack([rel.lon_position, rel.lat_position], axis=1)[rows],
        np.stack([rel.lon_distance_m, rel.lat_distance_m], axis=1)[rows],
        starts,
    )
    codes, distances = codes[group], distances[group]
    objects = (batch.ego, batch.other)

    def worst(reduce: np.ufunc, rel_names: tuple[str, ...], speeds: tuple[str, ...]) -> FloatArray:
        """Per row, ``reduce`` of the named columns over its group."""
        columns = [getattr(rel, name) for name in rel_names]
        columns += [getattr(obj, name) for obj in objects for name in speeds]
        out: FloatArray = reduce.reduceat(np.stack(columns, axis=1)[rows], starts)[group]
        return out

    lows = worst(np.minimum, _REL_MIN, _SPEEDS_MIN)
    highs = worst(np.maximum, _REL_MAX, _SPEEDS_MAX)
    ego_correct = np.logical_and.reduceat(rel.ego_in_correct_lane[rows], starts)[group]
    other_correct = np.logical_or.reduceat(rel.other_in_correct_lane[rows], starts)[group]
    fields = {
        "lon_position": _filled(rel.lon_position, rows, codes[:, 0]),
        "lon_distance_m": _filled(rel.lon_distance_m, rows, distances[:, 0]),
        "lat_position": _filled(rel.lat_position, rows, codes[:, 1]),
        "lat_distance_m": _filled(rel.lat_distance_m, rows, distances[:, 1]),
        "ego_in_correct_lane": _filled(rel.ego_in_correct_lane, rows, ego_correct),
        "other_in_correct_lane": _filled(rel.other_in_correct_lane, rows, other_correct),
    }
    for k, name in enumerate(_REL_MIN):
        fields[name] = _filled(getattr(rel, name), rows, lows[:, k])
    for k, name in enumerate(_REL_MAX):
        fields[name] = _filled(getattr(rel, name), rows, highs[:, k])
    new_rel = type(rel)(**fields, invalid=rel.invalid)

    def union(obj: ObjectArrays, column: int) -> ObjectArrays:
        speeds = {}
        for k, name in enumerate(_SPEEDS_MIN):
            speeds[name] = _filled(getattr(obj, name), rows, lows[:, column + k])
        for k, name in enumerate(_SPEEDS_MAX):
            speeds[name] = _filled(getattr(obj, name), rows, highs[:, column + k])
        return dataclasses.replace(obj, **speeds)

    first = len(_REL_MIN)
    merged_batch = dataclasses.replace(
        batch,
        ego=union(batch.ego, first),
        other=union(batch.other, first + len(_SPEEDS_MIN)),
    )
    return merged_batch, new_rel
