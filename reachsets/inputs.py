"""Input records of the reach-set engine: plain frozen dataclasses of read-only numpy arrays.

Conventions: map frame ENU, metres, yaw 0 = +x, counter-clockwise positive::

      y ^
        |   yaw > 0
        |  /
        | /
        +-------> x   (yaw = 0)

The TUM tools use a north-0 heading (``psi = yaw - pi/2``); converting is the adapter's job.
"""

from __future__ import annotations

from dataclasses import dataclass, fields
from typing import TYPE_CHECKING, Any

import numpy as np

from reachsets.errors import InputShapeError

#: The ego's size [m] when a caller of this library gives none: the reference
#: TrajectorySupervisor's simulated vehicle. The workbench always passes the frame's size.
REFERENCE_EGO_LENGTH_M = 4.7
REFERENCE_EGO_WIDTH_M = 2.8

if TYPE_CHECKING:
    from numpy.typing import NDArray

__all__ = [
    "REFERENCE_EGO_LENGTH_M",
    "REFERENCE_EGO_WIDTH_M",
    "EgoTrajectory",
    "ObjectStates",
    "ReachInputs",
    "RightOfWayRule",
    "RoadLane",
    "RoadLayout",
    "TrackBounds",
    "Zone",
    "ZoneKind",
    "ZoneMap",
    "as_frozen",
]


def as_frozen(value: Any, name: str, ndim: int, dtype: Any = np.float64) -> NDArray[Any]:
    """Return ``value`` as a read-only array of ``ndim`` dimensions.

    Args:
        value: Array-like.
        name: Field name used in the error message.
        ndim: Required number of dimensions.
        dtype: Target dtype.

    Returns:
        A read-only contiguous copy.

    Raises:
        InputShapeError: If the dimension count differs.
    """
    out = np.array(value, dtype=dtype, copy=True)
    if out.ndim != ndim:
        raise InputShapeError(name, f"expected {ndim}-d array", out.shape)
    out.flags.writeable = False
    return out


def _check_rows(obj: object, names: tuple[str, ...]) -> int:
    n = len(getattr(obj, names[0]))
    for name in names[1:]:
        if len(getattr(obj, name)) != n:
            raise InputShapeError(name, f"has {len(getattr(obj, name))} rows, expected {n}")
    return n


@dataclass(frozen=True, slots=True)
class EgoTrajectory:
    """The ego's planned trajectory, ``(K,)`` arrays, K >= 1, starting at the current instant.

    Attributes:
        x_m: Waypoint x (vehicle centre).
        y_m: Waypoint y.
        yaw_rad: Heading (ENU).
        speed_mps: Planned speed, used to time the waypoints when ``t_s`` is NaN.
        t_s: Time offset of each waypoint from now; all-NaN means "derive from speed".
        length_m: Ego length.
        width_m: Ego width.
    """

    x_m: NDArray[np.float64]
    y_m: NDArray[np.float64]
    yaw_rad: NDArray[np.float64]
    speed_mps: NDArray[np.float64]
    t_s: NDArray[np.float64]
    length_m: float = REFERENCE_EGO_LENGTH_M
    width_m: float = REFERENCE_EGO_WIDTH_M

    def __post_init__(self) -> None:
        """Freeze arrays and check lengths and finiteness."""
        for name in ("x_m", "y_m", "yaw_rad", "speed_mps", "t_s"):
            object.__setattr__(self, name, as_frozen(getattr(self, name), name, 1))
        n = _check_rows(self, ("x_m", "y_m", "yaw_rad", "speed_mps", "t_s"))
        if n == 0:
            raise InputShapeError("x_m", "an ego trajectory needs at least one point")
        pose = np.stack([self.x_m, self.y_m, self.yaw_rad])
        if not np.all(np.isfinite(pose)):
            raise InputShapeError("x_m/y_m/yaw_rad", "non-finite ego pose")


@dataclass(frozen=True, slots=True)
class ObjectStates:
    """Other vehicles at the current instant, ``(N,)`` arrays.

    Attributes:
        ids: Object ids.
        x_m: Centre x.
        y_m: Centre y.
        yaw_rad: Heading (ENU).
        speed_mps: Speed along the heading (``>= 0``; negative values are clipped to 0, NaN
            reads as 0; an infinite speed is kept, and the engine skips that object).
        length_m: Body length.
        width_m: Body width.
    """

    ids: NDArray[np.str_]
    x_m: NDArray[np.float64]
    y_m: NDArray[np.float64]
    yaw_rad: NDArray[np.float64]
    speed_mps: NDArray[np.float64]
    length_m: NDArray[np.float64]
    width_m: NDArray[np.float64]

    def __post_init__(self) -> None:
        """Freeze arrays, check lengths and clip negative and NaN speeds to 0."""
        for f in fields(self):
            if f.name == "ids":
                ids = np.array([str(i) for i in self.ids], dtype=np.str_)
                object.__setattr__(self, "ids", as_frozen(ids, "ids", 1, ids.dtype))
            else:
                object.__setattr__(self, f.name, as_frozen(getattr(self, f.name), f.name, 1))
        _check_rows(self, tuple(f.name for f in fields(self)))
        speed = np.clip(np.nan_to_num(self.speed_mps, posinf=np.inf, neginf=0.0), 0.0, None)
        object.__setattr__(self, "speed_mps", as_frozen(speed, "speed_mps", 1))

    def __len__(self) -> int:
        """Number of objects."""
        return len(self.ids)

    def take(self, index: NDArray[np.intp]) -> ObjectStates:
        """The objects at ``index`` (``(M,)`` integer positions)."""
        return ObjectStates.rows_of({f.name: getattr(self, f.name) for f in fields(self)}, index)

    @classmethod
    def rows_of(cls, columns: dict[str, NDArray[Any]], index: Any) -> ObjectStates:
        """Rows ``index`` of columns taken from checked ``ObjectStates`` (no re-validation).

        Args:
            columns: Field name -> ``(N,)`` array, each from an ``ObjectStates`` (or a
                concatenation of them).
            index: Integer positions or a slice.

        Returns:
            The objects, with read-only arrays.
        """
        out = object.__new__(cls)
        for name, col in columns.items():
            arr = np.array(col[index])
            arr.flags.writeable = False
            object.__setattr__(out, name, arr)
        return out

    @classmethod
    def of_frozen(cls, columns: dict[str, NDArray[Any]]) -> ObjectStates:
        """Objects made of checked, read-only ``(N,)`` columns as they are (no copy, no check).

        Args:
            columns: Every field name -> its read-only array, values as ``ObjectStates``
                holds them (ids ``str_``, speeds ``>= 0``): the caller has checked them.
        """
        out = object.__new__(cls)
        for name, col in columns.items():
            if col.flags.writeable:
                raise InputShapeError(name, "expected a read-only array", col.shape)
            object.__setattr__(out, name, col)
        return out

    @classmethod
    def empty(cls) -> ObjectStates:
        """No objects."""
        z = np.zeros(0)
        return cls(np.zeros(0, dtype="<U1"), z, z, z, z, z, z)


@dataclass(frozen=True, slots=True)
class TrackBounds:
    """Racing track as left and right bound polylines in driving direction.

    Attributes:
        left_m: Left bound, ``(M, 2)``.
        right_m: Right bound, ``(P, 2)`` (point counts may differ).
    """

    left_m: NDArray[np.float64]
    right_m: NDArray[np.float64]

    def __post_init__(self) -> None:
        """Freeze and check the bounds."""
        for name in ("left_m", "right_m"):
            arr = as_frozen(getattr(self, name), name, 2)
            if arr.shape[0] < 2 or arr.shape[1] != 2:  # noqa: PLR2004
                raise InputShapeError(name, "expected (M >= 2, 2) points", arr.shape)
            object.__setattr__(self, name, arr)


class ZoneKind:
    """Roborace zone types as numbered in the zone JSON."""

    START_FINISH = 0
    TRIGGER = 1
    OVERTAKE_LEFT = 2
    OVERTAKE_RIGHT = 3
    STOP = 4


@dataclass(frozen=True, slots=True)
class Zone:
    """One Roborace zone: a type and a range of indices into the zone map's centre line."""

    kind: int
    zone_id: str
    start_index: int
    end_index: int


@dataclass(frozen=True, slots=True)
class ZoneMap:
    """Roborace Season Alpha zones (see ``rules_roborace.zones_from_json``).

    Attributes:
        centre_m: Centre line the zone indices refer to, ``(C, 2)``.
        zones: The zones.
    """

    centre_m: NDArray[np.float64]
    zones: tuple[Zone, ...]

    def __post_init__(self) -> None:
        """Freeze the centre line."""
        object.__setattr__(self, "centre_m", as_frozen(self.centre_m, "centre_m", 2))


@dataclass(frozen=True, slots=True)
class RoadLane:
    """One lane of a public road as plain geometry.

    Attributes:
        lane_id: Id.
        polygon_m: Lane area as a closed ring, ``(K, 2)``.
        centre_m: Centre line in the driving direction, ``(C, 2)``.
        speed_limit_mps: Speed limit; NaN where unknown.
        in_intersection: Whether the lane lies inside an intersection.
    """

    lane_id: str
    polygon_m: NDArray[np.float64]
    centre_m: NDArray[np.float64]
    speed_limit_mps: float = float("nan")
    in_intersection: bool = False

    def __post_init__(self) -> None:
        """Freeze geometry."""
        object.__setattr__(self, "polygon_m", as_frozen(self.polygon_m, "polygon_m", 2))
        object.__setattr__(self, "centre_m", as_frozen(self.centre_m, "centre_m", 2))


@dataclass(frozen=True, slots=True)
class RightOfWayRule:
    """Vehicles on ``yield_lanes`` must give way to traffic on ``priority_lanes``."""

    priority_lanes: tuple[str, ...]
    yield_lanes: tuple[str, ...]


@dataclass(frozen=True, slots=True)
class RoadLayout:
    """Lane-like public-road geometry for the road rules.

    Attributes:
        lanes: All lanes.
        solid_lines_m: Solid lane markings as polylines, each ``(K, 2)``.
        right_of_way: Right-of-way rules between lanes.
    """

    lanes: tuple[RoadLane, ...]
    solid_lines_m: tuple[NDArray[np.float64], ...] = ()
    right_of_way: tuple[RightOfWayRule, ...] = ()


@dataclass(frozen=True, slots=True)
class ReachInputs:
    """Everything the engine needs for one frame.

    Attributes:
        ego: The ego's trajectory (the one to be rated).
        objects: Other vehicles.
        track: Racing track bounds, if any (trimming, F1/Roborace rules, ``bound``).
        road: Public-road lanes, if any (road rules, trimming to the drivable area).
        zones: Roborace zones, if any (replaces the F1 rules when given).
    """

    ego: EgoTrajectory
    objects: ObjectStates
    track: TrackBounds | None = None
    road: RoadLayout | None = None
    zones: ZoneMap | None = None
