"""Worst-case merging of similar constellations in the small-frame path, one frame.

The row twin of :func:`rss.structured.merge.merge_similar` for the groups it covers:
rows of one ``(ego, object, type)`` key of a non-intersection type whose ego and object
share their dynamics records. Every row of such a group gets the group's worst case
(positions and distances as :func:`rss.structured.merge.merge_position_groups`, ego in
correct lane: all, other: any, distances to enter: min, to leave: max, speed intervals:
union) and is checked as that. Any other group (an intersection type, which ad-rss merges
only for equal intersection lanes, or differing dynamics) is left to the batched engine.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from rss.structured.codes import EGO_PRIORITY, OVERLAP

if TYPE_CHECKING:
    from rss.structured.small_input import Packed
    from rss.structured.small_output import Columns

__all__ = ["merge_rows"]


def merge_rows(
    out: Columns, rows: Packed, keys: list[tuple[int, int, int]], *, unique: bool
) -> tuple[list[list[float]], list[list[float]]] | None:
    """Merge the groups of similar rows of ``out`` in place; speeds per row to check with.

    Args:
        out: The frame's extracted rows (relative positions, distances, lanes).
        rows: The frame's packed input.
        keys: ``(ego id, object id, type)`` per row.
        unique: One row per key (nothing to merge).

    Returns:
        ``(ego speeds, other speeds)`` per row (lon min, lon max, lat min, lat max [m/s],
        merged within groups), or ``None`` if a group must go to the batched engine.
    """
    ego_speeds = [rows.speeds[e] for e in rows.ego]
    other_speeds = [rows.speeds[o] for o in rows.other]
    if unique:
        return ego_speeds, other_speeds
    groups: dict[tuple[int, int, int], list[int]] = {}
    for c, key in enumerate(keys):
        members = groups.get(key)
        if members is None:
            groups[key] = [c]
        else:
            members.append(c)
    for key, members in groups.items():
        if len(members) == 1:
            continue
        if key[2] >= EGO_PRIORITY:
            return None
        first = members[0]
        for c in members:
            if (
                rows.ego_dynamics[c] != rows.ego_dynamics[first]
                or rows.other_dynamics[c] != rows.other_dynamics[first]
            ):
                return None
        _merge_group(out, members, ego_speeds, other_speeds)
    return ego_speeds, other_speeds


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
