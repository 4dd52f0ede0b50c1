"""Synthetic drives for the data-quality checks: an ego and one car, 10 Hz, exact kinematics."""

from __future__ import annotations

import numpy as np

from loaders.records import ActorTable, EgoState, Frame, ObjectClass

T0_NS = 1_000_000_000
DT_NS = 100_000_000
CAR = "7"


def drive(
    x_m: np.ndarray,
    speed_mps: np.ndarray,
    *,
    yaw_rad: np.ndarray | None = None,
    present: np.ndarray | None = None,
    y_m: np.ndarray | None = None,
) -> list[Frame]:
    """Frames of an ego at 10 m/s along y=0 and car ``CAR`` on ``(x_m, y_m)`` at ``speed_mps``.

    ``present``: frames in which the car is observed (default all).
    """
    n = len(x_m)
    yaw = np.zeros(n) if yaw_rad is None else yaw_rad
    y = np.full(n, 3.5) if y_m is None else y_m
    seen = np.ones(n, dtype=bool) if present is None else present
    frames = []
    for k in range(n):
        ego = EgoState(
            x_m=10.0 * k * 0.1,
            y_m=0.0,
            z_m=0.0,
            yaw_rad=0.0,
            speed_mps=10.0,
            accel_mps2=0.0,
            yaw_rate_radps=0.0,
        )
        rows = [k] if seen[k] else []
        actors = ActorTable.from_columns(
            ids=[CAR] * len(rows),
            object_class=[int(ObjectClass.CAR)] * len(rows),
            x_m=x_m[rows],
            y_m=y[rows],
            yaw_rad=yaw[rows],
            vx_mps=speed_mps[rows] * np.cos(yaw[rows]),
            vy_mps=speed_mps[rows] * np.sin(yaw[rows]),
            length_m=[4.5] * len(rows),
            width_m=[1.8] * len(rows),
        )
        frames.append(Frame(index=k, t_ns=T0_NS + k * DT_NS, ego=ego, actors=actors))
    return frames


def braking(
    n: int = 60, v0_mps: float = 15.0, brake_mps2: float = 4.0
) -> tuple[np.ndarray, np.ndarray]:
    """Positions and speeds of a car braking smoothly from ``v0`` after 2 s."""
    t = np.arange(n) * 0.1
    tb = np.clip(t - 2.0, 0.0, v0_mps / brake_mps2)
    speed = v0_mps - brake_mps2 * tb
    x = v0_mps * np.minimum(t, 2.0) + v0_mps * tb - 0.5 * brake_mps2 * tb**2
    x = x + speed * (t - 2.0 - tb).clip(0.0)
    return x, speed
