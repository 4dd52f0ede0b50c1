"""Small-frame path of the structured engine: one frame of a few constellations, row by row.

Called one frame at a time (an on-line monitor, the conformance command, a what-if, a
short clip), the batched engine spends its time in a few hundred numpy calls on arrays of
a handful of rows: the cost is per call, not per constellation. This path evaluates the
rows of one frame with the scalar twins (:mod:`rss.structured.scalar_extract`,
:mod:`rss.structured.scalar_checks`, compiled with mypyc like the scene modules) and
builds the same result arrays at the end. :func:`rss.structured.engine.check_frame`
chooses it by size (:data:`SMALL_FRAME_MAX`).

It covers the common frame: every constellation valid, one per (ego, object, type) key.
Anything else — an invalid row, two rows of one key (merged by ad-rss, and remembered as
one), an empty road area — returns ``None`` and the batched engine takes the frame, so
both paths agree by construction; ``tests/rss/structured/test_small.py`` checks it.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from rss.physics import ACCELERATION_LOWEST_MPS2
from rss.structured.formulas import dynamics_rows
from rss.structured.scalar_checks import check_row
from rss.structured.scalar_extract import (
    Road,
    lane_table,
    object_valid,
    place,
    relative_position,
)
from rss.structured.small_output import Columns, assemble

if TYPE_CHECKING:
    from rss.dynamics import RssDynamics
    from rss.structured.batch import (
        ConstellationBatch,
        DynamicsArrays,
        ObjectArrays,
        RoadAreaArrays,
    )
    from rss.structured.memory import RssMemory
    from rss.structured.small_output import Parts

__all__ = ["SMALL_FRAME_MAX", "check_frame_small"]

#: Largest frame (constellations) :func:`rss.structured.engine.check_frame` evaluates row
#: by row; measured crossover with the batched engine (docs/benchmarks.md).
SMALL_FRAME_MAX = 128

_EGO_VEHICLE, _INVALID_OBJECT = 1, 0
_OPPOSITE, _EGO_PRIO, _UNSTRUCTURED = 2, 3, 6


def _dynamics(dyn: DynamicsArrays) -> list[list[float]]:
    """``(C, 10)`` dynamics rows as lists (fields in :class:`DynamicsArrays` order)."""
    rows: list[list[float]] = dynamics_rows(dyn).T.tolist()
    return rows


class _Objects:
    """The columns of :class:`ObjectArrays` as one int and one float list per row.

    Ints: object id, object type, the ``K`` region lane ids. Floats: region lon min, lon
    max, lat min, lat max (``K`` each), then the speeds lon min, lon max, lat min, lat max.
    """

    def __init__(self, obj: ObjectArrays) -> None:
        self.n_regions: int = obj.region_lane_id.shape[1]
        ids = np.array([obj.object_id, obj.object_type]).T
        self.ints: list[list[int]] = np.concatenate([ids, obj.region_lane_id], axis=1).tolist()
        speeds = np.array(
            [
                obj.speed_lon_min_mps,
                obj.speed_lon_max_mps,
                obj.speed_lat_min_mps,
                obj.speed_lat_max_mps,
            ]
        ).T
        self.floats: list[list[float]] = np.concatenate(
            [
                obj.region_lon_min,
                obj.region_lon_max,
                obj.region_lat_min,
                obj.region_lat_max,
                speeds,
            ],
            axis=1,
        ).tolist()
        bounds = 4 * self.n_regions
        self.lane_rows: list[list[int]] = [row[2:] for row in self.ints]
        self.param_rows: list[list[float]] = [row[:bounds] for row in self.floats]
        self.speed_rows: list[list[float]] = [row[bounds:] for row in self.floats]

    def lanes(self, row: int) -> list[int]:
        """``(K,)`` region lane ids of ``row``."""
        return self.lane_rows[row]

    def params(self, row: int) -> list[float]:
        """Region bounds of ``row`` (lon min, lon max, lat min, lat max; ``K`` each)."""
        return self.param_rows[row]

    def speeds(self, row: int) -> list[float]:
        """Speeds of ``row`` [m/s]: lon min, lon max, lat min, lat max."""
        return self.speed_rows[row]


class _Roads:
    """The road areas of a batch as flat rows; one lane table per run of equal rows."""

    def __init__(self, road: RoadAreaArrays) -> None:
        c, self.n_segments, self.n_lanes = road.lane_id.shape
        ints = np.concatenate(
            [
                road.lane_id.reshape(c, -1),
                road.driving_direction.reshape(c, -1),
                road.segment_type,
            ],
            axis=1,
        )
        floats = np.concatenate(
            [
                road.length_min_m.reshape(c, -1),
                road.length_max_m.reshape(c, -1),
                road.width_min_m.reshape(c, -1),
                road.width_max_m.reshape(c, -1),
                road.before_intersection_m,
                road.after_intersection_m,
            ],
            axis=1,
        )
        self.owner: list[int] = [0]
        if c > 1:  # a frame's rows mostly share their road area: convert each run once
            new = np.ones(c, dtype=np.bool_)
            new[1:] = (ints[1:] != ints[:-1]).any(axis=1) | (floats[1:] != floats[:-1]).any(axis=1)
            self.owner = (np.cumsum(new) - 1).tolist()
            distinct = np.flatnonzero(new)
            ints, floats = ints[distinct], floats[distinct]
        self.ints: list[list[int]] = ints.tolist()
        self.floats: list[list[float]] = floats.tolist()
        self.tables: list[Road | None] = [None] * len(self.ints)

    def table(self, row: int) -> Road | None:
        """Lane table of ``row`` (``None``: empty road area)."""
        if self.n_segments == 0 or self.n_lanes == 0:
            return None
        k = self.owner[row]
        table = self.tables[k]
        if table is None:
            table = lane_table(self.ints[k], self.floats[k], self.n_segments, self.n_lanes)
            self.tables[k] = table
        return table


def _enter_leave(lon_min_m: float, lon_max_m: float, road: Road) -> tuple[float, float]:
    """Distances to enter and leave the intersecting area (``extraction`` rules)."""
    i_min, i_max = road.intersection_min_m, road.intersection_max_m
    enter = i_min - lon_max_m if i_min - lon_max_m >= 1e-3 else 0.0  # noqa: PLR2004
    leave = i_max - lon_min_m if i_max - lon_min_m >= 1e-3 else 0.0  # noqa: PLR2004
    return enter, leave


def _row(  # noqa: PLR0917 - one row of the frame's columns
    c: int,
    ctype: int,
    ego: _Objects,
    other: _Objects,
    ego_roads: _Roads,
    cross_roads: _Roads,
    out: Columns,
) -> bool:
    """Extract one valid row into ``out``; False if the batched engine must take the frame."""
    ego_table = ego_roads.table(c)
    if ego_table is None:
        return False
    ego_p = place(ego.lanes(c), ego.params(c), ego_table)
    intersection = ctype >= _EGO_PRIO
    other_table = cross_roads.table(c) if intersection else ego_table
    if other_table is None:
        return False
    other_p = place(other.lanes(c), other.params(c), other_table)
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
        lat_pos, lat_dist = 2, 0.0
        ego_el = _enter_leave(ego_p.lon_min_m, ego_p.lon_max_m, ego_table)
        other_el = _enter_leave(other_p.lon_min_m, other_p.lon_max_m, other_table)
        enter_leave = (ego_el[0], ego_el[1], other_el[0], other_el[1])
    ego_correct = not ego_p.on_negative_lane
    opposite = ctype == _OPPOSITE
    other_correct = not (other_p.on_positive_lane if opposite else other_p.on_negative_lane)
    out.add_relative(
        (lon_pos, lon_dist, lat_pos, lat_dist, ego_correct), other_correct, enter_leave
    )
    return True


def _resolve(out: Columns, ego_d: list[list[float]], default_ego: RssDynamics) -> None:
    """The frame's proper response (``response.resolve`` for ``F = 1``) into ``out``."""
    lon_resp = left_resp = right_resp = 0
    lon_max, lon_min = default_ego.accel_max_mps2, default_ego.brake_max_mps2
    left_max = right_max = default_ego.lat_accel_max_mps2
    for c, dangerous in enumerate(out.dangerous):
        if not dangerous:
            continue
        d = ego_d[c]
        lon = out.lon_response[c]
        lon_resp = max(lon_resp, lon)
        lon_max = min(lon_max, d[2] if lon == 2 else d[3] if lon == 1 else d[0])  # noqa: PLR2004
        lon_min = max(lon_min, d[1])
        left, right = out.left_response[c], out.right_response[c]
        left_resp, right_resp = max(left_resp, left), max(right_resp, right)
        left_max = min(left_max, d[5] if left == 1 else d[4])
        right_max = min(right_max, d[5] if right == 1 else d[4])
    out.response = (
        not any(out.dangerous),
        (lon_resp, left_resp, right_resp),
        (lon_min, lon_max, ACCELERATION_LOWEST_MPS2, left_max, ACCELERATION_LOWEST_MPS2, right_max),
    )


def check_frame_small(
    batch: ConstellationBatch, default_ego: RssDynamics, memory: RssMemory | None
) -> Parts | None:
    """One frame row by row (see the module docstring), or ``None`` for the batched engine.

    Args:
        batch: ``C`` constellations of one frame (``C >= 1``).
        default_ego: Default ego dynamics (seed of the acceleration restrictions).
        memory: Memory before the frame; ``None`` = fresh start.

    Returns:
        The result's parts and the memory after the frame (see
        :func:`rss.structured.small_output.assemble`), equal to what
        :func:`rss.structured.engine.check_frames` computes for ``F = 1``.
    """
    ctypes: list[int] = batch.constellation_type.tolist()
    ego, other = _Objects(batch.ego), _Objects(batch.other)
    ego_ids = [row[0] for row in ego.ints]
    other_ids = [row[0] for row in other.ints]
    keys: set[tuple[int, int, int]] = set()
    for c, ctype in enumerate(ctypes):
        if (
            not 0 <= ctype < _UNSTRUCTURED
            or ego.ints[c][1] != _EGO_VEHICLE
            or other.ints[c][1] in {_INVALID_OBJECT, _EGO_VEHICLE}
            or ego_ids[c] == other_ids[c]
            or not object_valid(other.lanes(c), other.params(c), other.speeds(c))
            or not object_valid(ego.lanes(c), ego.params(c), ego.speeds(c))
        ):
            return None
        keys.add((ego_ids[c], other_ids[c], ctype))
    if len(keys) != len(ctypes):
        return None
    ego_roads = _Roads(batch.ego_road)
    cross_roads = _Roads(batch.intersecting_road) if max(ctypes) >= _EGO_PRIO else ego_roads
    out = Columns(len(ctypes))
    for c, ctype in enumerate(ctypes):
        if not _row(c, ctype, ego, other, ego_roads, cross_roads, out):
            return None
    ego_d, oth_d = _dynamics(batch.ego_dynamics), _dynamics(batch.other_dynamics)
    for c, ctype in enumerate(ctypes):
        out.add_states(
            check_row(
                ctype,
                (
                    out.lon_position[c],
                    out.lon_distance_m[c],
                    out.lat_position[c],
                    out.lat_distance_m[c],
                    out.ego_correct[c],
                ),
                out.enter_leave[c],
                ego.speeds(c),
                other.speeds(c),
                ego_d[c],
                oth_d[c],
            )
        )
    out.apply_memory(ctypes, ego_ids, other_ids, memory)
    _resolve(out, ego_d, default_ego)
    return assemble(out)
