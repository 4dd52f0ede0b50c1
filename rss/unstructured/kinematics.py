"""Motion kernels of the trajectory sets, vectorised over trajectory points ``(M,)``.

ENU map frame, yaw 0 = +x, counter-clockwise positive. A trajectory point is a pose with a
speed and a yaw rate (:class:`Points`). Vehicles move on circles of radius ``v / yaw_rate``
(at least ``vehicle_min_radius``); pedestrians on circles of radius
``pedestrian_turning_radius / ratio`` or straight lines::

          y ▲      circle origin = p + r · (-sin ψ, cos ψ)   (r > 0: turning left)
            │   ╭─╮
            │  /   ╲    after an arc of length d:  Δψ = d / r,
            │ p ──▶ ψ   p' = origin + R(Δψ) (p - origin),  ψ' = ψ + Δψ
            └────────▶ x

Comparisons use ad-physics' tolerances (``rss.physics``). The scalar twins of these kernels
are in :mod:`rss.unstructured.reference_kinematics`.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import TYPE_CHECKING, Any

import numpy as np

from rss.physics import (
    DISTANCE_MAX_M,
    DISTANCE_PRECISION,
    DURATION_PRECISION,
    SPEED_PRECISION,
    accelerated_limited_movement,
    eq,
    ge,
    gt,
    le,
    lt,
    tmax,
    tmin,
)

if TYPE_CHECKING:
    from rss.arrays import FloatArray

#: A float or a float array broadcast against the points (rss.physics kernels take both).
Real = Any

__all__ = [
    "ANGULAR_VELOCITY_PRECISION",
    "CIRCLE_VERTICES",
    "ROW_LOOP_MIN_COLUMNS",
    "Phase",
    "Points",
    "Real",
    "change_ratios",
    "footprints",
    "pedestrian_move",
    "pedestrian_move_timed",
    "running_sum",
    "straight_move",
    "time_in_movement",
    "time_to_stop",
    "vehicle_arc",
    "vehicle_integrate",
]

#: ad-physics ``AngularVelocity`` precision [rad/s].
ANGULAR_VELOCITY_PRECISION = 1e-3
#: Pedestrian ratios with ``|ratio| <= radius / 1000 m`` move straight (ad-rss ``maxRadius``).
PEDESTRIAN_MAX_RADIUS_M = 1000.0
#: Vertices of a standing pedestrian's circle (ad-rss step 2π/20).
CIRCLE_VERTICES = 20


def change_ratios(steps: int) -> tuple[FloatArray, FloatArray]:
    """Yaw-rate (vehicle) or heading (pedestrian) change ratios: right ``[-1, 0)``, left ``(0, 1]``.

    ``steps + 1`` each.
    """
    diff = 2.0 / (2.0 * steps + 2.0)
    k = np.arange(steps + 1)
    return np.asarray(-1.0 + diff * k, dtype=np.float64), np.asarray(
        diff * (k + 1), dtype=np.float64
    )


@dataclass(frozen=True)
class Points:
    """Trajectory points (every field ``(M,)``).

    Attributes:
        x_m: Centre x (ENU) [m].
        y_m: Centre y [m].
        yaw_rad: Heading [rad] (not normalised).
        speed_mps: Speed >= 0 [m/s].
        yaw_rate_radps: Yaw rate, positive = turning left [rad/s].
    """

    x_m: Real
    y_m: FloatArray
    yaw_rad: Real
    speed_mps: FloatArray
    yaw_rate_radps: Real

    def broadcast(self) -> Points:
        """All fields broadcast to their common shape."""
        return Points(
            *np.broadcast_arrays(
                self.x_m, self.y_m, self.yaw_rad, self.speed_mps, self.yaw_rate_radps
            )
        )

    def take(self, mask: np.ndarray, other: Points) -> Points:
        """Elementwise ``where(mask, other, self)``."""
        return Points(
            *(
                np.where(mask, getattr(other, f), getattr(self, f))
                for f in ("x_m", "y_m", "yaw_rad", "speed_mps", "yaw_rate_radps")
            )
        )


def time_to_stop(
    speed_mps: Real,
    response_time_s: Real,
    max_speed_mps: Real,
    accel_mps2: Real,
    brake_mps2: Real,
) -> FloatArray:
    """Time until standstill: ``accel`` during the response time, ``brake`` (< 0) after.

    ad-rss ``calculateTimeToStop`` for ``accel >= 0`` (the only use here).

    Returns:
        Stop time [s], shape of the broadcast inputs.
    """
    v_rt, _ = accelerated_limited_movement(speed_mps, max_speed_mps, accel_mps2, response_time_s)
    standing = eq(v_rt, 0.0, SPEED_PRECISION)
    return np.where(standing, 0.0, response_time_s + v_rt / -np.asarray(brake_mps2))


def time_in_movement(speed_mps: Real, accel_mps2: Real, duration_s: Real) -> FloatArray:
    """``duration`` cut at the standstill time ``v / |a|`` when braking (``getTimeInMovement``)."""
    braking = np.asarray(accel_mps2) < 0.0
    safe_a = np.where(braking, accel_mps2, -1.0)
    stop = np.where(eq(speed_mps, 0.0, SPEED_PRECISION), 0.0, speed_mps / -safe_a)
    return np.where(
        braking, np.where(lt(stop, duration_s, DURATION_PRECISION), stop, duration_s), duration_s
    )


def vehicle_arc(
    p: Points,
    accel_mps2: Real,
    duration_s: Real,
    max_speed_mps: Real,
    min_radius_m: Real,
) -> Points:
    """Drive one arc of constant radius ``v / yaw_rate`` with a constant acceleration.

    ad-rss ``calculateTrajectoryPointOnCircle``; the radius uses the speed at the start.

    Args:
        p: Start points ``(M,)``.
        accel_mps2: Acceleration ``(M,)`` or scalar.
        duration_s: Duration >= 0.
        max_speed_mps: Speed cap of the acceleration.
        min_radius_m: Minimal turning radius.

    Returns:
        The end points (speed updated).
    """
    v1, dist = accelerated_limited_movement(p.speed_mps, max_speed_mps, accel_mps2, duration_s)
    turning = ~eq(p.yaw_rate_radps, 0.0, ANGULAR_VELOCITY_PRECISION)
    safe_rate = np.where(turning, p.yaw_rate_radps, 1.0)
    radius = np.where(turning, p.speed_mps / safe_rate, DISTANCE_MAX_M)
    small = lt(np.abs(radius), min_radius_m, DISTANCE_PRECISION)
    radius = np.where(
        small, np.where(radius >= 0.0, min_radius_m, -np.asarray(min_radius_m)), radius
    )
    dpsi = dist / radius
    sin_a, cos_a = np.sin(p.yaw_rad), np.cos(p.yaw_rad)
    ox, oy = p.x_m - radius * sin_a, p.y_m + radius * cos_a
    rx, ry = p.x_m - ox, p.y_m - oy
    c, s = np.cos(dpsi), np.sin(dpsi)
    x = np.where(turning | small, ox + c * rx - s * ry, p.x_m + dist * cos_a)
    y = np.where(turning | small, oy + s * rx + c * ry, p.y_m + dist * sin_a)
    yaw = np.where(turning | small, p.yaw_rad + dpsi, p.yaw_rad)
    moved = Points(x, y, yaw, v1, np.broadcast_to(p.yaw_rate_radps, x.shape))
    skip = eq(duration_s, 0.0, DURATION_PRECISION) & np.ones(x.shape, dtype=bool)
    return moved.take(skip, p)


#: Columns from which :func:`running_sum` adds row by row (numpy's ``cumsum`` along the
#: first axis walks each column separately, slow on wide arrays).
ROW_LOOP_MIN_COLUMNS = 256


def running_sum(first: FloatArray, steps: FloatArray) -> FloatArray:
    """``[first, first + s_0, first + s_0 + s_1, ...]`` ``(K + 1, M)`` from ``(M,)``, ``(K, M)``.

    The same additions in the same order as ``np.cumsum`` along the first axis (equal to the
    bit); wide arrays are summed one row at a time, which is several times faster.
    """
    if first.shape[0] < ROW_LOOP_MIN_COLUMNS:
        return np.cumsum(np.concatenate((first[None], steps)), axis=0)
    out = np.empty((steps.shape[0] + 1, first.shape[0]))
    out[0] = first
    for k in range(steps.shape[0]):
        np.add(out[k], steps[k], out=out[k + 1])
    return out


def _step_speeds(
    v0: FloatArray, accel: FloatArray, dt: FloatArray, moving: np.ndarray, max_speed_mps: Real
) -> tuple[FloatArray, FloatArray]:
    """Speeds at the step ends ``(K + 1, M)`` and step distances ``(K, M)``.

    Each step is :func:`rss.physics.accelerated_limited_movement` from the previous speed
    with that step's acceleration ``accel`` ``(K, M)``. Without caps the sequence is the
    running sum ``v0 + Σ a·dt`` (added in the same order) cut at standstill or at the cap;
    that guess is checked by applying the step to all steps at once, and the inputs it
    does not reproduce exactly (tiny accelerations against the tolerances, a cap reached in
    an earlier phase) are iterated step by step.
    """
    run = running_sum(v0, accel * dt)
    cap = tmax(max_speed_mps, v0, SPEED_PRECISION)
    guess = tmin(cap, np.where(le(run, 0.0, SPEED_PRECISION), 0.0, run), SPEED_PRECISION)
    guess[0] = v0
    v1, dist = accelerated_limited_movement(guess[:-1], max_speed_mps, accel, dt)
    if not np.array_equal(np.where(moving, v1, guess[:-1]), guess[1:]):
        for k in range(dt.shape[0]):
            v1k, dk = accelerated_limited_movement(guess[k], max_speed_mps, accel[k], dt[k])
            guess[k + 1] = np.where(moving[k], v1k, guess[k])
            dist[k] = dk
    return guess, np.where(moving, dist, 0.0)


@dataclass(frozen=True)
class Phase:
    """One phase of :func:`vehicle_integrate` (each field broadcast against the points).

    Attributes:
        accel_mps2: Acceleration during the phase [m/s²].
        duration_s: Duration >= 0 [s].
        ratio: Yaw-rate change ratio ∈ [-1, 1]: the yaw rate at a step end is the rate at
            the phase start plus ``ratio · change · t`` (t from the phase start).
    """

    accel_mps2: Real
    duration_s: Real
    ratio: Real


def _phase_grid(duration: FloatArray, step_s: float) -> FloatArray:
    """Step ends ``(K + 1, 1)`` of a phase: ``t + step`` added one by one up to the longest."""
    grid = [0.0]
    longest = float(duration.max()) if duration.size else 0.0
    while grid[-1] < longest and longest - grid[-1] >= DURATION_PRECISION:  # tolerant <
        grid.append(grid[-1] + step_s)
    return np.array(grid)[:, None]


def vehicle_integrate(  # noqa: PLR0917  (kernel over arrays)
    p: Points,
    accel_mps2: Real,
    duration_s: Real,
    ratio: Real,
    yaw_rate_change_radps2: float,
    step_s: float,
    max_speed_mps: Real,
    min_radius_m: float,
    then: Phase | None = None,
) -> Points:
    """Drive ``duration`` in steps while the yaw rate changes linearly (``ratio`` ∈ [-1, 1]).

    ad-rss ``calculateTrajectoryPoint`` of the vehicle model: at the end of each step the
    yaw rate is ``yaw_rate_0 + ratio · change · t``, then one arc of the step length.
    ``then`` continues from the end point with a second phase (its own grid from 0, the
    yaw rate changing from the end rate), as a second call on the end points would.
    Vectorised over ``(steps K, points M)``: only the speeds are iterated (each step's
    speed depends on the previous one through the caps); headings are a cumulative sum
    and positions the sum of the chords ``2 r sin(Δψ/2) · (cos, sin)(ψ + Δψ/2)``. Stack
    every variant (ratios, accelerations, durations, start points) into one call.

    Returns:
        The end points, shape of the broadcast inputs.
    """
    phases = [Phase(accel_mps2, duration_s, ratio), *([then] if then is not None else [])]
    fields = (p.x_m, p.y_m, p.yaw_rad, p.speed_mps, p.yaw_rate_radps, max_speed_mps)
    b = np.broadcast_arrays(
        *fields, *(v for ph in phases for v in (ph.accel_mps2, ph.duration_s, ph.ratio))
    )
    shape = b[0].shape
    flat = [np.ravel(a) for a in b]
    x0, y0, yaw0, v0, rate0, vcap = flat[:6]
    columns = np.arange(x0.shape[0])
    rate_end, steps = rate0, []
    for k in range(len(phases)):
        accel, duration, ratio_m = flat[6 + 3 * k : 9 + 3 * k]
        t = _phase_grid(duration, step_s)
        if t.shape[0] == 1:
            continue
        active = lt(t[:-1], duration, DURATION_PRECISION)  # (K, M)
        full = ge(duration, t[1:], DURATION_PRECISION)
        dt = np.where(full, step_s, duration - t[:-1])
        rate = rate_end + yaw_rate_change_radps2 * np.where(full, t[1:], duration) * ratio_m
        last = active.sum(axis=0) - 1
        rate_end = np.where(last >= 0, rate[np.maximum(last, 0), columns], rate_end)
        steps.append((np.broadcast_to(accel, dt.shape), active, dt, rate))
    if not steps:
        return Points(*(np.array(a, dtype=np.float64) for a in b[:5]))
    accel, active, dt, rate = (
        np.concatenate([s[i] for s in steps]) if len(steps) > 1 else steps[0][i] for i in range(4)
    )
    moving = active & ~eq(dt, 0.0, DURATION_PRECISION)
    speeds, dist = _step_speeds(v0, accel, np.where(moving, dt, 0.0), moving, vcap)
    turning = ~eq(rate, 0.0, ANGULAR_VELOCITY_PRECISION)
    radius = np.where(turning, speeds[:-1] / np.where(turning, rate, 1.0), DISTANCE_MAX_M)
    small = lt(np.abs(radius), min_radius_m, DISTANCE_PRECISION)
    radius = np.where(small, np.where(radius >= 0.0, min_radius_m, -min_radius_m), radius)
    arc = turning | small
    dpsi = np.where(arc, dist / radius, 0.0)
    yaw = running_sum(yaw0, dpsi)
    half = dpsi / 2.0
    chord = np.where(arc, 2.0 * radius * np.sin(half), dist)
    x = x0 + np.sum(chord * np.cos(yaw[:-1] + half), axis=0)
    y = y0 + np.sum(chord * np.sin(yaw[:-1] + half), axis=0)
    return Points(
        x.reshape(shape),
        y.reshape(shape),
        yaw[-1].reshape(shape),
        speeds[-1].reshape(shape),
        rate_end.reshape(shape),
    )


def straight_move(p: Points, distance_m: Real) -> Points:
    """Move along the heading by ``distance`` where it is > 0 (speed unchanged)."""
    go = gt(distance_m, 0.0, DISTANCE_PRECISION)
    d = np.where(go, distance_m, 0.0)
    return replace(p, x_m=p.x_m + np.cos(p.yaw_rad) * d, y_m=p.y_m + np.sin(p.yaw_rad) * d)


def pedestrian_move(p: Points, distance_m: Real, ratio: Real, turning_radius_m: float) -> Points:
    """Move a distance on the circle of radius ``turning_radius / ratio`` (straight near 0).

    ad-rss ``TrajectoryPedestrian::calculateTrajectoryPoint`` (distance variant).
    """
    ratio = np.broadcast_to(ratio, np.broadcast(p.x_m, ratio).shape)
    turning = np.abs(ratio) > turning_radius_m / PEDESTRIAN_MAX_RADIUS_M
    radius = turning_radius_m / np.where(turning, ratio, 1.0)
    start = p.yaw_rad - np.pi / 2.0
    ox, oy = p.x_m - np.cos(start) * radius, p.y_m - np.sin(start) * radius
    dpsi = distance_m / radius
    x = np.where(
        turning, ox + np.cos(start + dpsi) * radius, p.x_m + np.cos(p.yaw_rad) * distance_m
    )
    y = np.where(
        turning, oy + np.sin(start + dpsi) * radius, p.y_m + np.sin(p.yaw_rad) * distance_m
    )
    yaw = np.where(turning, p.yaw_rad + dpsi, p.yaw_rad)
    moved = replace(p, x_m=x, y_m=y, yaw_rad=yaw)
    # ``take`` broadcasts every field to the mask's (full) shape
    return moved.take(eq(distance_m, 0.0, DISTANCE_PRECISION) & np.ones(x.shape, dtype=bool), p)


def pedestrian_move_timed(  # noqa: PLR0917  (kernel over arrays)
    p: Points,
    accel_mps2: Real,
    duration_s: Real,
    ratio: Real,
    turning_radius_m: float,
    max_speed_mps: Real,
) -> Points:
    """Accelerate for ``duration`` and move the covered distance (pedestrian model)."""
    v1, dist = accelerated_limited_movement(p.speed_mps, max_speed_mps, accel_mps2, duration_s)
    return replace(pedestrian_move(p, dist, ratio, turning_radius_m), speed_mps=v1).broadcast()


def footprints(p: Points, length_m: Real, width_m: Real, front_extra_m: FloatArray) -> FloatArray:
    """Corners of the footprints at the points: ``(..., 4, 2)`` in the order FR, FL, BL, BR.

    Args:
        p: Points of any shape ``(...)``.
        length_m: Length [m], broadcast to the points' shape.
        width_m: Width [m].
        front_extra_m: Added in front (the ego's ``min_longitudinal_safety_distance``).
    """
    half_l = np.asarray(length_m) / 2.0  # -(l / 2) is (-l) / 2 to the bit
    front, half_w = half_l + front_extra_m, np.asarray(width_m) / 2.0
    lon = np.empty((*np.broadcast_shapes(front.shape, half_w.shape), 4))  # no stack calls
    lat = np.empty_like(lon)
    lon[..., :2], lon[..., 2:] = front[..., None], -half_l[..., None]
    lat[..., 1:3], lat[..., ::3] = half_w[..., None], -half_w[..., None]
    c, s = np.cos(p.yaw_rad)[..., None], np.sin(p.yaw_rad)[..., None]
    out = np.empty((*np.broadcast_shapes(c.shape, lon.shape), 2))
    out[..., 0] = p.x_m[..., None] + c * lon - s * lat
    out[..., 1] = p.y_m[..., None] + s * lon + c * lat
    return out
