"""Agents of an unstructured check: a structure of arrays in the ENU map frame.

::

      y ▲   yaw 0 = +x, counter-clockwise positive; yaw_rate > 0 turns left;
        │   (x, y) is the centre of the footprint (length along the heading).
        └──────▶ x

The object type (ad-rss ``ObjectType`` codes, :class:`rss.model.ObjectType`) picks the
motion model: pedestrians (``Pedestrian``, ``ArtificialPedestrian``) or vehicles
(``EgoVehicle``, ``OtherVehicle``, ``ArtificialVehicle``, ``Bicycle``, ``OtherObject``).
``ArtificialObject`` has no model in ad-rss and makes the agent invalid.
"""

from __future__ import annotations

import enum
import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from rss.model import ObjectType
from rss.unstructured.errors import UnstructuredInputError
from rss.unstructured.memory import frozen

if TYPE_CHECKING:
    from collections.abc import Sequence

    from rss.arrays import FloatArray, IntArray

__all__ = ["MotionModel", "UnstructuredAgents", "motion_model"]

_ANGLE_LIMIT_RAD = 2.0 * np.pi


class MotionModel(enum.IntEnum):
    """Trajectory-set model of an object type."""

    INVALID = 0
    VEHICLE = 1
    PEDESTRIAN = 2


_MODEL = np.full(len(ObjectType), MotionModel.VEHICLE, dtype=np.int64)
_MODEL[[ObjectType.Invalid, ObjectType.ArtificialObject]] = MotionModel.INVALID
_MODEL[[ObjectType.Pedestrian, ObjectType.ArtificialPedestrian]] = MotionModel.PEDESTRIAN


#: ``MotionModel.INVALID`` as a plain int (numpy looks attributes up on an enum class).
_INVALID_MODEL = int(MotionModel.INVALID)


def motion_model(object_type: IntArray) -> IntArray:
    """:class:`MotionModel` codes of ad-rss object type codes ``(N,)``."""
    return np.asarray(_MODEL[np.asarray(object_type, dtype=np.int64)])


@dataclass(frozen=True)
class UnstructuredAgents:
    """``N`` traffic participants of one frame (every field ``(N,)``, read-only).

    Attributes:
        object_id: Object ids (memory keys).
        object_type: :class:`rss.model.ObjectType` codes.
        x_m: Centre x (ENU) [m].
        y_m: Centre y [m].
        yaw_rad: Heading [rad], within ±2π.
        speed_min_mps: Lower bound of the speed [m/s], >= 0.
        speed_max_mps: Upper bound of the speed [m/s].
        yaw_rate_radps: Yaw rate [rad/s], positive = turning left.
        steering_angle_rad: Steering angle [rad] (only the ego's is used: drive-away).
        length_m: Footprint length [m].
        width_m: Footprint width [m].
    """

    object_id: IntArray
    object_type: IntArray
    x_m: FloatArray
    y_m: FloatArray
    yaw_rad: FloatArray
    speed_min_mps: FloatArray
    speed_max_mps: FloatArray
    yaw_rate_radps: FloatArray
    steering_angle_rad: FloatArray
    length_m: FloatArray
    width_m: FloatArray

    def __post_init__(self) -> None:
        """Freeze the arrays and check their shapes.

        Raises:
            UnstructuredInputError: Fields of different lengths or not 1-D.
        """
        n = None
        for name, dtype in _DTYPES.items():
            value = getattr(self, name)
            if not (  # a frozen array owning its data is kept (take, concat)
                isinstance(value, np.ndarray)
                and value.dtype == dtype
                and value.flags.owndata
                and not value.flags.writeable
            ):
                value = np.array(value, dtype=dtype)
            if value.ndim != 1 or (n is not None and value.shape[0] != n):
                raise UnstructuredInputError(
                    name, f"must be 1-D of length {n}, got shape {value.shape}"
                )
            n = value.shape[0]
            value.setflags(write=False)
            object.__setattr__(self, name, value)

    def __len__(self) -> int:
        """Number of agents."""
        return len(self.object_id)

    @staticmethod
    def from_rows(rows: Sequence[dict[str, float]]) -> UnstructuredAgents:
        """Build from one mapping per agent (keys = field names; steering, yaw rate default 0)."""
        defaults = {"yaw_rate_radps": 0.0, "steering_angle_rad": 0.0}
        names = UnstructuredAgents.__dataclass_fields__
        return UnstructuredAgents(**{n: [r.get(n, defaults.get(n)) for r in rows] for n in names})  # type: ignore[arg-type]

    @staticmethod
    def concat(parts: Sequence[UnstructuredAgents]) -> UnstructuredAgents:
        """The agents of ``parts``, one after the other."""
        return _checked([np.concatenate([getattr(p, n) for p in parts]) for n in _FIELDS])

    def take(self, index: IntArray) -> UnstructuredAgents:
        """The agents at ``index``."""
        return _checked([getattr(self, n)[index] for n in _FIELDS])

    def _rows(self) -> list[tuple[float, ...]]:
        """Per agent: the object type, then the float fields (:data:`_FLOAT_FIELDS` order)."""
        columns = [self.object_type.tolist()] + [getattr(self, n).tolist() for n in _FLOAT_FIELDS]
        return list(zip(*columns, strict=True))

    def valid(self) -> np.ndarray:
        """``(N,)`` agents ad-rss accepts (finite, angles within ±2π, speeds ordered, a model).

        A few rows are checked one by one (the same tests; no dozen of numpy calls).
        """
        if len(self) <= _ROW_CHECK_MAX:
            return np.array([_valid_row(row) for row in self._rows()], dtype=bool)
        values = np.stack([getattr(self, n) for n in _FLOAT_FIELDS])
        angles = values[_ANGLE_ROWS]
        return np.asarray(
            np.isfinite(values).all(axis=0)
            & (np.abs(angles) <= _ANGLE_LIMIT_RAD).all(axis=0)
            & (self.speed_min_mps >= 0.0)
            & (self.speed_min_mps <= self.speed_max_mps)
            & (self.length_m > 0.0)
            & (self.width_m > 0.0)
            & (motion_model(self.object_type) != _INVALID_MODEL)
        )


def _checked(values: list[np.ndarray]) -> UnstructuredAgents:
    """Agents of fresh arrays (``_FIELDS`` order) derived from checked agents.

    Their dtypes are the fields' and their lengths agree (concatenations or one index of
    every field), so :meth:`UnstructuredAgents.__post_init__`'s checks are skipped; the
    arrays are frozen in place.
    """
    out = object.__new__(UnstructuredAgents)
    for name, value in zip(_FIELDS, values, strict=True):
        object.__setattr__(out, name, frozen(value))
    return out


def _valid_row(row: tuple[float, ...]) -> bool:
    """:meth:`UnstructuredAgents.valid` of one row (``_rows`` order: type, then the floats)."""
    model = _MODEL_CODES[int(row[0])]  # an unknown code raises as in the array test
    if not all(map(math.isfinite, row[1:])):
        return False
    yaw, steering, v_min, v_max, length, width = (row[i] for i in _CHECKED_COLUMNS)
    return (
        abs(yaw) <= _ANGLE_LIMIT_RAD
        and abs(steering) <= _ANGLE_LIMIT_RAD
        and v_min >= 0.0
        and v_min <= v_max
        and length > 0.0
        and width > 0.0
        and model != _INVALID_MODEL
    )


_FIELDS = tuple(UnstructuredAgents.__dataclass_fields__)
_FLOAT_FIELDS = tuple(n for n in _FIELDS if not n.startswith("object"))
_DTYPES = {n: np.float64 if n in _FLOAT_FIELDS else np.int64 for n in _FIELDS}
_MODEL_CODES = _MODEL.tolist()
#: Agents up to which :meth:`UnstructuredAgents.valid` checks row by row.
_ROW_CHECK_MAX = 8
#: Columns of a ``_rows`` row (type first) that :func:`_valid_row` tests beyond finiteness.
_CHECKED_COLUMNS = [
    1 + _FLOAT_FIELDS.index(name)
    for name in (
        "yaw_rad",
        "steering_angle_rad",
        "speed_min_mps",
        "speed_max_mps",
        "length_m",
        "width_m",
    )
]
_ANGLE_ROWS = [_FLOAT_FIELDS.index("yaw_rad"), _FLOAT_FIELDS.index("steering_angle_rad")]
