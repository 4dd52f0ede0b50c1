"""Frame records: what every loader yields and every engine adapter consumes.

All records are frozen dataclasses of read-only numpy arrays (structure of arrays).
Conventions (see DESIGN.md):

- time is integer nanoseconds (``*_ns``);
- positions are in the map frame, ENU, metres; yaw 0 = +x, counter-clockwise positive::

          y (north)
          ^
          |   yaw > 0
          |  /
          | /
          +--------> x (east), yaw = 0

- velocities of actors are given in the map frame (``vx_mps``, ``vy_mps``); the ego speed is
  the signed speed along its heading.
"""

from __future__ import annotations

import enum
from dataclasses import dataclass, field, fields
from typing import TYPE_CHECKING, Any

import numpy as np

if TYPE_CHECKING:
    from numpy.typing import NDArray

__all__ = [
    "DEFAULT_EGO_HEIGHT_M",
    "DEFAULT_EGO_LENGTH_M",
    "DEFAULT_EGO_WIDTH_M",
    "ActorTable",
    "EgoState",
    "Frame",
    "ObjectClass",
    "Plan",
    "PlanKind",
    "freeze",
]

#: The ego's size where the log does not carry it (a mid-size car with mirrors; the size
#: ad-rss' scene creation assumes too). The one default of the whole workbench: every
#: engine and the viewer read the ego's size from the frame (docs/architecture.md).
DEFAULT_EGO_LENGTH_M = 4.5
DEFAULT_EGO_WIDTH_M = 2.0
DEFAULT_EGO_HEIGHT_M = 1.5


class ObjectClass(enum.IntEnum):
    """Object classes; each has its own RSS dynamics and reach-set limits."""

    UNKNOWN = 0
    CAR = 1
    TRUCK = 2
    BUS = 3
    MOTORCYCLE = 4
    BICYCLE = 5
    PEDESTRIAN = 6

    @property
    def label(self) -> str:
        """Lower-case name used in CLI output, TOML tables and Rerun labels."""
        return self.name.lower()


class PlanKind(enum.Enum):
    """What the ego's plan of a frame is (``Frame.plan_kind``).

    Attributes:
        NOMINAL: The trajectory the planner means to drive (every ROS plan topic; the
            ``performance`` trajectory of a ScenarioArchitect log).
        EMERGENCY: A fail-safe trajectory the ego would switch to (the ``emergency``
            trajectory of a ScenarioArchitect log): the reach-set engine's ``auto`` mode
            rates it as it is instead of a stop from the ego's state.
    """

    NOMINAL = "nominal"
    EMERGENCY = "emergency"


def freeze(array: Any, dtype: Any = None) -> NDArray[Any]:
    """Return a read-only contiguous copy-or-view of ``array``.

    Args:
        array: Anything ``np.asarray`` accepts.
        dtype: Optional dtype to convert to.

    Returns:
        A numpy array with ``writeable`` cleared.
    """
    out = np.ascontiguousarray(array, dtype=dtype)
    if out.flags.writeable:
        if out.base is not None and not out.flags.owndata:
            out = out.copy()
        out.flags.writeable = False
    return out


def _freeze_fields(obj: object) -> None:
    for f in fields(obj):  # type: ignore[arg-type]
        value = getattr(obj, f.name)
        if isinstance(value, np.ndarray):
            object.__setattr__(obj, f.name, freeze(value))


@dataclass(frozen=True, slots=True)
class EgoState:
    """Ego vehicle state at one frame (map frame, SI units).

    The size is the log's where it carries one (CommonRoad obstacle shape, ScenarioArchitect
    vehicle), else the ``DEFAULT_EGO_*`` values; ``--rss-params [scene] ego_length`` etc.
    replace it in every frame (``workbench.driver``).
    """

    x_m: float
    y_m: float
    z_m: float
    yaw_rad: float
    speed_mps: float
    accel_mps2: float
    yaw_rate_radps: float
    length_m: float = DEFAULT_EGO_LENGTH_M
    width_m: float = DEFAULT_EGO_WIDTH_M
    height_m: float = DEFAULT_EGO_HEIGHT_M


@dataclass(frozen=True, slots=True)
class ActorTable:
    """Other traffic participants at one frame, one array per field, all shaped ``(N,)``.

    Attributes:
        ids: Stable object ids as strings, ``(N,)`` unicode.
        object_class: ``ObjectClass`` values, ``(N,)`` int8.
        x_m: Centre x in the map frame.
        y_m: Centre y in the map frame.
        z_m: Centre z (box centre height) in the map frame.
        yaw_rad: Heading, ENU, counter-clockwise from +x.
        vx_mps: Velocity x in the map frame.
        vy_mps: Velocity y in the map frame.
        length_m: Box length (along heading).
        width_m: Box width.
        height_m: Box height.
        valid: False where any of the pose/velocity/size values is not finite or out of
            range; an invalid row is reported and skipped by the engines, never fatal.
        match_dt_ns: Frame time minus the stamp of the object message this row was taken
            from (``>= 0`` means the message is older and the row was extrapolated at
            constant velocity by that much).
    """

    ids: NDArray[np.str_]
    object_class: NDArray[np.int8]
    x_m: NDArray[np.float64]
    y_m: NDArray[np.float64]
    z_m: NDArray[np.float64]
    yaw_rad: NDArray[np.float64]
    vx_mps: NDArray[np.float64]
    vy_mps: NDArray[np.float64]
    length_m: NDArray[np.float64]
    width_m: NDArray[np.float64]
    height_m: NDArray[np.float64]
    valid: NDArray[np.bool_]
    match_dt_ns: NDArray[np.int64]

    def __post_init__(self) -> None:
        """Freeze all arrays and check that they share one length."""
        _freeze_fields(self)
        n = len(self.ids)
        for f in fields(self):
            value = getattr(self, f.name)
            if len(value) != n:
                msg = f"ActorTable.{f.name} has {len(value)} rows, ids has {n}"
                raise ValueError(msg)

    def __len__(self) -> int:
        """Number of actors."""
        return len(self.ids)

    @property
    def speed_mps(self) -> NDArray[np.float64]:
        """Speed magnitude, ``(N,)``."""
        return np.hypot(self.vx_mps, self.vy_mps)

    @classmethod
    def empty(cls) -> ActorTable:
        """A table with no actors."""
        f = np.zeros(0, dtype=np.float64)
        return cls(
            ids=np.zeros(0, dtype="<U1"),
            object_class=np.zeros(0, dtype=np.int8),
            x_m=f,
            y_m=f,
            z_m=f,
            yaw_rad=f,
            vx_mps=f,
            vy_mps=f,
            length_m=f,
            width_m=f,
            height_m=f,
            valid=np.zeros(0, dtype=np.bool_),
            match_dt_ns=np.zeros(0, dtype=np.int64),
        )

    @classmethod
    def from_columns(cls, **columns: Any) -> ActorTable:
        """Build a table from array-likes, converting each field to its dtype.

        ``valid`` defaults to "every value finite and sizes positive"; ``match_dt_ns``
        defaults to zeros; ``z_m`` and ``height_m`` default to zeros and 1.5 m.
        """
        n = len(columns["ids"])
        cols = dict(columns)
        cols.setdefault("z_m", np.zeros(n))
        cols.setdefault("height_m", np.full(n, 1.5))
        cols.setdefault("match_dt_ns", np.zeros(n, dtype=np.int64))
        floats = {
            name: np.asarray(cols[name], dtype=np.float64)
            for name in (
                "x_m",
                "y_m",
                "z_m",
                "yaw_rad",
                "vx_mps",
                "vy_mps",
                "length_m",
                "width_m",
                "height_m",
            )
        }
        if "valid" not in cols:
            stacked = np.vstack(list(floats.values())) if n else np.zeros((9, 0))
            cols["valid"] = np.all(np.isfinite(stacked), axis=0) & (
                (floats["length_m"] > 0) & (floats["width_m"] > 0)
            )
        ids = np.asarray(cols["ids"], dtype=np.str_) if n else np.zeros(0, dtype="<U1")
        return cls(
            ids=ids,
            object_class=np.asarray(cols["object_class"], dtype=np.int8),
            valid=np.asarray(cols["valid"], dtype=np.bool_),
            match_dt_ns=np.asarray(cols["match_dt_ns"], dtype=np.int64),
            **floats,
        )


@dataclass(frozen=True, slots=True)
class Plan:
    """The ego's planned trajectory at one frame, ``(K,)`` arrays in the map frame.

    Attributes:
        x_m: Waypoint x.
        y_m: Waypoint y.
        yaw_rad: Waypoint heading (derived from the path where the message has none).
        t_offset_s: Time from the frame stamp to reach the waypoint; NaN where the message
            carries no timing (``nav_msgs/Path``).
        speed_mps: Planned speed at the waypoint; NaN where unknown.
    """

    x_m: NDArray[np.float64]
    y_m: NDArray[np.float64]
    yaw_rad: NDArray[np.float64]
    t_offset_s: NDArray[np.float64]
    speed_mps: NDArray[np.float64]

    def __post_init__(self) -> None:
        """Freeze all arrays."""
        _freeze_fields(self)

    def __len__(self) -> int:
        """Number of waypoints."""
        return len(self.x_m)


@dataclass(frozen=True, slots=True)
class Frame:
    """One evaluation step on the ego clock.

    Attributes:
        index: Frame number, 0-based, dense.
        t_ns: Ego message stamp (log time unless the profile says header time).
        ego: Ego state.
        actors: Other traffic participants.
        plan: Planned trajectory valid at this frame, if the drive has one.
        extras: Format-specific side data of the loader (documented by each loader).
        plan_kind: What ``plan`` is (meaningless without a plan).
    """

    index: int
    t_ns: int
    ego: EgoState
    actors: ActorTable
    plan: Plan | None = None
    extras: dict[str, Any] = field(default_factory=dict)
    plan_kind: PlanKind = PlanKind.NOMINAL
