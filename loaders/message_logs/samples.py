"""What the message decoders return: one ego sample or one object list, before framing."""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from loaders.records import ObjectClass, Plan

if TYPE_CHECKING:
    from collections.abc import Sequence

    from numpy.typing import NDArray

__all__ = [
    "CLASS_NAMES",
    "EgoSample",
    "EgoWithObjects",
    "ObjectColumns",
    "PlanSample",
    "class_from_name",
]

#: Free-text class names (vision_msgs ``class_id``, Foxglove metadata, our JSON) → class.
CLASS_NAMES: dict[str, ObjectClass] = {
    "car": ObjectClass.CAR,
    "vehicle": ObjectClass.CAR,
    "van": ObjectClass.CAR,
    "truck": ObjectClass.TRUCK,
    "trailer": ObjectClass.TRUCK,
    "bus": ObjectClass.BUS,
    "motorcycle": ObjectClass.MOTORCYCLE,
    "motorbike": ObjectClass.MOTORCYCLE,
    "bicycle": ObjectClass.BICYCLE,
    "bike": ObjectClass.BICYCLE,
    "cyclist": ObjectClass.BICYCLE,
    "pedestrian": ObjectClass.PEDESTRIAN,
    "person": ObjectClass.PEDESTRIAN,
    "walker": ObjectClass.PEDESTRIAN,
}


def class_from_name(name: str) -> ObjectClass:
    """Map a free-text class name (case-insensitive) to an ``ObjectClass``; unknown otherwise."""
    return CLASS_NAMES.get(name.strip().lower(), ObjectClass.UNKNOWN)


@dataclass(frozen=True, slots=True)
class EgoSample:
    """One decoded ego message (map frame).

    ``speed_mps`` and ``yaw_rate_radps`` are NaN when the message carries no twist; the
    frame assembler then derives them by finite differences. ``heading_from_track`` marks a
    sample without orientation (GNSS fix without IMU): ``yaw_rad`` is NaN and the assembler
    takes the heading of the track through the neighbouring samples. ``size_m`` is the ego's
    ``(length, width, height)`` when the message carries it (OSI host vehicle), else None
    (the ``DEFAULT_EGO_*`` size).
    """

    stamp_ns: int | None
    x_m: float
    y_m: float
    z_m: float
    yaw_rad: float
    speed_mps: float = float("nan")
    yaw_rate_radps: float = float("nan")
    heading_from_track: bool = False
    size_m: tuple[float, float, float] | None = None


@dataclass(frozen=True, slots=True)
class PlanSample:
    """One decoded plan message."""

    stamp_ns: int | None
    plan: Plan


@dataclass(frozen=True, slots=True)
class ObjectColumns:
    """One decoded object message as columns, all ``(N,)``, map frame.

    Attributes:
        stamp_ns: Header stamp, if the message has one.
        ids: Object ids.
        object_class: ``ObjectClass`` values.
        x_m: Centre x.
        y_m: Centre y.
        z_m: Centre z.
        yaw_rad: Heading.
        vx_mps: Map-frame velocity x; NaN when the message has none.
        vy_mps: Map-frame velocity y; NaN when the message has none.
        length_m: Full box length.
        width_m: Full box width.
        height_m: Full box height.
        has_velocity: False when the message type carries no velocity; the assembler
            estimates it per id by finite differences across messages.
        ignored: Entries of the message that are not objects and were left out
            (``MarkerArray`` markers other than box cubes); counted in the drive's notes.
    """

    stamp_ns: int | None
    ids: list[str]
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
    has_velocity: bool = True
    ignored: int = 0

    @classmethod
    def from_rows(
        cls,
        stamp_ns: int | None,
        ids: list[str],
        classes: Sequence[int],
        rows: Sequence[tuple[float, ...]],
        *,
        has_velocity: bool = True,
        ignored: int = 0,
    ) -> ObjectColumns:
        """Build from per-object rows ``(x, y, z, yaw, vx, vy, length, width, height)``."""
        table = np.asarray(rows, dtype=np.float64).reshape(len(rows), 9)
        c = [table[:, k] for k in range(9)]
        return cls(
            stamp_ns=stamp_ns,
            ids=ids,
            object_class=np.asarray(classes, dtype=np.int8),
            x_m=c[0],
            y_m=c[1],
            z_m=c[2],
            yaw_rad=c[3],
            vx_mps=c[4],
            vy_mps=c[5],
            length_m=c[6],
            width_m=c[7],
            height_m=c[8],
            has_velocity=has_velocity,
            ignored=ignored,
        )


@dataclass(frozen=True, slots=True)
class EgoWithObjects:
    """One message holding the ego and the object list (ASAM OSI ground truth).

    The assembler files ``objects`` under the ego topic (when that topic is an object
    topic of the drive) before it makes the frame of ``ego``, so the frame takes them
    unextrapolated (``match_dt_ns`` 0).
    """

    ego: EgoSample
    objects: ObjectColumns
