"""Ego occupancy: footprint rectangles along the planned trajectory at the reach-set stamps."""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property
from typing import TYPE_CHECKING

import numpy as np
import shapely

from reachsets.footprints import rectangle_corners

if TYPE_CHECKING:
    from numpy.typing import NDArray

    from reachsets.inputs import EgoTrajectory

__all__ = [
    "MIN_TIMING_SPEED_MPS",
    "EgoOccupancy",
    "ego_occupancy",
    "ego_occupancy_scalar",
    "trajectory_times",
]

#: Floor of the mean segment speed when timing waypoints (reference value).
MIN_TIMING_SPEED_MPS = 0.01


@dataclass(frozen=True)
class EgoOccupancy:
    """Ego footprints at the grid stamps.

    Attributes:
        t_s: Stamps, ``(T,)``.
        x_m: Interpolated centre x, ``(T,)``.
        y_m: Interpolated centre y, ``(T,)``.
        yaw_rad: Interpolated heading, ``(T,)``.
        corners_m: Footprint corners (FL, RL, RR, FR), ``(T, 4, 2)``.
    """

    t_s: NDArray[np.float64]
    x_m: NDArray[np.float64]
    y_m: NDArray[np.float64]
    yaw_rad: NDArray[np.float64]
    corners_m: NDArray[np.float64]

    @cached_property
    def polygons(self) -> NDArray[np.object_]:
        """Footprint rectangles, ``(T,)`` shapely polygons (built on first use)."""
        return np.asarray(shapely.polygons(self.corners_m))


def trajectory_times(traj: EgoTrajectory) -> NDArray[np.float64]:
    """Time offset of every waypoint, ``(K,)`` seconds.

    Uses ``traj.t_s`` when it is all finite; otherwise ``t_i = sum(ds_i / v_mean_i)`` with
    ``v_mean`` the mean speed of consecutive points floored at ``MIN_TIMING_SPEED_MPS``, so
    a trajectory that ends at standstill gets very large final stamps (reference behaviour).
    """
    if np.all(np.isfinite(traj.t_s)):
        return np.asarray(traj.t_s, dtype=np.float64)
    ds = np.hypot(np.diff(traj.x_m), np.diff(traj.y_m))
    v = np.nan_to_num(np.asarray(traj.speed_mps, dtype=np.float64))
    v_mean = np.maximum((v[:-1] + v[1:]) / 2, MIN_TIMING_SPEED_MPS)
    return np.concatenate([[0.0], np.cumsum(ds / v_mean)])


def ego_occupancy(traj: EgoTrajectory, times_s: NDArray[np.float64]) -> EgoOccupancy:
    """Footprints of the ego at ``times_s``.

    Poses are interpolated linearly in time (held at the ends); the heading is unwrapped
    before interpolation so it never turns the long way round.

    Args:
        traj: The ego trajectory.
        times_s: Stamps, ``(T,)`` seconds from now.

    Returns:
        The occupancy, one rectangle ``ego.length_m x ego.width_m`` per stamp.
    """
    t_wp = trajectory_times(traj)
    yaw_unwrapped = np.unwrap(traj.yaw_rad)
    x = np.interp(times_s, t_wp, traj.x_m)
    y = np.interp(times_s, t_wp, traj.y_m)
    yaw = np.interp(times_s, t_wp, yaw_unwrapped)
    corners = rectangle_corners(x, y, yaw, traj.length_m, traj.width_m)
    return EgoOccupancy(np.asarray(times_s, dtype=np.float64), x, y, yaw, corners)


def _interp_scalar(t: float, ts: list[float], vs: list[float]) -> float:
    if t <= ts[0]:
        return vs[0]
    for i in range(1, len(ts)):
        if t <= ts[i]:
            span = ts[i] - ts[i - 1]
            w = 0.0 if span == 0 else (t - ts[i - 1]) / span
            return vs[i - 1] + w * (vs[i] - vs[i - 1])
    return vs[-1]


def ego_occupancy_scalar(
    traj: EgoTrajectory, times_s: list[float]
) -> list[list[tuple[float, float]]]:
    """Slow, obvious reference of ``ego_occupancy``: corner lists (FL, RL, RR, FR) per stamp."""
    xs = [float(v) for v in traj.x_m]
    ys = [float(v) for v in traj.y_m]
    if all(math.isfinite(float(v)) for v in traj.t_s):
        ts = [float(v) for v in traj.t_s]
    else:
        ts = [0.0]
        for i in range(1, len(xs)):
            ds = math.hypot(xs[i] - xs[i - 1], ys[i] - ys[i - 1])
            vm = (float(traj.speed_mps[i - 1]) + float(traj.speed_mps[i])) / 2
            ts.append(ts[-1] + ds / max(vm, MIN_TIMING_SPEED_MPS))
    yaws = [float(traj.yaw_rad[0])]
    for raw in traj.yaw_rad[1:]:
        d = (float(raw) - yaws[-1] + math.pi) % (2 * math.pi) - math.pi
        yaws.append(yaws[-1] + d)
    out = []
    for t in times_s:
        x = _interp_scalar(t, ts, xs)
        y = _interp_scalar(t, ts, ys)
        yaw = _interp_scalar(t, ts, yaws)
        c, s = math.cos(yaw), math.sin(yaw)
        hl, hw = traj.length_m / 2, traj.width_m / 2
        corners = [(hl, hw), (-hl, hw), (-hl, -hw), (hl, -hw)]
        out.append([(x + c * a - s * b, y + s * a + c * b) for a, b in corners])
    return out
