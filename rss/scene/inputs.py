"""Inputs and output of scene creation: the ego, the other objects, the scene."""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from rss.arrays import FloatArray, IntArray
    from rss.dynamics import RssDynamics
    from rss.model import Constellation
    from rss.scene.lanegraph import Step

__all__ = ["Scene", "SceneEgo", "SceneObjects", "conservative_stop_m"]


@dataclass(frozen=True)
class SceneEgo:
    """The ego (map frame, ENU).

    Attributes:
        object_id: Id in the constellations.
        x_m: Centre x.
        y_m: Centre y.
        yaw_rad: Heading.
        speed_mps: Speed along the heading.
        length_m: Length.
        width_m: Width.
        dynamics: RSS dynamics.
        route: Planned route as ``(lane, forward)`` steps; empty = predict the routes.
    """

    object_id: int
    x_m: float
    y_m: float
    yaw_rad: float
    speed_mps: float
    length_m: float
    width_m: float
    dynamics: RssDynamics
    route: tuple[Step, ...] = ()


@dataclass(frozen=True)
class SceneObjects:
    """Other objects, ``(N,)`` arrays (map frame).

    Attributes:
        ids: Ids.
        object_type: :class:`rss.model.ObjectType` codes.
        x_m: Centre x.
        y_m: Centre y.
        yaw_rad: Heading.
        vx_mps: Velocity x.
        vy_mps: Velocity y.
        length_m: Length.
        width_m: Width.
        dynamics: RSS dynamics per object.
    """

    ids: IntArray
    object_type: IntArray
    x_m: FloatArray
    y_m: FloatArray
    yaw_rad: FloatArray
    vx_mps: FloatArray
    vy_mps: FloatArray
    length_m: FloatArray
    width_m: FloatArray
    dynamics: tuple[RssDynamics, ...]


@dataclass(frozen=True)
class Scene:
    """Constellations of one frame.

    Attributes:
        constellations: Constellations (several per object at intersections).
        not_relevant: Ids of objects without a constellation (far, off the map, no route).
        ego_on_map: Whether the ego touches a lane.
        road_areas: Per constellation, the map lanes of its road area(s) as
            ``(lane index, p0, p1)``: the window along the lane's point order (fractions of
            its length). Empty for the road-boundary constellations. For display.
    """

    constellations: tuple[Constellation, ...]
    not_relevant: tuple[int, ...]
    ego_on_map: bool
    road_areas: tuple[tuple[tuple[int, float, float], ...], ...] = ()


def conservative_stop_m(speed_mps: float, dyn: RssDynamics) -> float:
    """Stopping distance: accelerate for the response time, then brake_min_correct."""
    rho, a = dyn.response_time_s, dyn.accel_max_mps2
    v = abs(speed_mps) + a * rho
    return (
        abs(speed_mps) * rho + 0.5 * a * rho * rho + v * v / (2.0 * abs(dyn.brake_min_correct_mps2))
    )
