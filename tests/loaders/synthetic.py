"""The synthetic drive every loader fixture encodes: one ego and three actors on a straight road.

Ego messages come at ``T0 + k * DT`` (``k < N_FRAMES``); object messages come
``OBJECT_LEAD_NS`` earlier, so every frame matches an object message that is 20 ms old and
extrapolates it. Plans come every fifth frame, 10 ms before the ego message.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

__all__ = [
    "ACTORS",
    "DT_NS",
    "EGO_SPEED",
    "N_FRAMES",
    "OBJECT_LEAD_NS",
    "T0",
    "Actor",
    "actor_state",
    "ego_state",
    "ego_times",
    "object_times",
    "plan_points",
    "plan_times",
]

T0 = 1_700_000_000_000_000_000
DT_NS = 100_000_000
N_FRAMES = 30
OBJECT_LEAD_NS = 20_000_000
EGO_SPEED = 5.0


@dataclass(frozen=True)
class Actor:
    """A constant-velocity actor."""

    id: int
    cls: str  # car | truck | pedestrian
    x0: float
    y0: float
    vx: float
    vy: float
    length: float
    width: float
    height: float

    @property
    def yaw(self) -> float:
        return math.atan2(self.vy, self.vx)


ACTORS: tuple[Actor, ...] = (
    Actor(11, "car", 20.0, 3.5, 8.0, 0.0, 4.5, 1.9, 1.5),
    Actor(12, "truck", 60.0, -3.5, -6.0, 0.0, 10.0, 2.5, 3.5),
    Actor(13, "pedestrian", 30.0, 6.0, 0.0, -1.0, 0.6, 0.6, 1.8),
)


def ego_times() -> list[int]:
    return [T0 + k * DT_NS for k in range(N_FRAMES)]


def object_times() -> list[int]:
    return [t - OBJECT_LEAD_NS for t in ego_times()]


def plan_times() -> list[int]:
    return [t - 10_000_000 for t in ego_times()[::5]]


def ego_state(t_ns: int) -> tuple[float, float, float]:
    """Ego ``(x, y, yaw)`` at ``t_ns``: straight along +x at 5 m/s."""
    return EGO_SPEED * (t_ns - T0) / 1e9, 0.0, 0.0


def actor_state(actor: Actor, t_ns: int) -> tuple[float, float]:
    """Actor centre ``(x, y)`` at ``t_ns``."""
    s = (t_ns - T0) / 1e9
    return actor.x0 + actor.vx * s, actor.y0 + actor.vy * s


def plan_points(t_ns: int) -> list[tuple[float, float, float, float]]:
    """Plan ``(x, y, t_offset_s, speed)`` points from the ego position at ``t_ns``."""
    x0, y0, _ = ego_state(t_ns)
    return [(x0 + EGO_SPEED * k, y0, float(k), EGO_SPEED) for k in range(6)]
