"""Slow, obvious scalar twins of the trajectory-set kernels (the reference for the tests).

One trajectory point at a time, plain ``math``, one loop iteration per integration step,
written as ad-rss states the model (no vectorisation, no closed forms). The fast kernels of
:mod:`rss.unstructured.kinematics` must agree with these to rounding; see
``tests/rss/unstructured/test_reference.py``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from rss.physics import (
    ACCELERATION_PRECISION,
    DISTANCE_MAX_M,
    DISTANCE_PRECISION,
    DURATION_PRECISION,
    SPEED_PRECISION,
)
from rss.unstructured.kinematics import ANGULAR_VELOCITY_PRECISION, PEDESTRIAN_MAX_RADIUS_M

__all__ = [
    "Pose",
    "ref_footprint",
    "ref_movement",
    "ref_pedestrian_move",
    "ref_time_to_stop",
    "ref_vehicle_arc",
    "ref_vehicle_integrate",
]


@dataclass(frozen=True)
class Pose:
    """One trajectory point: centre, heading, speed, yaw rate."""

    x: float
    y: float
    yaw: float
    speed: float
    yaw_rate: float


def _eq(a: float, b: float, precision: float) -> bool:
    return abs(a - b) < precision


def _lt(a: float, b: float, precision: float) -> bool:
    return a < b and not _eq(a, b, precision)


def ref_movement(
    speed: float, max_speed: float, accel: float, duration: float
) -> tuple[float, float]:
    """Speed and distance after ``accel`` for ``duration`` (stops at 0, capped above)."""
    v1 = speed + accel * duration
    if v1 < 0.0 or _eq(v1, 0.0, SPEED_PRECISION):
        v1 = 0.0
    # std::max / std::min with ad-physics' tolerant "<": the first argument wins ties
    cap = speed if _lt(max_speed, speed, SPEED_PRECISION) else max_speed
    v1 = v1 if _lt(v1, cap, SPEED_PRECISION) else cap
    t_acc = 0.0 if _eq(accel, 0.0, ACCELERATION_PRECISION) else (v1 - speed) / accel
    distance = speed * duration + 0.5 * accel * t_acc * t_acc + (v1 - speed) * (duration - t_acc)
    return v1, distance


def ref_time_to_stop(
    speed: float, response_time: float, max_speed: float, accel: float, brake: float
) -> float:
    """``accel`` during the response time, then ``brake`` (< 0) to standstill."""
    v_rt, _ = ref_movement(speed, max_speed, accel, response_time)
    if _eq(v_rt, 0.0, SPEED_PRECISION):
        return 0.0
    return response_time + v_rt / -brake


def ref_vehicle_arc(
    p: Pose, accel: float, duration: float, max_speed: float, min_radius: float
) -> Pose:
    """One arc of radius ``speed / yaw_rate`` (at least ``min_radius``) for ``duration``."""
    if _eq(duration, 0.0, DURATION_PRECISION):
        return p
    v1, dist = ref_movement(p.speed, max_speed, accel, duration)
    turning = not _eq(p.yaw_rate, 0.0, ANGULAR_VELOCITY_PRECISION)
    radius = p.speed / p.yaw_rate if turning else DISTANCE_MAX_M
    if _lt(abs(radius), min_radius, DISTANCE_PRECISION):
        radius = min_radius if radius >= 0.0 else -min_radius
        turning = True
    if not turning:
        return Pose(
            p.x + dist * math.cos(p.yaw), p.y + dist * math.sin(p.yaw), p.yaw, v1, p.yaw_rate
        )
    # rotate the point about the circle's centre (left of the heading for radius > 0)
    cx, cy = p.x - radius * math.sin(p.yaw), p.y + radius * math.cos(p.yaw)
    angle = dist / radius
    dx, dy = p.x - cx, p.y - cy
    x = cx + math.cos(angle) * dx - math.sin(angle) * dy
    y = cy + math.sin(angle) * dx + math.cos(angle) * dy
    return Pose(x, y, p.yaw + angle, v1, p.yaw_rate)


def ref_vehicle_integrate(  # noqa: PLR0917  (the model's parameters, one by one)
    p: Pose,
    accel: float,
    duration: float,
    ratio: float,
    yaw_rate_change: float,
    step: float,
    max_speed: float,
    min_radius: float,
) -> Pose:
    """Steps of ``step`` seconds; the yaw rate at each step's end is ``rate0 + ratio·change·t``."""
    t, rate0, cur = 0.0, p.yaw_rate, p
    while _lt(t, duration, DURATION_PRECISION):
        full = not _lt(duration, t + step, DURATION_PRECISION)
        dt = step if full else duration - t
        t = t + step if full else duration
        rate = rate0 + yaw_rate_change * t * ratio
        cur = ref_vehicle_arc(
            Pose(cur.x, cur.y, cur.yaw, cur.speed, rate), accel, dt, max_speed, min_radius
        )
        cur = Pose(cur.x, cur.y, cur.yaw, cur.speed, rate)
    return cur


def ref_pedestrian_move(p: Pose, distance: float, ratio: float, turning_radius: float) -> Pose:
    """Walk ``distance`` on the circle of radius ``turning_radius / ratio`` (straight near 0)."""
    if _eq(distance, 0.0, DISTANCE_PRECISION):
        return p
    if abs(ratio) <= turning_radius / PEDESTRIAN_MAX_RADIUS_M:
        return Pose(
            p.x + math.cos(p.yaw) * distance,
            p.y + math.sin(p.yaw) * distance,
            p.yaw,
            p.speed,
            p.yaw_rate,
        )
    radius = turning_radius / ratio
    start = p.yaw - math.pi / 2.0
    cx, cy = p.x - math.cos(start) * radius, p.y - math.sin(start) * radius
    angle = distance / radius
    return Pose(
        cx + math.cos(start + angle) * radius,
        cy + math.sin(start + angle) * radius,
        p.yaw + angle,
        p.speed,
        p.yaw_rate,
    )


def ref_footprint(
    p: Pose, length: float, width: float, front_extra: float
) -> list[tuple[float, float]]:
    """Corners FR, FL, BL, BR of the footprint (front extended by ``front_extra``)."""
    corners = [
        (length / 2.0 + front_extra, -width / 2.0),
        (length / 2.0 + front_extra, width / 2.0),
        (-length / 2.0, width / 2.0),
        (-length / 2.0, -width / 2.0),
    ]
    c, s = math.cos(p.yaw), math.sin(p.yaw)
    return [(p.x + c * lon - s * lat, p.y + s * lon + c * lat) for lon, lat in corners]
