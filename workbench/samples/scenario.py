"""The scenario record every writer consumes, and how its topics are laid out."""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Literal

import numpy as np

from workbench.samples.motion import Track

if TYPE_CHECKING:
    from collections.abc import Sequence

    from numpy.typing import NDArray

    from loaders.records import ObjectClass
    from workbench.samples.lanelet_map import MapBuilder
    from workbench.samples.motion import Motion

__all__ = [
    "SIZE_M",
    "EgoKind",
    "ObjectsKind",
    "PlanKind",
    "RosLayout",
    "Scenario",
    "actor",
    "in_range",
]

EgoKind = Literal["odometry", "pose"]
ObjectsKind = Literal["object_array", "predicted", "tracked", "detection3d"]
PlanKind = Literal["path", "trajectory"]


@dataclass(frozen=True, slots=True)
class RosLayout:
    """Which message types a scenario's ROS 2 variants use.

    ROS 1 variants always publish ``derived_object_msgs/ObjectArray`` and ``nav_msgs/Path``
    (the Autoware and vision_msgs 4.x types are ROS 2-only) and no ``/tf``.
    """

    ego: EgoKind
    ego_topic: str
    objects: ObjectsKind
    plan: PlanKind


@dataclass(frozen=True, slots=True)
class Scenario:
    """A complete synthetic drive.

    Attributes:
        name: File stem of every output.
        summary: One paragraph on what a reviewer should see.
        seed: Seed of the generator used for detection confidences.
        t_s: Scenario clock, ``(T,)`` at 20 Hz from 0.
        ego: The ego vehicle (id 0).
        actors: Other traffic participants.
        lane_map: The Lanelet2 map.
        layout: ROS 2 message types and topics.
        road_lanelets: Number of ``road`` lanelets in the map (checked by tests).
    """

    name: str
    summary: str
    seed: int
    t_s: NDArray[np.float64]
    ego: Track
    actors: tuple[Track, ...]
    lane_map: MapBuilder
    layout: RosLayout
    road_lanelets: int

    @property
    def tracks(self) -> tuple[Track, ...]:
        """Ego first, then the actors."""
        return (self.ego, *self.actors)


#: Box sizes ``(length, width, height)`` in metres per class name.
SIZE_M: dict[str, tuple[float, float, float]] = {
    "car": (4.6, 1.9, 1.5),
    "truck": (9.0, 2.5, 3.5),
    "bus": (12.0, 2.55, 3.2),
    "motorcycle": (2.2, 0.8, 1.4),
    "bicycle": (1.8, 0.6, 1.7),
    "pedestrian": (0.6, 0.6, 1.75),
}


def in_range(ego: Motion, other: Motion, range_m: float) -> NDArray[np.bool_]:
    """Samples at which ``other`` is within ``range_m`` of the ego (sensor range), ``(T,)``."""
    return np.hypot(other.x_m - ego.x_m, other.y_m - ego.y_m) <= range_m


def actor(
    rng: np.random.Generator,
    track_id: int,
    cls: ObjectClass,
    motion: Motion,
    lanes: Sequence[int],
    *,
    ego: Motion,
    range_m: float = 100.0,
) -> Track:
    """An object track of standard size, visible within ``range_m`` of the ego.

    The detection confidence is drawn from ``rng`` (uniform 0.8-0.99, 3 decimals).
    """
    return Track.of(
        track_id,
        cls,
        SIZE_M[cls.label],
        motion,
        lanes,
        visible=in_range(ego, motion, range_m),
        confidence=round(float(rng.uniform(0.8, 0.99)), 3),
    )
