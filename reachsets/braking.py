"""The trajectory the ego could still drive: braking from its current state along its path.

The reference supervisor rates the *emergency* trajectory (a planned stop), so that a safe
verdict means the ego can still stop without being hit by any rule-conform vehicle. Road logs
carry only the planned trajectory; ``braking_trajectory`` builds the stop the ego can always
make instead: it keeps its speed for ``dead_time_s`` and then brakes at ``decel_mps2`` to a
standstill, along its path (the plan's waypoints from its current position on, straight on
along the last heading beyond them).

Defaults from the type-approval braking test every passenger car passes (UN Regulation No.
13-H, type-0 test with the engine disconnected): stopping distance ``s <= 0.1 v + 0.0060 v^2``
(``v`` in km/h, ``s`` in m) and mean fully developed deceleration ``>= 6.43 m/s^2``. Read in SI
units, ``0.1 v_kmh = 0.36 s x v`` (a dead time of 0.36 s) and ``0.0060 v_kmh^2 = v^2 / (2 x
6.43 m/s^2)``.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

__all__ = ["BRAKE_DEAD_TIME_S", "BRAKE_DECEL_MPS2", "braking_trajectory"]

#: Deceleration of the braking trajectory (UN R13-H type-0 MFDD) [m/s^2].
BRAKE_DECEL_MPS2 = 6.43
#: Time the ego keeps its speed before braking (UN R13-H: 0.1 v_kmh m = 0.36 s x v) [s].
BRAKE_DEAD_TIME_S = 0.36

_Arrays = tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]


def _distance(
    v0: float, t: NDArray[np.float64], decel: float, dead: float
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Travelled distance and speed at ``t`` (keep ``v0`` for ``dead``, then brake to a stop)."""
    tb = np.clip(t - dead, 0.0, v0 / decel)
    dist = v0 * np.minimum(t, dead) + v0 * tb - 0.5 * decel * tb**2
    speed = np.where(t < dead, v0, np.maximum(v0 - decel * (t - dead), 0.0))
    return dist, speed


def _path_from(
    x0: float, y0: float, path_x: NDArray[np.float64], path_y: NDArray[np.float64]
) -> tuple[NDArray[np.float64], NDArray[np.float64], int]:
    """The path from ``(x0, y0)``: its foot point on the polyline, then the later waypoints.

    Returns:
        Points x, y and the index of the first waypoint after the foot.
    """
    if len(path_x) < 2:  # noqa: PLR2004
        return np.array([x0]), np.array([y0]), len(path_x)
    a = np.stack([path_x[:-1], path_y[:-1]], axis=1)
    d = np.diff(np.stack([path_x, path_y], axis=1), axis=0)
    seg2 = np.maximum(np.sum(d * d, axis=1), 1e-12)
    u = np.clip(np.sum((np.array([x0, y0]) - a) * d, axis=1) / seg2, 0.0, 1.0)
    foot = a + u[:, None] * d
    k = int(np.argmin(np.hypot(foot[:, 0] - x0, foot[:, 1] - y0)))
    return (
        np.concatenate([[x0], path_x[k + 1 :]]),
        np.concatenate([[y0], path_y[k + 1 :]]),
        k + 1,
    )


def braking_trajectory(  # noqa: PLR0917 - the state and the path
    x0_m: float,
    y0_m: float,
    yaw0_rad: float,
    speed_mps: float,
    path_x_m: NDArray[np.float64],
    path_y_m: NDArray[np.float64],
    path_yaw_rad: NDArray[np.float64],
    *,
    decel_mps2: float = BRAKE_DECEL_MPS2,
    dead_time_s: float = BRAKE_DEAD_TIME_S,
    horizon_s: float = 5.0,
    dt_s: float = 0.1,
) -> tuple[_Arrays, NDArray[np.float64]]:
    """Waypoints of a stop from the ego's state along its path.

    Args:
        x0_m: Ego centre x now.
        y0_m: Ego centre y now.
        yaw0_rad: Ego heading now (ENU).
        speed_mps: Ego speed now (its magnitude is used; non-finite reads as 0).
        path_x_m: The path's waypoints x (e.g. the plan's), ``(K,)``; ``K = 0``: straight on.
        path_y_m: Waypoints y, ``(K,)``.
        path_yaw_rad: Waypoint headings, ``(K,)``.
        decel_mps2: Braking deceleration, ``> 0``.
        dead_time_s: Time at constant speed before braking, ``>= 0``.
        horizon_s: Last waypoint time.
        dt_s: Waypoint spacing in time.

    Returns:
        ``(x, y, yaw, speed)`` and the times ``t`` of the waypoints, each ``(M,)``.
    """
    v0 = abs(float(speed_mps)) if np.isfinite(speed_mps) else 0.0
    t = np.round(np.arange(0.0, horizon_s + dt_s / 2, dt_s), 9)
    dist, speed = _distance(v0, t, decel_mps2, dead_time_s)
    px, py, first = _path_from(x0_m, y0_m, path_x_m, path_y_m)
    pyaw = np.concatenate([[yaw0_rad], path_yaw_rad[first:]]) if len(path_x_m) else [yaw0_rad]
    pyaw = np.unwrap(np.asarray(pyaw, dtype=np.float64))
    seg = np.hypot(np.diff(px), np.diff(py))
    s = np.concatenate([[0.0], np.cumsum(seg)])
    # travel direction beyond the path's end: along its last segment, else along the heading
    if len(seg) and seg[-1] > 0:
        ux, uy = (px[-1] - px[-2]) / seg[-1], (py[-1] - py[-2]) / seg[-1]
    else:
        sign = -1.0 if np.isfinite(speed_mps) and speed_mps < 0 else 1.0
        ux, uy = sign * np.cos(pyaw[-1]), sign * np.sin(pyaw[-1])
    beyond = np.maximum(dist - s[-1], 0.0)
    x = np.interp(dist, s, px) + ux * beyond
    y = np.interp(dist, s, py) + uy * beyond
    yaw = np.interp(dist, s, pyaw)
    return (x, y, yaw, speed), t
