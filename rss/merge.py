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
    from rss.batch import ConstellationBatch, IntArray, ObjectArrays, RoadAreaArrays
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


def _intersection_lanes(road: RoadAreaArrays, row: int) -> tuple[int, ...]:
    inter = road.segment_type[row] == int(RoadSegmentType.Intersection)
    lanes = road.lane_id[row][inter]
    return tuple(sorted(int(v) for v in lanes[lanes >= 0]))


def _groups(batch: ConstellationBatch, rel: Relative, frame: IntArray) -> list[list[int]]:
    """Rows to merge: valid, same frame, ids, type (and intersection lanes), dynamics."""
    keys: dict[tuple[object, ...], list[int]] = {}
    dyn = [
        np.stack([getattr(d, f.name) for f in dataclasses.fields(d)], axis=1)
        for d in (batch.ego_dynamics, batch.other_dynamics)
    ]
    for row in np.flatnonzero(rel.invalid == int(InvalidReason.Valid)).tolist():
        kind = int(batch.constellation_type[row])
        key: tuple[object, ...] = (
            int(frame[row]),
            int(batch.ego.object_id[row]),
            int(batch.other.object_id[row]),
            kind,
            dyn[0][row].tobytes(),
            dyn[1][row].tobytes(),
        )
        if kind in _INTERSECTION_TYPES:
            key += (
                _intersection_lanes(batch.ego_road, row),
                _intersection_lanes(batch.intersecting_road, row),
            )
        keys.setdefault(key, []).append(row)
    return [rows for rows in keys.values() if len(rows) > 1]


def _union_speeds(obj: ObjectArrays, groups: list[list[int]]) -> ObjectArrays:
    fields = {
        name: getattr(obj, name).copy()
        for name in (
            "speed_lon_min_mps",
            "speed_lon_max_mps",
            "speed_lat_min_mps",
            "speed_lat_max_mps",
        )
    }
    for rows in groups:
        for name, values in fields.items():
            values[rows] = values[rows].min() if name.endswith("min_mps") else values[rows].max()
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
    out = {f.name: getattr(rel, f.name).copy() for f in dataclasses.fields(rel)}
    for rows in groups:
        lon, lon_d = int(out["lon_position"][rows[0]]), float(out["lon_distance_m"][rows[0]])
        lat, lat_d = int(out["lat_position"][rows[0]]), float(out["lat_distance_m"][rows[0]])
        for row in rows[1:]:
            lon, lon_d = merge_positions(
                lon, int(out["lon_position"][row]), lon_d, float(out["lon_distance_m"][row])
            )
            lat, lat_d = merge_positions(
                lat, int(out["lat_position"][row]), lat_d, float(out["lat_distance_m"][row])
            )
        out["lon_position"][rows], out["lon_distance_m"][rows] = lon, lon_d
        out["lat_position"][rows], out["lat_distance_m"][rows] = lat, lat_d
        out["ego_in_correct_lane"][rows] = out["ego_in_correct_lane"][rows].all()
        out["other_in_correct_lane"][rows] = out["other_in_correct_lane"][rows].any()
        for who in ("ego", "other"):
            enter, leave = out[f"{who}_dist_to_enter_m"], out[f"{who}_dist_to_leave_m"]
            enter[rows], leave[rows] = enter[rows].min(), leave[rows].max()
    merged = dataclasses.replace(
        batch, ego=_union_speeds(batch.ego, groups), other=_union_speeds(batch.other, groups)
    )
    return merged, type(rel)(**out)
