"""Record-oriented rows of a small frame for the row-by-row path (:mod:`rss.structured.small`).

The batched engine reads a :class:`ConstellationBatch` as ~60 padded column arrays; the row
path wants one Python list per distinct object, road area and dynamics record instead.
:class:`Packed` holds them: every distinct item once (a frame's ego, its road area and
its dynamics are shared by all its constellations), and per constellation the index of
its items.

:func:`rss.structured.stacking.stack_constellations` keeps the rows it collects anyway
with the batch for frames of at most :data:`SMALL_FRAME_MAX` constellations
(:func:`remember`, the last :data:`_KEPT` batches by identity); :func:`packed` packs them
on first use (:func:`pack`); a batch the standstill rule rewrote shares the objects and
road areas of a kept one and reads only its types and dynamics; a batch built otherwise
is read from its arrays (every row then has items of its own). All give the same values:
the arrays are filled from the same rows, and padding (lanes -1, zero bounds) does not
change a lane table or a placement (``tests/rss/structured/test_small.py`` checks each
way against the batched engine).
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Final, Protocol

import numpy as np

from rss.dynamics import DYNAMICS_KEYS

if TYPE_CHECKING:
    from collections.abc import Callable, Sequence

    from rss.dynamics import RssDynamics
    from rss.structured.batch import ConstellationBatch, ObjectArrays, RoadAreaArrays

__all__ = ["SMALL_FRAME_MAX", "Packed", "pack", "packed", "remember"]

#: Largest frame (constellations) :func:`rss.structured.engine.check_frame` evaluates row
#: by row; measured crossover with the batched engine (docs/speed-history.md).
SMALL_FRAME_MAX: Final = 128

_FIELDS: Final = tuple(DYNAMICS_KEYS.values())
_KEPT: Final = 8  # batches whose packing is kept (by identity)
_KEEP: list[tuple[ConstellationBatch, Packed | Callable[[], Packed]]] = []


class Packed:
    """One frame's constellations as distinct items and per-row indices.

    Attributes:
        ctypes: ``C`` :class:`ConstellationType` codes.
        ego: Per row, the index of its ego in the object lists.
        other: Per row, the index of its other object.
        object_id: Per object, its id.
        object_type: Per object, its :class:`ObjectType` code.
        lanes: Per object, the ``K`` lane ids of its regions (-1 = none; ``K >= 1``).
        params: Per object, region lon min, lon max, lat min, lat max (``K`` each, flat).
        speeds: Per object, lon min, lon max, lat min, lat max [m/s].
        ego_road: Per row, the index of its ego road area (-1: empty).
        cross_road: Per row, the index of its intersecting road area (-1: empty).
        road_ints: Per road area, lane ids and driving directions (``(R, L)`` each) and
            segment types (``(R,)``), flat (:func:`rss.structured.scalar_extract.lane_table`).
        road_floats: Per road area, length min, max, width min, max (``(R, L)`` each),
            lengths before and after the intersecting area (``(R,)`` each) [m].
        road_shape: Per road area, ``(R, L)``.
        ego_dynamics: Per row, the index of the ego's dynamics.
        other_dynamics: Per row, the index of the other's dynamics.
        dynamics: Per dynamics record, its ten fields in :class:`DynamicsArrays` order.
    """

    def __init__(self, ctypes: list[int]) -> None:
        """Empty lists for the rows of ``ctypes``."""
        self.ctypes = ctypes
        self.ego: list[int] = []
        self.other: list[int] = []
        self.object_id: list[int] = []
        self.object_type: list[int] = []
        self.lanes: list[list[int]] = []
        self.params: list[list[float]] = []
        self.speeds: list[list[float]] = []
        self.ego_road: list[int] = []
        self.cross_road: list[int] = []
        self.road_ints: list[list[int]] = []
        self.road_floats: list[list[float]] = []
        self.road_shape: list[tuple[int, int]] = []
        self.ego_dynamics: list[int] = []
        self.other_dynamics: list[int] = []
        self.dynamics: list[list[float]] = []


def remember(batch: ConstellationBatch, rows: Packed | Callable[[], Packed]) -> None:
    """Keep ``rows`` (or a callable making them on first use) as the packing of ``batch``.

    The last :data:`_KEPT` batches are kept; a batch only given to the batched engine
    never packs its rows.
    """
    _KEEP.append((batch, rows))
    if len(_KEEP) > _KEPT:
        del _KEEP[0]


def packed(batch: ConstellationBatch) -> Packed:
    """The packing of ``batch``: the one stacking kept, else read from its arrays."""
    for k in range(len(_KEEP) - 1, -1, -1):
        kept, made = _KEEP[k]
        if kept is batch:
            if isinstance(made, Packed):
                return made
            rows = made()
            _KEEP[k] = (batch, rows)
            return rows
    base = _same_places(batch)
    if base is not None:  # the standstill rule's copy: new types and dynamics only
        rows = _with_dynamics(base, batch)
        remember(batch, rows)
        return rows
    rows = Packed(batch.constellation_type.tolist())
    size = len(rows.ctypes)
    _objects(rows, batch.ego)
    _objects(rows, batch.other)
    rows.ego = list(range(size))
    rows.other = list(range(size, 2 * size))
    rows.ego_road = _roads(rows, batch.ego_road)
    rows.cross_road = _roads(rows, batch.intersecting_road)
    _read_dynamics(rows, batch)
    return rows


def _same_places(batch: ConstellationBatch) -> Packed | None:
    """The packing of a kept batch with the very objects and road areas of ``batch``.

    :func:`rss.structured.standstill.apply_standstill` replaces only the types and the
    dynamics of a batch (``dataclasses.replace``): its objects and road areas are the same
    arrays, so their packed rows are too.
    """
    for k in range(len(_KEEP) - 1, -1, -1):
        kept, made = _KEEP[k]
        if (
            kept.ego is batch.ego
            and kept.other is batch.other
            and kept.ego_road is batch.ego_road
            and kept.intersecting_road is batch.intersecting_road
        ):
            if isinstance(made, Packed):
                return made
            rows = made()
            _KEEP[k] = (kept, rows)
            return rows
    return None


def _with_dynamics(base: Packed, batch: ConstellationBatch) -> Packed:
    """``base``'s objects and road areas (shared, never changed), ``batch``'s types and dynamics."""
    rows = Packed(batch.constellation_type.tolist())
    rows.ego, rows.other = base.ego, base.other
    rows.object_id, rows.object_type = base.object_id, base.object_type
    rows.lanes, rows.params, rows.speeds = base.lanes, base.params, base.speeds
    rows.ego_road, rows.cross_road = base.ego_road, base.cross_road
    rows.road_ints, rows.road_floats = base.road_ints, base.road_floats
    rows.road_shape = base.road_shape
    _read_dynamics(rows, batch)
    return rows


def _read_dynamics(rows: Packed, batch: ConstellationBatch) -> None:
    """``batch``'s dynamics columns as distinct records and their index per row."""
    size = len(rows.ctypes)
    columns = [
        np.array([getattr(dyn, name) for name in _FIELDS], dtype=np.float64)
        for dyn in (batch.ego_dynamics, batch.other_dynamics)
    ]
    uses = _dynamics(rows, np.concatenate(columns, axis=1).T)
    rows.ego_dynamics, rows.other_dynamics = uses[:size], uses[size:]


def _dynamics(rows: Packed, table: np.ndarray) -> list[int]:
    """Append the distinct rows of ``table`` (``(n, 10)``) to ``rows.dynamics``.

    Rows of equal bit patterns are one record, as ``merge`` compares them.

    Returns:
        The record of each row.
    """
    bits = np.ascontiguousarray(table).view(np.int64).tolist()
    values = table.tolist()
    known: dict[tuple[int, ...], int] = {}
    out: list[int] = []
    for k, key in enumerate(bits):
        record = known.get(tuple(key))
        if record is None:
            record = known[tuple(key)] = len(rows.dynamics)
            rows.dynamics.append(values[k])
        out.append(record)
    return out


def _objects(rows: Packed, obj: ObjectArrays) -> None:
    """Append every row of ``obj`` as an object of its own."""
    rows.object_id.extend(obj.object_id.tolist())
    rows.object_type.extend(obj.object_type.tolist())
    rows.lanes.extend(obj.region_lane_id.tolist())
    bounds = (obj.region_lon_min, obj.region_lon_max, obj.region_lat_min, obj.region_lat_max)
    rows.params.extend(np.concatenate(bounds, axis=1).tolist())
    speeds = (
        obj.speed_lon_min_mps,
        obj.speed_lon_max_mps,
        obj.speed_lat_min_mps,
        obj.speed_lat_max_mps,
    )
    rows.speeds.extend(np.array(speeds, dtype=np.float64).T.tolist())


def _roads(rows: Packed, road: RoadAreaArrays) -> list[int]:
    """Append the distinct road areas of ``road`` (runs of equal rows); index per row."""
    c, n_segments, n_lanes = road.lane_id.shape
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
    owner = [0]
    if c > 1:  # a frame's rows mostly share their road area: convert each run once
        new = np.ones(c, dtype=np.bool_)
        new[1:] = (ints[1:] != ints[:-1]).any(axis=1) | (floats[1:] != floats[:-1]).any(axis=1)
        owner = (np.cumsum(new) - 1).tolist()
        distinct = np.flatnonzero(new)
        ints, floats = ints[distinct], floats[distinct]
    first = len(rows.road_ints)
    rows.road_ints.extend(ints.tolist())
    rows.road_floats.extend(floats.tolist())
    rows.road_shape.extend([(n_segments, n_lanes)] * len(ints))
    return [first + k for k in owner]


def pack(
    ctypes: list[int],
    objects: tuple[ObjectRows, ObjectRows],
    roads: tuple[RoadRows, RoadRows],
    dynamics: tuple[Sequence[RssDynamics], Sequence[RssDynamics]],
) -> Packed:
    """The packing of a frame from the rows :mod:`rss.structured.stacking` collected.

    Args:
        ctypes: Constellation type codes.
        objects: The ego's and the other's distinct objects and uses.
        roads: The ego's and the intersecting road areas.
        dynamics: The ego's and the other's dynamics per row.
    """
    rows = Packed(ctypes)
    rows.ego = _pack_objects(rows, objects[0])
    rows.other = _pack_objects(rows, objects[1])
    rows.ego_road = _pack_roads(rows, roads[0])
    rows.cross_road = _pack_roads(rows, roads[1])
    known: dict[int, int] = {}
    values: list[RssDynamics] = []
    uses: list[int] = []
    for d in (*dynamics[0], *dynamics[1]):
        k = known.get(id(d))
        if k is None:
            k = known[id(d)] = len(values)
            values.append(d)
        uses.append(k)
    table = np.array([[getattr(d, name) for name in _FIELDS] for d in values], dtype=np.float64)
    distinct = _dynamics(rows, table)
    size = len(ctypes)
    rows.ego_dynamics = [distinct[k] for k in uses[:size]]
    rows.other_dynamics = [distinct[k] for k in uses[size:]]
    return rows


class ObjectRows(Protocol):
    """What :func:`pack` reads of the stacking step's distinct objects (a protocol)."""

    uses: list[int]
    ids: list[int]
    types: list[int]
    speeds: list[float]
    counts: list[int]
    lanes: list[int]
    params: list[float]


class RoadRows(Protocol):
    """What :func:`pack` reads of the stacking step's distinct road segments (a protocol)."""

    sizes: list[int]
    uses: list[int]
    lanes: int
    kinds: list[int]
    lengths: list[float]
    counts: list[int]
    codes: list[int]
    values: list[float]


def _pack_objects(rows: Packed, objects: ObjectRows) -> list[int]:
    """Append the distinct objects; their index per row."""
    first = len(rows.object_id)
    rows.object_id.extend(np.array(objects.ids, dtype=np.int64).tolist())
    rows.object_type.extend(objects.types)
    lanes = np.array(objects.lanes, dtype=np.int64).tolist()
    bounds = np.array(objects.params, dtype=np.float64).tolist()
    speeds = np.array(objects.speeds, dtype=np.float64).tolist()
    at = 0
    for k, count in enumerate(objects.counts):
        if count == 0:
            rows.lanes.append([-1])
            rows.params.append([0.0, 0.0, 0.0, 0.0])
        else:
            rows.lanes.append(lanes[at : at + count])
            region = bounds[4 * at : 4 * (at + count)]
            rows.params.append([region[4 * j + q] for q in range(4) for j in range(count)])
        rows.speeds.append(speeds[4 * k : 4 * k + 4])
        at += count
    return [first + k for k in objects.uses]


def _pack_roads(rows: Packed, roads: RoadRows) -> list[int]:
    """Append the distinct road areas (equal segment sequences); their index per row."""
    starts = [0] * len(roads.counts)
    for k in range(1, len(starts)):
        starts[k] = starts[k - 1] + roads.counts[k - 1]
    values = np.array(roads.values, dtype=np.float64).tolist()
    codes = np.array(roads.codes, dtype=np.int64).tolist()
    lengths = np.array(roads.lengths, dtype=np.float64).tolist()
    known: dict[tuple[int, ...], int] = {}
    out: list[int] = []
    at = 0
    for size in roads.sizes:
        key = tuple(roads.uses[at : at + size])
        at += size
        k = known.get(key, -2)
        if k == -2:  # noqa: PLR2004 - not seen yet
            tables = (starts, codes, values, lengths)
            k = known[key] = -1 if size == 0 else _road(rows, roads, key, tables)
        out.append(k)
    return out


def _road(
    rows: Packed,
    roads: RoadRows,
    segments: tuple[int, ...],
    tables: tuple[list[int], list[int], list[float], list[float]],
) -> int:
    """Append one road area (its segments ``segments``, ``L`` slots each); its index."""
    starts, codes, values, lengths = tables
    n_lanes = roads.lanes
    width = len(segments) * n_lanes
    lane_id, direction = [-1] * width, [0] * width
    metric = [0.0] * (4 * width)
    for r, k in enumerate(segments):
        for j in range(roads.counts[k]):
            lane = starts[k] + j
            slot = r * n_lanes + j
            lane_id[slot] = codes[2 * lane]
            direction[slot] = codes[2 * lane + 1]
            for q in range(4):
                metric[q * width + slot] = values[4 * lane + q]
    rows.road_ints.append(lane_id + direction + [roads.kinds[k] for k in segments])
    before = [lengths[2 * k] for k in segments]
    after = [lengths[2 * k + 1] for k in segments]
    rows.road_floats.append(metric + before + after)
    rows.road_shape.append((len(segments), n_lanes))
    return len(rows.road_ints) - 1
