"""Ego occupancy: footprint rectangles along the planned trajectory at the reach-set stamps."""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property
from typing import TYPE_CHECKING

import numpy as np
import shapely

from reachsets.footprints import rectangle_corners
from reachsets.small_scalar import interp_poses, unwrapped, waypoint_times

if TYPE_CHECKING:
    from collections.abc import Sequence

    from numpy.typing import NDArray

    from reachsets.inputs import EgoTrajectory

__all__ = [
    "MIN_TIMING_SPEED_MPS",
    "EgoOccupancy",
    "ego_occupancy",
    "ego_occupancy_many",
    "ego_occupancy_scalar",
    "trajectory_times",
]

#: Floor of the mean segment speed when timing waypoints (reference value).
MIN_TIMING_SPEED_MPS = 0.01


@dataclass(frozen=True)
class EgoOccupancy:
    """Ego footprints at the grid stamps, of one frame (``S = (T,)``) or many (``(F, T)``).

    Attributes:
        t_s: Stamps, ``(T,)``.
        x_m: Interpolated centre x, ``S``.
        y_m: Interpolated centre y, ``S``.
        yaw_rad: Interpolated heading, ``S``.
        corners_m: Footprint corners (FL, RL, RR, FR), ``S + (4, 2)``.
    """

    t_s: NDArray[np.float64]
    x_m: NDArray[np.float64]
    y_m: NDArray[np.float64]
    yaw_rad: NDArray[np.float64]
    corners_m: NDArray[np.float64]

    def frame(self, f: int) -> EgoOccupancy:
        """Frame ``f`` of a many-frame occupancy (``(T,)`` poses)."""
        return EgoOccupancy(self.t_s, self.x_m[f], self.y_m[f], self.yaw_rad[f], self.corners_m[f])

    @cached_property
    def polygons(self) -> NDArray[np.object_]:
        """Footprint rectangles, ``S`` shapely polygons (built on first use)."""
        return np.asarray(shapely.polygons(self.corners_m))


def trajectory_times(traj: EgoTrajectory) -> NDArray[np.float64]:
    """Time offset of every waypoint, ``(K,)`` seconds.

    Uses ``traj.t_s`` when it is all finite; otherwise ``t_i = sum(ds_i / v_mean_i)`` with
    ``v_mean`` the mean speed of consecutive points floored at ``MIN_TIMING_SPEED_MPS``, so
    a trajectory that ends at standstill gets very large final stamps (reference behaviour).
    """
    padded = _padded([traj])
    return _waypoint_times(padded)[0, : len(traj.x_m)]


def _padded(trajs: Sequence[EgoTrajectory]) -> dict[str, NDArray[np.float64]]:
    """``x, y, yaw, v, t`` of every trajectory as ``(F, K)`` rows, ``K >= 2``.

    Each row is padded by repeating its last point (which holds the last pose).
    """
    lengths = np.array([len(t.x_m) for t in trajs])
    k = max(2, int(lengths.max()))
    offsets = np.cumsum(lengths) - lengths
    take = offsets[:, None] + np.minimum(np.arange(k)[None, :], lengths[:, None] - 1)
    names = {"x": "x_m", "y": "y_m", "yaw": "yaw_rad", "v": "speed_mps", "t": "t_s"}
    return {
        key: np.concatenate([getattr(t, attr) for t in trajs])[take] for key, attr in names.items()
    }


def _waypoint_times(p: dict[str, NDArray[np.float64]]) -> NDArray[np.float64]:
    """``trajectory_times`` of padded rows, ``(F, K)`` (padding adds zero-length steps)."""
    ds = np.hypot(np.diff(p["x"], axis=1), np.diff(p["y"], axis=1))
    v = np.where(np.isfinite(p["v"]), p["v"], 0.0)
    v_mean = np.maximum((v[:, :-1] + v[:, 1:]) / 2, MIN_TIMING_SPEED_MPS)
    derived = np.zeros(p["x"].shape)
    derived[:, 1:] = np.cumsum(ds / v_mean, axis=1)
    given = np.isfinite(p["t"]).all(axis=1, keepdims=True)
    return np.where(given, p["t"], derived)


def _unwrap_rows(yaw: NDArray[np.float64]) -> NDArray[np.float64]:
    """``np.unwrap`` along each row of ``(F, K)`` headings."""
    d = np.diff(yaw, axis=1)
    dmod = (d + np.pi) % (2 * np.pi) - np.pi
    dmod[(dmod == -np.pi) & (d > 0)] = np.pi
    fix = np.where(np.abs(d) < np.pi, 0.0, dmod - d)
    out = yaw.copy()
    out[:, 1:] += np.cumsum(fix, axis=1)
    return out


def _interp_rows(
    q: NDArray[np.float64], xp: NDArray[np.float64], *fps: NDArray[np.float64]
) -> list[NDArray[np.float64]]:
    """``np.interp(q, xp[f], fp[f])`` for every row ``f`` of ``(F, K)`` arrays, ``(F, T)``.

    ``xp`` rows are non-decreasing; values are held beyond both ends.
    """
    n, k = xp.shape
    j = np.minimum(np.maximum((xp[:, None, :] <= q[None, :, None]).sum(axis=2) - 1, 0), k - 2)
    j += (np.arange(n) * k)[:, None]  # flat index of the interval start
    x0 = xp.ravel()[j]
    span = xp.ravel()[j + 1] - x0
    w = np.clip((q - x0) / np.where(span > 0, span, 1.0), 0.0, 1.0)
    out = []
    for fp in fps:
        f0 = fp.ravel()[j]
        out.append(f0 + w * (fp.ravel()[j + 1] - f0))
    return out


def ego_occupancy(traj: EgoTrajectory, times_s: NDArray[np.float64]) -> EgoOccupancy:
    """Footprints of the ego at ``times_s`` (one frame of ``ego_occupancy_many``)."""
    return ego_occupancy_many([traj], times_s).frame(0)


def ego_occupancy_many(
    trajs: Sequence[EgoTrajectory], times_s: NDArray[np.float64]
) -> EgoOccupancy:
    """Footprints of the ego at ``times_s`` for the plans of ``F`` frames.

    Poses are interpolated linearly in time (held at the ends); the heading is unwrapped
    before interpolation so it never turns the long way round.

    Args:
        trajs: The ego trajectories, one per frame.
        times_s: Stamps, ``(T,)`` seconds from now.

    Returns:
        The occupancy with ``(F, T)`` poses, one rectangle ``ego.length_m x ego.width_m``
        per frame and stamp.
    """
    t = np.asarray(times_s, dtype=np.float64)
    if len(trajs) == 1 and len(trajs[0].x_m) >= 2:  # noqa: PLR2004 - one frame: scalar twins
        x, y, yaw = _poses_scalar(trajs[0], t)
    else:
        p = _padded(trajs)
        x, y, yaw = _interp_rows(t, _waypoint_times(p), p["x"], p["y"], _unwrap_rows(p["yaw"]))
    length = np.array([tr.length_m for tr in trajs])[:, None]
    width = np.array([tr.width_m for tr in trajs])[:, None]
    corners = rectangle_corners(x, y, yaw, length, width)
    return EgoOccupancy(t, x, y, yaw, corners)


def _poses_scalar(
    traj: EgoTrajectory, t: NDArray[np.float64]
) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
    """``(1, T)`` poses of one trajectory of at least 2 points (``small_scalar``, same bits)."""
    xs, ys = np.asarray(traj.x_m, dtype=np.float64), np.asarray(traj.y_m, dtype=np.float64)
    ds = np.hypot(np.diff(xs), np.diff(ys)).tolist()
    wt = waypoint_times(
        ds,
        np.asarray(traj.speed_mps, dtype=np.float64).tolist(),
        np.asarray(traj.t_s, dtype=np.float64).tolist(),
    )
    yaw = unwrapped(np.asarray(traj.yaw_rad, dtype=np.float64).tolist())
    out = np.array(interp_poses(t.tolist(), wt, [xs.tolist(), ys.tolist(), yaw]))
    return out[0:1], out[1:2], out[2:3]


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
