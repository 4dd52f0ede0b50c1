"""Structure-of-arrays form of all constellations of one frame (the engine's input).

Road areas and occupied regions are ragged; they are padded to the largest size in the
frame: ``C`` constellations, ``R`` road segments, ``L`` lanes per segment, ``K`` occupied
regions per object. Absent lanes / regions have id ``-1``. Built from :mod:`rss.model`
constellations by :func:`rss.structured.stacking.stack_constellations`.
"""

from __future__ import annotations

import dataclasses
import functools
from dataclasses import dataclass
from typing import TYPE_CHECKING, TypeVar

import numpy as np
import numpy.typing as npt

from rss.arrays import FloatArray, IntArray  # noqa: TC001 - dataclass field types, read at run time when compiled (mypyc)
from rss.dynamics import DYNAMICS_KEYS

if TYPE_CHECKING:
    from collections.abc import Sequence

    from rss.dynamics import RssDynamics

__all__ = [
    "ConstellationBatch",
    "DynamicsArrays",
    "ObjectArrays",
    "RoadAreaArrays",
    "int_array",
    "readonly_floats",
    "readonly_ints",
    "stack_dynamics",
    "take_rows",
]

_T = TypeVar("_T")

_DYNAMICS_FIELDS = tuple(DYNAMICS_KEYS.values())


def readonly_ints(array: npt.ArrayLike) -> IntArray:
    """``array`` as a read-only int64 array (a copy)."""
    out: IntArray = np.array(array, dtype=np.int64)
    out.flags.writeable = False
    return out


def int_array(values: list[int]) -> IntArray:
    """A flat list of Python ints as a writeable ``(n,)`` int64 array (no shape discovery)."""
    return np.fromiter(values, np.int64, len(values))


def readonly_floats(array: npt.ArrayLike) -> FloatArray:
    """``array`` as a read-only float64 array (a copy)."""
    out: FloatArray = np.array(array, dtype=np.float64)
    out.flags.writeable = False
    return out


@dataclass(frozen=True)
class DynamicsArrays:
    """RSS dynamics of ``C`` participants.

    Every field is ``(C,)`` float64, named and in units as in :class:`rss.dynamics.RssDynamics`.
    """

    accel_max_mps2: FloatArray
    brake_max_mps2: FloatArray
    brake_min_mps2: FloatArray
    brake_min_correct_mps2: FloatArray
    lat_accel_max_mps2: FloatArray
    lat_brake_min_mps2: FloatArray
    lateral_fluctuation_margin_m: FloatArray
    response_time_s: FloatArray
    max_speed_on_acceleration_mps: FloatArray
    min_longitudinal_safety_distance_m: FloatArray


def stack_dynamics(dynamics: Sequence[RssDynamics]) -> DynamicsArrays:
    """Stack validated dynamics into ``(C,)`` arrays (a shared object is read once)."""
    known: dict[int, int] = {}
    values: list[float] = []
    use: list[int] = []
    for d in dynamics:
        k = known.get(id(d))
        if k is None:
            k = known[id(d)] = len(known)
            values.extend([getattr(d, name) for name in _DYNAMICS_FIELDS])
        use.append(k)
    table = np.array(values, dtype=np.float64).reshape(len(known), len(_DYNAMICS_FIELDS))
    rows = table[int_array(use)]
    columns = enumerate(_DYNAMICS_FIELDS)
    return DynamicsArrays(**{name: readonly_floats(rows[:, k]) for k, name in columns})


@dataclass(frozen=True)
class RoadAreaArrays:
    """Padded road areas of ``C`` constellations.

    Attributes:
        lane_id: ``(C, R, L)`` int64 lane ids, -1 = no lane.
        driving_direction: ``(C, R, L)`` :class:`LaneDrivingDirection` codes.
        length_min_m: ``(C, R, L)``.
        length_max_m: ``(C, R, L)``.
        width_min_m: ``(C, R, L)``.
        width_max_m: ``(C, R, L)``.
        segment_type: ``(C, R)`` :class:`RoadSegmentType` codes, -1 = no segment.
        before_intersection_m: ``(C, R)`` minimum_length_before_intersecting_area.
        after_intersection_m: ``(C, R)`` minimum_length_after_intersecting_area.
    """

    lane_id: IntArray
    driving_direction: IntArray
    length_min_m: FloatArray
    length_max_m: FloatArray
    width_min_m: FloatArray
    width_max_m: FloatArray
    segment_type: IntArray
    before_intersection_m: FloatArray
    after_intersection_m: FloatArray


@dataclass(frozen=True)
class ObjectArrays:
    """One object per constellation.

    Attributes:
        object_id: ``(C,)`` int64.
        object_type: ``(C,)`` :class:`ObjectType` codes.
        region_lane_id: ``(C, K)`` lane id of each occupied region, -1 = none.
        region_lon_min: ``(C, K)`` parametric [0, 1].
        region_lon_max: ``(C, K)``.
        region_lat_min: ``(C, K)``.
        region_lat_max: ``(C, K)``.
        speed_lon_min_mps: ``(C,)``.
        speed_lon_max_mps: ``(C,)``.
        speed_lat_min_mps: ``(C,)`` lateral positive = to the right.
        speed_lat_max_mps: ``(C,)``.
    """

    object_id: IntArray
    object_type: IntArray
    region_lane_id: IntArray
    region_lon_min: FloatArray
    region_lon_max: FloatArray
    region_lat_min: FloatArray
    region_lat_max: FloatArray
    speed_lon_min_mps: FloatArray
    speed_lon_max_mps: FloatArray
    speed_lat_min_mps: FloatArray
    speed_lat_max_mps: FloatArray


@dataclass(frozen=True)
class ConstellationBatch:
    """All constellations of one frame.

    Attributes:
        constellation_type: ``(C,)`` :class:`ConstellationType` codes.
        ego: The ego of each constellation (in ``ego_road``).
        other: The other object (``ego_road`` or ``intersecting_road``).
        ego_dynamics: ``(C,)`` ego dynamics per constellation.
        other_dynamics: ``(C,)`` other dynamics.
        ego_road: Road area along the ego's driving direction.
        intersecting_road: The other's road area (intersection types; may be empty).
    """

    constellation_type: IntArray
    ego: ObjectArrays
    other: ObjectArrays
    ego_dynamics: DynamicsArrays
    other_dynamics: DynamicsArrays
    ego_road: RoadAreaArrays
    intersecting_road: RoadAreaArrays

    @property
    def size(self) -> int:
        """Number of constellations ``C``."""
        return int(self.constellation_type.shape[0])


@functools.cache
def _field_names(cls: type) -> tuple[str, ...]:
    return tuple(f.name for f in dataclasses.fields(cls))


def take_rows(records: _T, rows: IntArray) -> _T:
    """Select constellations ``rows`` from a dataclass of ``(C, ...)`` arrays (recursively)."""
    cls: type = type(records)
    values = {}
    for name in _field_names(cls):
        value = getattr(records, name)
        values[name] = value[rows] if isinstance(value, np.ndarray) else take_rows(value, rows)
    out: _T = cls(**values)
    return out
