"""Worst-case merging of similar constellations in the small-frame path, one frame.

The row twin of :func:`rss.structured.merge.merge_similar`: rows merge when they share
the batched engine's group key (``merge._groups``) — ego id, object id and type; for an
intersection type also the lanes of the Intersection segments of the ego road and of the
intersecting road (as ad-rss gives constellations of other intersection lanes their own
id); and the dynamics records of ego and object (rows of one pair and type with other
dynamics are groups of their own, as in the batched engine). Every row of a group gets
the group's worst case (positions and distances as
:func:`rss.structured.merge.merge_position_groups`, ego in correct lane: all, other: any,
distances to enter: min, to leave: max, speed intervals: union) and is checked as that.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from rss.structured.codes import EGO_PRIORITY, INTERSECTION_SEGMENT, OVERLAP

if TYPE_CHECKING:
    from rss.structured.small_input import Packed
    from rss.structured.small_output import Columns

__all__ = ["merge_rows"]

#: A group's key: ego id, object id, type, the intersection lanes of the ego road and of
#: the intersecting road (empty for other types), ego and object dynamics records.
_Key = tuple[int, int, int, tuple[int, ...], tuple[int, ...], int, int]


def merge_rows(
    out: Columns, rows: Packed, keys: list[tuple[int, int, int]], *, unique: bool
) -> tuple[list[list[float]], list[list[float]]]:
    """Merge the groups of similar rows of ``out`` in place; speeds per row to check with.

    Args:
        out: The frame's extracted rows (relative positions, distances, lanes).
        rows: The frame's packed input.
        keys: ``(ego id, object id, type)`` per row.
        unique: One row per key (nothing to merge).

    Returns:
        ``(ego speeds, other speeds)`` per row (lon min, lon max, lat min, lat max [m/s],
        merged within groups).
    """
    ego_speeds = [rows.speeds[e] for e in rows.ego]
    other_speeds = [rows.speeds[o] for o in rows.other]
    if unique:
        return ego_speeds, other_speeds
    count: dict[tuple[int, int, int], int] = {}
    for key in keys:
        count[key] = count.get(key, 0) + 1
    lanes: dict[int, tuple[int, ...]] = {}
    groups: dict[_Key, list[int]] = {}
    for c, key in enumerate(keys):
        if count[key] == 1:
            continue
        ego_lanes: tuple[int, ...] = ()
        cross_lanes: tuple[int, ...] = ()
        if key[2] >= EGO_PRIORITY:
            ego_lanes = _lanes(rows, rows.ego_road[c], lanes)
            cross_lanes = _lanes(rows, rows.cross_road[c], lanes)
        group = (
            key[0],
            key[1],
            key[2],
            ego_lanes,
            cross_lanes,
            rows.ego_dynamics[c],
            rows.other_dynamics[c],
        )
        members = groups.get(group)
        if members is None:
            groups[group] = [c]
        else:
            members.append(c)
    for members in groups.values():
        if len(members) > 1:
            _merge_group(out, members, ego_speeds, other_speeds)
    return ego_speeds, other_speeds


def _lanes(rows: Packed, road: int, known: dict[int, tuple[int, ...]]) -> tuple[int, ...]:
    """Sorted lane ids (-1 pads left out) of the Intersection segments of road area ``road``.

    Equal for two rows exactly when ``merge._lane_keys`` is: it sorts the same ids with -1
    in every other of the batch's ``R * L`` slots, a width all rows share.
    """
    found = known.get(road)
    if found is not None:
        return found
    n_segments, n_lanes = rows.road_shape[road]
    ints = rows.road_ints[road]
    types = 2 * n_segments * n_lanes
    ids = [
        ints[r * n_lanes + j]
        for r in range(n_segments)
        if ints[types + r] == INTERSECTION_SEGMENT
        for j in range(n_lanes)
        if ints[r * n_lanes + j] != -1
    ]
    ids.sort()
    found = known[road] = tuple(ids)
    return found


def _position(codes: list[int], distances: list[float]) -> tuple[int, float]:
    """Worst case of positions and distances (``merge.merge_position_groups``, one group)."""
    high, low = max(codes), min(codes)
    if high >= OVERLAP >= low:
        return OVERLAP, 0.0
    return (high if high < OVERLAP else low), min(distances)


def _union(speeds: list[list[float]], members: list[int]) -> list[float]:
    """Union of the speed intervals of ``members``."""
    return [
        min(speeds[c][0] for c in members),
        max(speeds[c][1] for c in members),
        min(speeds[c][2] for c in members),
        max(speeds[c][3] for c in members),
    ]


def _merge_group(
    out: Columns,
    members: list[int],
    ego_speeds: list[list[float]],
    other_speeds: list[list[float]],
) -> None:
    """Give every row of one group the group's worst case."""
    rows = [out.rows[c] for c in members]
    lon = _position([r.lon_position for r in rows], [r.lon_distance_m for r in rows])
    lat = _position([r.lat_position for r in rows], [r.lat_distance_m for r in rows])
    ego_correct = all(r.ego_correct for r in rows)
    other_correct = any(r.other_correct for r in rows)
    enter_leave = (
        min(r.ego_enter_m for r in rows),
        max(r.ego_leave_m for r in rows),
        min(r.other_enter_m for r in rows),
        max(r.other_leave_m for r in rows),
    )
    ego, other = _union(ego_speeds, members), _union(other_speeds, members)
    for c, r in zip(members, rows, strict=True):
        r.lon_position, r.lon_distance_m = lon
        r.lat_position, r.lat_distance_m = lat
        r.ego_correct = ego_correct
        r.other_correct = other_correct
        r.ego_enter_m, r.ego_leave_m, r.other_enter_m, r.other_leave_m = enter_leave
        ego_speeds[c] = ego
        other_speeds[c] = other
