"""Seeded random unstructured frames (ego + vehicles / pedestrians around it)."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from rss.model import ObjectType
from rss.params import DEFAULT_PEDESTRIAN_DYNAMICS, DEFAULT_VEHICLE_DYNAMICS
from rss.unstructured import UnstructuredAgents

if TYPE_CHECKING:
    from rss.dynamics import RssDynamics

__all__ = ["random_ego", "random_frame"]


def random_ego(rng: np.random.Generator) -> UnstructuredAgents:
    """An ego at the origin with a random speed, yaw rate and steering."""
    speed = float(rng.choice([0.0, rng.uniform(0.0, 15.0)]))
    return UnstructuredAgents.from_rows(
        [
            {
                "object_id": 0,
                "object_type": int(ObjectType.EgoVehicle),
                "x_m": 0.0,
                "y_m": 0.0,
                "yaw_rad": float(rng.uniform(-np.pi, np.pi)),
                "speed_min_mps": speed * float(rng.uniform(0.8, 1.0)),
                "speed_max_mps": speed,
                "yaw_rate_radps": float(rng.uniform(-0.3, 0.3)),
                "steering_angle_rad": float(rng.uniform(-0.5, 0.5)),
                "length_m": 4.5,
                "width_m": 2.0,
            }
        ]
    )


def random_frame(rng: np.random.Generator, n: int) -> tuple[UnstructuredAgents, list[RssDynamics]]:
    """``n`` agents within 60 m: half vehicles, half pedestrians (some standing)."""
    rows, dynamics = [], []
    for i in range(n):
        pedestrian = bool(rng.random() < 0.5)
        top = 2.5 if pedestrian else 15.0
        speed = float(rng.choice([0.0, rng.uniform(0.0, top), rng.uniform(0.0, top)]))
        radius, angle = float(rng.uniform(2.0, 60.0)), float(rng.uniform(-np.pi, np.pi))
        rows.append(
            {
                "object_id": i + 1,
                "object_type": int(
                    ObjectType.Pedestrian if pedestrian else ObjectType.OtherVehicle
                ),
                "x_m": radius * np.cos(angle),
                "y_m": radius * np.sin(angle),
                "yaw_rad": float(rng.uniform(-np.pi, np.pi)),
                "speed_min_mps": speed * float(rng.uniform(0.7, 1.0)),
                "speed_max_mps": speed,
                "yaw_rate_radps": 0.0 if pedestrian else float(rng.uniform(-0.4, 0.4)),
                "steering_angle_rad": 0.0,
                "length_m": 0.6 if pedestrian else float(rng.uniform(3.5, 6.0)),
                "width_m": 0.6 if pedestrian else float(rng.uniform(1.6, 2.5)),
            }
        )
        dynamics.append(DEFAULT_PEDESTRIAN_DYNAMICS if pedestrian else DEFAULT_VEHICLE_DYNAMICS)
    return UnstructuredAgents.from_rows(rows), dynamics
