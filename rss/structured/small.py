"""Small-frame path of the structured engine: one frame of a few constellations, row by row.

Called one frame at a time (an on-line monitor, the conformance command, a what-if, a
short clip), the batched engine spends its time in a few hundred numpy calls on arrays of
a handful of rows: the cost is per call, not per constellation. This path evaluates the
rows of one frame with the scalar twins (:mod:`rss.structured.scalar_extract`,
:mod:`rss.structured.scalar_checks`, compiled with mypyc like the scene modules) from the
record-oriented rows of :mod:`rss.structured.small_input`; the verdicts, the proper
response and the memory are computed eagerly, the result arrays are built when first read
(:mod:`rss.structured.small_result`). :func:`rss.structured.engine.check_frame`
chooses it by size (:data:`SMALL_FRAME_MAX`).

It covers the common frame: every constellation valid; rows of one (ego, object, type) key
(remembered as one) merged into their worst case as the batched engine merges them, for
every type (:mod:`rss.structured.small_merge`). Anything else — an invalid row, an object
outside its road area, an empty road area — returns ``None`` and the batched engine takes
the frame, so both paths agree by construction; ``tests/rss/structured/test_small*.py``
check it.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Final

from rss.physics import ACCELERATION_LOWEST_MPS2
from rss.structured.codes import (
    BRAKE_MIN,
    BRAKE_MIN_CORRECT,
    EGO_PRIORITY,
    EGO_VEHICLE,
    INVALID_OBJECT,
    LAT_BRAKE_MIN,
    OPPOSITE_DIRECTION,
    OVERLAP,
    UNSTRUCTURED,
)
from rss.structured.scalar_checks import check_row
from rss.structured.scalar_extract import (
    Placed,
    Road,
    lane_table,
    object_valid,
    place,
    relative_position,
)
from rss.structured.small_input import SMALL_FRAME_MAX, Packed, packed
from rss.structured.small_merge import merge_rows
from rss.structured.small_output import Columns, Row

if TYPE_CHECKING:
    from rss.dynamics import RssDynamics
    from rss.structured.batch import ConstellationBatch

__all__ = ["SMALL_FRAME_MAX", "check_frame_small"]

_LOWEST_MPS2: Final = ACCELERATION_LOWEST_MPS2


class _Places:
    """Lane tables and placements of one frame, each computed once (the ego's is shared)."""

    def __init__(self, rows: Packed) -> None:
        self.rows = rows
        self.tables: list[Road | None] = [None] * len(rows.road_ints)
        self.n_roads = len(rows.road_ints)
        self.placed: dict[int, Placed] = {}  # by object * n_roads + road

    def table(self, road: int) -> Road | None:
        """Lane table of road area ``road`` (``None``: empty road area)."""
        if road < 0:
            return None
        table = self.tables[road]
        if table is None:
            rows = self.rows
            n_segments, n_lanes = rows.road_shape[road]
            table = lane_table(rows.road_ints[road], rows.road_floats[road], n_segments, n_lanes)
            self.tables[road] = table
        return table

    def place(self, obj: int, road: int, table: Road) -> Placed:
        """Extents of object ``obj`` in road area ``road`` (its lane table ``table``)."""
        key = obj * self.n_roads + road
        placed = self.placed.get(key)
        if placed is None:
            placed = place(self.rows.lanes[obj], self.rows.params[obj], table)
            self.placed[key] = placed
        return placed


def _enter_leave(lon_min_m: float, lon_max_m: float, road: Road) -> tuple[float, float]:
    """Distances to enter and leave the intersecting area (``extraction`` rules)."""
    i_min, i_max = road.intersection_min_m, road.intersection_max_m
    enter = i_min - lon_max_m if i_min - lon_max_m >= 1e-3 else 0.0  # noqa: PLR2004
    leave = i_max - lon_min_m if i_max - lon_min_m >= 1e-3 else 0.0  # noqa: PLR2004
    return enter, leave


def _row(c: int, ctype: int, places: _Places, out: Columns) -> bool:
    """Extract one valid row into ``out``; False if the batched engine must take the frame."""
    rows = places.rows
    ego_road = rows.ego_road[c]
    ego_table = places.table(ego_road)
    if ego_table is None:
        return False
    ego_p = places.place(rows.ego[c], ego_road, ego_table)
    intersection = ctype >= EGO_PRIORITY
    other_road = rows.cross_road[c] if intersection else ego_road
    other_table = places.table(other_road)
    if other_table is None:
        return False
    other_p = places.place(rows.other[c], other_road, other_table)
    if not (ego_p.found and other_p.found):
        return False
    lon_pos, lon_dist = relative_position(
        ego_p.lon_min_m, ego_p.lon_max_m, other_p.lon_min_m, other_p.lon_max_m
    )
    lat_pos, lat_dist = relative_position(
        ego_p.lat_min_m, ego_p.lat_max_m, other_p.lat_min_m, other_p.lat_max_m
    )
    lat_pos = 4 - lat_pos  # InFront <-> AtRight, ..., AtBack <-> AtLeft
    enter_leave = (0.0, 0.0, 0.0, 0.0)
    if intersection:
        ego_i, other_i = ego_table.intersection_min_m, other_table.intersection_min_m
        if not (math.isfinite(ego_i) and math.isfinite(other_i)):
            return False
        lon_pos, lon_dist = relative_position(
            ego_p.lon_min_m - ego_i,
            ego_p.lon_max_m - ego_i,
            other_p.lon_min_m - other_i,
            other_p.lon_max_m - other_i,
        )
        lat_pos, lat_dist = OVERLAP, 0.0
        ego_el = _enter_leave(ego_p.lon_min_m, ego_p.lon_max_m, ego_table)
        other_el = _enter_leave(other_p.lon_min_m, other_p.lon_max_m, other_table)
        enter_leave = (ego_el[0], ego_el[1], other_el[0], other_el[1])
    ego_correct = not ego_p.on_negative_lane
    opposite = ctype == OPPOSITE_DIRECTION
    other_correct = not (other_p.on_positive_lane if opposite else other_p.on_negative_lane)
    out.rows.append(
        Row((lon_pos, lon_dist, lat_pos, lat_dist, ego_correct), other_correct, enter_leave)
    )
    return True


def _resolve(out: Columns, rows: Packed, default_ego: RssDynamics) -> None:
    """The frame's proper response (``response.resolve`` for ``F = 1``) into ``out``."""
    lon_resp = left_resp = right_resp = 0
    lon_max, lon_min = default_ego.accel_max_mps2, default_ego.brake_max_mps2
    left_max = right_max = default_ego.lat_accel_max_mps2
    is_safe = True
    for c, row in enumerate(out.rows):
        if not row.dangerous:
            continue
        is_safe = False
        d = rows.dynamics[rows.ego_dynamics[c]]
        lon = row.lon_response
        lon_resp = max(lon_resp, lon)
        lon_max = min(
            lon_max, d[2] if lon == BRAKE_MIN else d[3] if lon == BRAKE_MIN_CORRECT else d[0]
        )
        lon_min = max(lon_min, d[1])
        left, right = row.left_response, row.right_response
        left_resp, right_resp = max(left_resp, left), max(right_resp, right)
        left_max = min(left_max, d[5] if left == LAT_BRAKE_MIN else d[4])
        right_max = min(right_max, d[5] if right == LAT_BRAKE_MIN else d[4])
    out.response = (
        is_safe,
        (lon_resp, left_resp, right_resp),
        (lon_min, lon_max, _LOWEST_MPS2, left_max, _LOWEST_MPS2, right_max),
    )


def check_frame_small(
    batch: ConstellationBatch,
    default_ego: RssDynamics,
    before: dict[tuple[int, int, int], tuple[bool, bool, int]],
) -> Columns | None:
    """One frame row by row (see the module docstring), or ``None`` for the batched engine.

    Args:
        batch: ``C`` constellations of one frame (``C >= 1``).
        default_ego: Default ego dynamics (seed of the acceleration restrictions).
        before: The memory before the frame by key (``small_output.recall``; empty = fresh
            start).

    Returns:
        The frame's rows, memory after the frame (``memory``, by key) and proper
        response (``response``), equal to what :func:`rss.structured.engine.check_frames`
        computes for ``F = 1``; the arrays are built from them on demand
        (:mod:`rss.structured.small_arrays`).
    """
    rows = packed(batch)
    ctypes = rows.ctypes
    ids, kinds = rows.object_id, rows.object_type
    checked = [False] * len(ids)
    keys: list[tuple[int, int, int]] = []
    for c, ctype in enumerate(ctypes):
        ego, other = rows.ego[c], rows.other[c]
        ego_id, other_id = ids[ego], ids[other]
        if (
            not 0 <= ctype < UNSTRUCTURED
            or kinds[ego] != EGO_VEHICLE
            or kinds[other] == INVALID_OBJECT
            or kinds[other] == EGO_VEHICLE
            or ego_id == other_id
            or not _valid(rows, other, checked)
            or not _valid(rows, ego, checked)
        ):
            return None
        keys.append((ego_id, other_id, ctype))
    places = _Places(rows)
    out = Columns(len(ctypes))
    for c, ctype in enumerate(ctypes):
        if not _row(c, ctype, places, out):
            return None
    unique = len(set(keys)) == len(keys)
    ego_speeds, other_speeds = merge_rows(out, rows, keys, unique=unique)
    for c, ctype in enumerate(ctypes):
        row = out.rows[c]
        row.add_states(
            check_row(
                ctype,
                row.relative(),
                row.enter_leave(),
                ego_speeds[c],
                other_speeds[c],
                rows.dynamics[rows.ego_dynamics[c]],
                rows.dynamics[rows.other_dynamics[c]],
            )
        )
    out.apply_memory(ctypes, keys, before, unique=unique)
    _resolve(out, rows, default_ego)
    return out


def _valid(rows: Packed, obj: int, checked: list[bool]) -> bool:
    """Whether object ``obj`` is valid (``scalar_extract.object_valid``, once per object)."""
    if checked[obj]:
        return True
    if not object_valid(rows.lanes[obj], rows.params[obj], rows.speeds[obj]):
        return False
    checked[obj] = True
    return True
