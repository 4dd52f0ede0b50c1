"""Seeded random unstructured frames (ego + vehicles / pedestrians around it)."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np

from rss.model import ObjectType
from rss.params import DEFAULT_PEDESTRIAN_DYNAMICS, DEFAULT_VEHICLE_DYNAMICS
from rss.unstructured import UnstructuredAgents

if TYPE_CHECKING:
    from rss.dynamics import RssDynamics

__all__ = ["random_case", "random_ego", "random_frame", "random_sequence"]


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


def random_frame(
    rng: np.random.Generator, n: int, pedestrian_share: float = 0.5
) -> tuple[UnstructuredAgents, list[RssDynamics]]:
    """``n`` agents within 60 m: vehicles and pedestrians (some standing).

    Args:
        rng: The generator.
        n: Number of agents.
        pedestrian_share: Probability of a pedestrian (0: vehicles only, 1: pedestrians only).
    """
    rows, dynamics = [], []
    for i in range(n):
        pedestrian = bool(rng.random() < pedestrian_share)
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


def _row(
    oid: int, kind: ObjectType, pose: tuple[float, float, float], speed: float
) -> dict[str, float]:
    pedestrian = kind == ObjectType.Pedestrian
    return {
        "object_id": oid,
        "object_type": int(kind),
        "x_m": pose[0],
        "y_m": pose[1],
        "yaw_rad": pose[2],
        "speed_min_mps": speed,
        "speed_max_mps": speed,
        "length_m": 0.6 if pedestrian else 4.5,
        "width_m": 0.6 if pedestrian else 2.0,
    }


def _wrap(angle: float) -> float:
    return float((angle + np.pi) % (2.0 * np.pi) - np.pi)


def random_sequence(
    rng: np.random.Generator, steps: int, n: int
) -> list[tuple[UnstructuredAgents, UnstructuredAgents, list[RssDynamics]]]:
    """A drive-away sequence: ego and ``n`` close agents, slow or stopped, moving a little.

    Per step each participant keeps its exact position with probability 1/2 (so stored
    drive-away states can persist), otherwise it moves along its heading; speeds switch
    between standing, creeping and slow, and the ego's steering angle is random.
    """
    kinds = [
        ObjectType.Pedestrian if rng.random() < 0.4 else ObjectType.OtherVehicle for _ in range(n)
    ]
    poses = []
    for _ in range(n):
        radius, angle = float(rng.uniform(4.0, 20.0)), float(rng.uniform(-np.pi, np.pi))
        poses.append(
            [radius * np.cos(angle), radius * np.sin(angle), float(rng.uniform(-np.pi, np.pi))]
        )
    ego_pose = [0.0, 0.0, float(rng.uniform(-np.pi, np.pi))]
    out = []
    for _ in range(steps):
        ego_speed = float(rng.choice([0.0, 0.0, 0.05, 1.0, 4.0]))
        ego = _row(0, ObjectType.EgoVehicle, (ego_pose[0], ego_pose[1], ego_pose[2]), ego_speed)
        ego["steering_angle_rad"] = float(rng.choice([0.0, rng.uniform(-0.6, 0.6), np.pi / 2]))
        rows, dynamics = [], []
        for i, kind in enumerate(kinds):
            speed = float(rng.choice([0.0, 0.0, 0.05, 1.0, 3.0]))
            if rng.random() < 0.5:
                step = speed * 0.5 + 0.2
                poses[i][0] += step * np.cos(poses[i][2])
                poses[i][1] += step * np.sin(poses[i][2])
            rows.append(_row(i + 1, kind, (poses[i][0], poses[i][1], poses[i][2]), speed))
            pedestrian = kind == ObjectType.Pedestrian
            dynamics.append(DEFAULT_PEDESTRIAN_DYNAMICS if pedestrian else DEFAULT_VEHICLE_DYNAMICS)
        out.append(
            (UnstructuredAgents.from_rows([ego]), UnstructuredAgents.from_rows(rows), dynamics)
        )
        if rng.random() < 0.5:
            ego_pose[0] += (ego_speed * 0.5 + 0.2) * np.cos(ego_pose[2])
            ego_pose[1] += (ego_speed * 0.5 + 0.2) * np.sin(ego_pose[2])
            ego_pose[2] = _wrap(ego_pose[2] + float(rng.uniform(-0.3, 0.3)))
    return out


def random_case(rng: np.random.Generator, case_id: str) -> dict[str, Any]:
    """A random ``kind: unstructured`` conformance case: ego and one agent of :func:`random_frame`.

    The format's keys (``conformance/rss-cases-format.md``), the default dynamics of the
    agent's type (ego: ``defaults.ego``).
    """
    ego = random_ego(rng)
    agents, _ = random_frame(rng, 1)

    def obj(table: UnstructuredAgents) -> dict[str, object]:
        return {
            "object_type": ObjectType(int(table.object_type[0])).name,
            "x": float(table.x_m[0]),
            "y": float(table.y_m[0]),
            "yaw": float(table.yaw_rad[0]),
            "speed_min": float(table.speed_min_mps[0]),
            "speed_max": float(table.speed_max_mps[0]),
            "yaw_rate": float(table.yaw_rate_radps[0]),
            "steering_angle": float(table.steering_angle_rad[0]),
            "length": float(table.length_m[0]),
            "width": float(table.width_m[0]),
        }

    return {"id": case_id, "kind": "unstructured", "ego": obj(ego), "other": obj(agents)}
