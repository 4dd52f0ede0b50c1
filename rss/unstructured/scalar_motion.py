"""Scalar twins of the motion kernels of :mod:`rss.unstructured.kinematics` (one point at a time).

The small-frame path of the set builders (:mod:`rss.unstructured.vehicle_small`,
:mod:`rss.unstructured.pedestrian_small`) computes the trajectory points of a few agents
with plain floats instead of a hundred small numpy calls; compiled with mypyc
(:mod:`rss.compiled`) these run at C speed; :func:`corner_table` gives the footprint
corners of those points (:func:`rss.unstructured.kinematics.footprints`). Every function
performs the same IEEE operations in the same order as its array twin and picks the
branch the twin's ``np.where`` picks, so both give the same floats (``math.sin``/
``math.cos`` are the C library's, as numpy's float64 ``sin``/``cos`` on the supported
platforms; the tests of ``tests/rss/unstructured/test_small.py`` check the equality to
the bit).
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Final

import numpy as np

from rss.physics import (
    ACCELERATION_PRECISION,
    DISTANCE_MAX_M,
    DISTANCE_PRECISION,
    DURATION_PRECISION,
    SPEED_PRECISION,
)
from rss.structured.scalar_physics import accelerated_limited_movement

if TYPE_CHECKING:
    from rss.arrays import FloatArray
    from rss.unstructured.agents import UnstructuredAgents
    from rss.unstructured.batch import AgentDynamics

__all__ = [
    "ANGULAR_VELOCITY_PRECISION",
    "DYNAMICS_COLUMNS",
    "arc",
    "corner_table",
    "corners_of",
    "drive",
    "finish",
    "is_negative_zero",
    "pedestrian_move",
    "phase_grid",
    "step_accelerations",
    "time_in_movement",
    "time_to_stop",
]

#: The precisions of :mod:`rss.physics` as compiled constants (mypyc reads a ``Final``
#: float natively; an imported name is a dictionary lookup per use).
_AP: Final = ACCELERATION_PRECISION
_DISTANCE_MAX_M: Final = DISTANCE_MAX_M
_DP: Final = DURATION_PRECISION
_P: Final = DISTANCE_PRECISION
_SP: Final = SPEED_PRECISION

#: The ``AgentDynamics`` fields the point-by-point set builders read, in their column order.
DYNAMICS_COLUMNS = (
    "response_time_s",
    "max_speed_mps",
    "accel_max_mps2",
    "brake_max_mps2",
    "brake_min_mps2",
)

#: ad-physics ``AngularVelocity`` precision [rad/s] (:mod:`rss.unstructured.kinematics`).
ANGULAR_VELOCITY_PRECISION: Final = 1e-3


def is_negative_zero(value: float) -> bool:
    """``value`` is ``-0.0`` (the array twins may turn it into ``+0.0`` on some paths)."""
    return value == 0.0 and math.copysign(1.0, value) < 0.0


def time_to_stop(
    speed_mps: float, response_time_s: float, max_speed_mps: float, accel: float, brake: float
) -> float:
    """:func:`rss.unstructured.kinematics.time_to_stop` of one agent [s]."""
    v_rt, _ = accelerated_limited_movement(speed_mps, max_speed_mps, accel, response_time_s)
    if abs(v_rt - 0.0) < _SP:
        return 0.0
    return response_time_s + v_rt / -brake


def time_in_movement(speed_mps: float, accel_mps2: float, duration_s: float) -> float:
    """:func:`rss.unstructured.kinematics.time_in_movement` of one point [s]."""
    if not accel_mps2 < 0.0:
        return duration_s
    stop = 0.0 if abs(speed_mps - 0.0) < _SP else speed_mps / -accel_mps2
    return stop if duration_s - stop >= _DP else duration_s


def step_accelerations(low: float, high: float, steps: int) -> list[float]:
    """One agent's column of :func:`rss.unstructured.vehicle_batch.step_accelerations_batch`."""
    out = []
    width = (high - low) / (1.0 + steps)
    for k in range(1, steps + 1):
        value = low + width * float(k)
        out.append(value if high - value >= _AP else high)
    out.append(high)
    return out


def phase_grid(longest_s: float, step_s: float) -> list[float]:
    """Step ends of a phase (``rss.unstructured.kinematics._phase_grid`` of its longest row)."""
    grid = [0.0]
    while grid[-1] < longest_s and longest_s - grid[-1] >= _DP:
        grid.append(grid[-1] + step_s)
    return grid


def _radius(speed_mps: float, rate_radps: float, min_radius_m: float) -> tuple[float, bool]:
    """``(radius [m], on a circle)`` of the arc kernels (turning or below the minimal radius)."""
    turning = not abs(rate_radps - 0.0) < ANGULAR_VELOCITY_PRECISION
    radius = speed_mps / rate_radps if turning else _DISTANCE_MAX_M
    if min_radius_m - abs(radius) >= _P:
        return (min_radius_m if radius >= 0.0 else -min_radius_m), True
    return radius, turning


def arc(  # noqa: PLR0917  (one point of a kernel over arrays)
    x_m: float,
    y_m: float,
    yaw_rad: float,
    speed_mps: float,
    rate_radps: float,
    accel_mps2: float,
    duration_s: float,
    max_speed_mps: float,
    min_radius_m: float,
) -> tuple[float, float, float]:
    """End pose ``(x, y, yaw)`` of :func:`rss.unstructured.kinematics.vehicle_arc` of one point."""
    if abs(duration_s - 0.0) < _DP:
        return x_m, y_m, yaw_rad
    _, dist = accelerated_limited_movement(speed_mps, max_speed_mps, accel_mps2, duration_s)
    radius, circle = _radius(speed_mps, rate_radps, min_radius_m)
    dpsi = dist / radius
    sin_a, cos_a = math.sin(yaw_rad), math.cos(yaw_rad)
    if not circle:
        return x_m + dist * cos_a, y_m + dist * sin_a, yaw_rad
    ox, oy = x_m - radius * sin_a, y_m + radius * cos_a
    rx, ry = x_m - ox, y_m - oy
    c, s = math.cos(dpsi), math.sin(dpsi)
    return ox + c * rx - s * ry, oy + s * rx + c * ry, yaw_rad + dpsi


#: Pedestrian ratios with ``|ratio| <= radius / 1000 m`` move straight (kinematics' twin).
PEDESTRIAN_MAX_RADIUS_M: Final = 1000.0


def pedestrian_move(
    pose: tuple[float, float, float], distance_m: float, ratio: float, turning_radius_m: float
) -> tuple[float, float, float]:
    """:func:`rss.unstructured.kinematics.pedestrian_move` of one point: ``(x, y, yaw)``."""
    x, y, yaw = pose
    if abs(distance_m - 0.0) < _P:
        return pose
    if not abs(ratio) > turning_radius_m / PEDESTRIAN_MAX_RADIUS_M:
        return x + math.cos(yaw) * distance_m, y + math.sin(yaw) * distance_m, yaw
    radius = turning_radius_m / ratio
    start = yaw - math.pi / 2.0
    ox, oy = x - math.cos(start) * radius, y - math.sin(start) * radius
    dpsi = distance_m / radius
    return ox + math.cos(start + dpsi) * radius, oy + math.sin(start + dpsi) * radius, yaw + dpsi


#: One phase of :func:`drive`: (step ends of the call, accel [m/s²], duration [s], ratio).
Phase = tuple[list[float], float, float, float]


#: A row between phases of :func:`drive`: ``(Σ chord x, Σ chord y, yaw, speed, yaw rate, steps)``.
State = tuple[float, float, float, float, float, int]


def finish(
    pose: tuple[float, float, float], state: State
) -> tuple[float, float, float, float, float]:
    """``(x, y, yaw, speed, rate)`` at the end of the row's phases."""
    sum_x, sum_y, yaw, speed, rate_end, k = state
    if k == 0:
        return pose[0], pose[1], yaw, speed, rate_end
    return pose[0] + sum_x, pose[1] + sum_y, yaw, speed, rate_end


def drive(state: State, phase: Phase, limits: tuple[float, float, float, float]) -> State:
    """One phase of a row of :func:`rss.unstructured.kinematics.vehicle_integrate`.

    Args:
        state: The row before the phase (start: ``(0, 0, yaw, speed, yaw rate, 0)``).
        phase: Its grid is the one the whole batched call shares (its longest row), so a
            row idles through the steps after its own duration.
        limits: ``(step [s], yaw-rate change [rad/s²], speed cap [m/s], min radius [m])``.

    Steps that neither move nor turn add signed zeros in the twin; they are skipped where
    no sum or heading is zero (where adding a zero cannot change a value) and computed
    otherwise.

    Returns:
        The state after the phase (:func:`finish` gives the end pose).
    """
    step_s, change, vcap, min_r = limits
    sum_x, sum_y, yaw, speed, rate_end, k = state
    grid, accel, duration, ratio = phase
    start = rate_end
    for i in range(len(grid) - 1):
        t0, t1 = grid[i], grid[i + 1]
        active = duration - t0 >= _DP
        if not active and k > 0 and sum_x != 0.0 and sum_y != 0.0 and yaw != 0.0:
            k += len(grid) - 1 - i
            break
        full = t1 - duration < _DP
        dt = step_s if full else duration - t0
        rate = start + change * (t1 if full else duration) * ratio
        if active:
            rate_end = rate
        dist, v1 = 0.0, speed
        if active and not abs(dt - 0.0) < _DP:
            v1, dist = accelerated_limited_movement(speed, vcap, accel, dt)
        radius, circle = _radius(speed, rate, min_r)
        dpsi = dist / radius if circle else 0.0
        half = dpsi / 2.0
        chord = 2.0 * radius * math.sin(half) if circle else dist
        term_x = chord * math.cos(yaw + half)
        term_y = chord * math.sin(yaw + half)
        if k == 0:
            sum_x, sum_y = term_x, term_y
        else:
            sum_x, sum_y = sum_x + term_x, sum_y + term_y
        yaw += dpsi
        speed = v1
        k += 1
    return sum_x, sum_y, yaw, speed, rate_end, k


def corner_table(
    poses: list[list[tuple[float, float, float]]],
    sizes: list[tuple[float, float]],
    front_extra_m: list[float],
) -> list[float]:
    """:func:`rss.unstructured.kinematics.footprints` of ``N`` agents' rows, flat.

    Args:
        poses: Per agent, the ``(x, y, yaw)`` of its ``R`` footprint-table rows.
        sizes: Per agent, ``(length [m], width [m])``.
        front_extra_m: Per agent, the length added in front [m].

    Returns:
        The corners (FR, FL, BL, BR) of the ``(R * 4, N, 2)`` table of
        :func:`rss.unstructured.batch.sets_of_points`, row-major: the same operations in
        the same order as the array twin, so the same floats.
    """
    n = len(poses)
    rows = len(poses[0]) if n else 0
    sides = []  # per agent: front, -half length, half width, -half width
    for j in range(n):
        half_l = sizes[j][0] / 2.0
        half_w = sizes[j][1] / 2.0
        sides.append((half_l + front_extra_m[j], -half_l, half_w, -half_w))
    out = [0.0] * (rows * 8 * n)
    step = 2 * n  # from one corner of a row to the next
    for j in range(n):
        front, back, left, right = sides[j]
        for r in range(rows):
            x, y, yaw = poses[j][r]
            c, s = math.cos(yaw), math.sin(yaw)
            at = (4 * r * n + j) * 2
            _corner(out, at, (x, y, c, s), front, right)  # FR
            _corner(out, at + step, (x, y, c, s), front, left)  # FL
            _corner(out, at + 2 * step, (x, y, c, s), back, left)  # BL
            _corner(out, at + 3 * step, (x, y, c, s), back, right)  # BR
    return out


def _corner(
    out: list[float], at: int, frame: tuple[float, float, float, float], lon: float, lat: float
) -> None:
    """Write the corner at ``(lon, lat)`` of the footprint ``(x, y, cos yaw, sin yaw)``."""
    x, y, c, s = frame
    out[at] = x + c * lon - s * lat
    out[at + 1] = y + s * lon + c * lat


def corners_of(
    poses: list[list[tuple[float, float, float]]], agents: UnstructuredAgents, dyn: AgentDynamics
) -> FloatArray:
    """The ``(R * 4, N, 2)`` corner table of the agents' rows (:func:`corner_table`)."""
    sizes = list(zip(agents.length_m.tolist(), agents.width_m.tolist(), strict=True))
    flat = corner_table(poses, sizes, dyn.front_extra_m.tolist())
    return np.array(flat, dtype=np.float64).reshape(-1, len(poses), 2)
