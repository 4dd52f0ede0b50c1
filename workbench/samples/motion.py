"""Agent trajectories: speed profiles integrated along paths, lane changes, splicing.

Every trajectory is sampled on the scenario clock (20 Hz); object messages use every
second sample (10 Hz).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from workbench.samples.geometry import quintic_step

if TYPE_CHECKING:
    from collections.abc import Sequence

    from numpy.typing import NDArray

    from loaders.records import ObjectClass
    from workbench.samples.geometry import Polyline

__all__ = ["DT_S", "LaneChange", "Motion", "Track", "drive", "splice", "time_axis"]

#: Sample period of the scenario clock (ego odometry rate 20 Hz).
DT_S = 0.05


def time_axis(duration_s: float) -> NDArray[np.float64]:
    """Sample times ``0, DT_S, ...`` up to and including ``duration_s``, ``(T,)``."""
    return np.asarray(np.arange(round(duration_s / DT_S) + 1) * DT_S, dtype=np.float64)


@dataclass(frozen=True, slots=True)
class LaneChange:
    """A smooth lateral move by ``delta_m`` (positive left) over ``duration_s``."""

    t0_s: float
    duration_s: float
    delta_m: float


@dataclass(frozen=True, slots=True)
class Motion:
    """A kinematic trajectory, all arrays ``(T,)``.

    Attributes:
        x_m: Centre x (map frame).
        y_m: Centre y.
        yaw_rad: Body heading, unwrapped.
        speed_mps: Signed speed along the body heading (negative when reversing).
        lane_change: True while the agent is moving between lanes.
    """

    x_m: NDArray[np.float64]
    y_m: NDArray[np.float64]
    yaw_rad: NDArray[np.float64]
    speed_mps: NDArray[np.float64]
    lane_change: NDArray[np.bool_]


def _profile(
    t_s: NDArray[np.float64], v0_mps: float, phases: Sequence[tuple[float, float]]
) -> NDArray[np.float64]:
    """Speed magnitude from piecewise-constant accelerations, clipped at 0."""
    accel = np.zeros_like(t_s)
    for t_start, a in phases:
        accel[t_s >= t_start - 1e-9] = a
    v = np.empty_like(t_s)
    v[0] = v0_mps
    for k in range(1, len(t_s)):
        v[k] = max(0.0, v[k - 1] + accel[k - 1] * DT_S)
    return v


def drive(
    path: Polyline,
    t_s: NDArray[np.float64],
    *,
    s0_m: float,
    v0_mps: float = 0.0,
    phases: Sequence[tuple[float, float]] = (),
    offset_m: float = 0.0,
    lane_changes: Sequence[LaneChange] = (),
    reverse: bool = False,
) -> Motion:
    """Move an agent along ``path`` with a speed profile and optional lane changes.

    Args:
        path: Reference line (e.g. a lane centre line), direction = body forward.
        t_s: Scenario clock, ``(T,)``.
        s0_m: Arc length at ``t_s[0]``.
        v0_mps: Initial speed magnitude.
        phases: ``(t_start_s, accel_mps2)``: the acceleration applied from ``t_start_s`` on.
        offset_m: Initial lateral offset from the path (positive left).
        lane_changes: Smooth lateral moves.
        reverse: Move against the path direction (body keeps the path heading).

    Returns:
        The trajectory.
    """
    v = _profile(t_s, v0_mps, phases)
    ds = np.concatenate([[0.0], (v[1:] + v[:-1]) / 2 * DT_S])
    s = s0_m + (-1.0 if reverse else 1.0) * np.cumsum(ds)
    d = np.full_like(t_s, offset_m)
    moving_laterally = np.zeros(len(t_s), dtype=np.bool_)
    for change in lane_changes:
        d += change.delta_m * quintic_step(t_s, change.t0_s, change.duration_s)
        moving_laterally |= (t_s > change.t0_s) & (t_s < change.t0_s + change.duration_s)
    d_dot = np.gradient(d, DT_S)
    xy = path.pose(s, d)
    lateral_angle = np.arctan2(d_dot, np.maximum(v, 1e-3)) * (-1.0 if reverse else 1.0)
    yaw = path.heading(s) + lateral_angle
    speed = np.hypot(v, d_dot) * (-1.0 if reverse else 1.0)
    return Motion(xy[:, 0], xy[:, 1], yaw, speed, moving_laterally)


def splice(first: Motion, second: Motion, index: int) -> Motion:
    """Take samples ``[:index]`` from ``first`` and ``[index:]`` from ``second``."""

    def cat(a: NDArray[np.float64], b: NDArray[np.float64]) -> NDArray[np.float64]:
        return np.concatenate([a[:index], b[index:]])

    return Motion(
        cat(first.x_m, second.x_m),
        cat(first.y_m, second.y_m),
        np.unwrap(cat(first.yaw_rad, second.yaw_rad)),
        cat(first.speed_mps, second.speed_mps),
        np.concatenate([first.lane_change[:index], second.lane_change[index:]]),
    )


@dataclass(frozen=True, slots=True)
class Track:
    """One agent over the whole scenario, arrays ``(T,)`` on the scenario clock.

    Attributes:
        id: Stable numeric id (ego = 0).
        object_class: Class of the agent.
        length_m: Box length.
        width_m: Box width.
        height_m: Box height.
        motion: Pose and speed over time.
        accel_mps2: Signed longitudinal acceleration (derivative of the signed speed).
        yaw_rate_radps: Derivative of the yaw.
        visible: Whether object messages include the agent at that sample.
        lanes: Ids of the lanelets the agent drives on (outside lane changes).
        confidence: Detection confidence reported in object messages.
    """

    id: int
    object_class: ObjectClass
    length_m: float
    width_m: float
    height_m: float
    motion: Motion
    accel_mps2: NDArray[np.float64]
    yaw_rate_radps: NDArray[np.float64]
    visible: NDArray[np.bool_]
    lanes: tuple[int, ...]
    confidence: float = 1.0

    @classmethod
    def of(
        cls,
        track_id: int,
        object_class: ObjectClass,
        size_m: tuple[float, float, float],
        motion: Motion,
        lanes: Sequence[int],
        *,
        visible: NDArray[np.bool_] | None = None,
        confidence: float = 1.0,
    ) -> Track:
        """Build a track, deriving acceleration and yaw rate from the motion."""
        n = len(motion.x_m)
        return cls(
            id=track_id,
            object_class=object_class,
            length_m=size_m[0],
            width_m=size_m[1],
            height_m=size_m[2],
            motion=motion,
            accel_mps2=np.gradient(motion.speed_mps, DT_S),
            yaw_rate_radps=np.gradient(np.unwrap(motion.yaw_rad), DT_S),
            visible=np.ones(n, dtype=np.bool_) if visible is None else visible,
            lanes=tuple(lanes),
            confidence=confidence,
        )
