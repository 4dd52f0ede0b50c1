"""Slow, obvious scalar reference of the kernels of :mod:`rss.physics` and the structured checks.

Plain floats, one value at a time.

Tests check that the vectorised kernels agree with these on random inputs.
"""

from __future__ import annotations

import math

from rss.physics import (
    ACCELERATION_PRECISION,
    DISTANCE_PRECISION,
    DURATION_MAX_S,
    DURATION_PRECISION,
    SPEED_PRECISION,
)

__all__ = [
    "accelerated_limited_movement",
    "safe_lateral_distance",
    "safe_longitudinal_distance_same",
    "stated_braking_lateral",
    "stated_braking_longitudinal",
    "time_to_cover_distance",
]


def _eq(a: float, b: float, p: float) -> bool:
    return abs(a - b) < p


def _lt(a: float, b: float, p: float) -> bool:
    return a < b and not _eq(a, b, p)


def accelerated_limited_movement(
    v0: float, v_cap: float, a: float, t: float
) -> tuple[float, float]:
    """Speed and distance after accelerating ``a`` for ``t`` seconds, capped, never < 0."""
    v1 = v0 + a * t
    if _lt(v1, 0.0, SPEED_PRECISION) or _eq(v1, 0.0, SPEED_PRECISION):
        v1 = 0.0
    cap = v0 if _lt(v_cap, v0, SPEED_PRECISION) else v_cap  # std::max(v_cap, v0)
    v1 = v1 if _lt(v1, cap, SPEED_PRECISION) else cap  # std::min(cap, v1)
    t_acc = 0.0 if _eq(a, 0.0, ACCELERATION_PRECISION) else (v1 - v0) / a
    return v1, v0 * t + 0.5 * a * t_acc * t_acc + (v1 - v0) * (t - t_acc)


def _stop(v: float, decel: float) -> float:
    if math.copysign(1.0, v) == math.copysign(1.0, decel) or decel == 0.0:
        return 0.0
    return v * v / (-2.0 * decel)


def stated_braking_longitudinal(
    v: float, v_cap: float, rho: float, accel: float, decel: float
) -> float:
    """Capped acceleration during ``rho``, then braking to standstill."""
    v_rho, d_rho = accelerated_limited_movement(v, v_cap, accel, rho)
    return d_rho + _stop(v_rho, decel)


def stated_braking_lateral(v: float, rho: float, accel: float, decel: float) -> float:
    """Plain kinematics during ``rho``, then braking if still moving in ``accel``'s direction."""
    v_rho = v + accel * rho
    return v * rho + 0.5 * accel * rho * rho + _stop(v_rho, decel)


def _root(v: float, a: float, s: float) -> float:
    sq = math.sqrt(max(v * v + 2.0 * a * s, 0.0))
    r1, r2 = (-v + sq) / a, (-v - sq) / a
    both = r1 >= DURATION_PRECISION and r2 >= DURATION_PRECISION
    return min(r1, r2) if both else max(r1, r2)


def _time_for_distance(v: float, v_cap: float, a: float, s: float) -> float:
    if _eq(a, 0.0, ACCELERATION_PRECISION) or (a > 0.0 and not _lt(v, v_cap, SPEED_PRECISION)):
        return DURATION_MAX_S if _eq(v, 0.0, SPEED_PRECISION) else s / v
    if a < 0.0:
        return _root(v, a, s)
    t_cap = max((v_cap - v) / a, 0.0)
    d_cap = v * t_cap + 0.5 * a * t_cap * t_cap
    if not _lt(d_cap, s, DISTANCE_PRECISION):
        return _root(v, a, s)
    return t_cap + (s - d_cap) / v_cap


def time_to_cover_distance(  # noqa: PLR0917  (mirrors the kernel)
    v: float, v_cap: float, rho: float, a_during: float, a_after: float, s: float
) -> float:
    """Time to travel ``s`` (``a_during`` for ``rho``, then braking ``a_after`` < 0)."""
    v_rho, d_rho = accelerated_limited_movement(v, v_cap, a_during, rho)
    if not _lt(d_rho, s, DISTANCE_PRECISION):
        return _time_for_distance(v, v_cap, a_during, s)
    remaining = s - d_rho
    stop = v_rho * v_rho / (-2.0 * a_after)
    if not _lt(remaining, stop, DISTANCE_PRECISION):
        return DURATION_MAX_S
    t = _time_for_distance(v_rho, v_cap, a_after, remaining)
    return DURATION_MAX_S if t >= DURATION_MAX_S else t + rho


def safe_longitudinal_distance_same(
    v_follower: float, follower: dict[str, float], v_leader: float, leader_brake_max: float
) -> float:
    """Follower behind leader; ``follower`` holds ad-rss-named dynamics keys."""
    d_f = stated_braking_longitudinal(
        v_follower,
        follower["max_speed_on_acceleration"],
        follower["response_time"],
        follower["accel_max"],
        follower["brake_min"],
    )
    d = d_f - _stop(v_leader, leader_brake_max)
    return (0.0 if _lt(d, 0.0, DISTANCE_PRECISION) else d) + follower[
        "min_longitudinal_safety_distance"
    ]


def safe_lateral_distance(
    v_left: float, left: dict[str, float], v_right: float, right: dict[str, float]
) -> float:
    """Left and right vehicle, lateral speeds positive to the right."""
    d_left = stated_braking_lateral(
        v_left, left["response_time"], left["lat_accel_max"], left["lat_brake_min"]
    )
    d_right = stated_braking_lateral(
        v_right, right["response_time"], -right["lat_accel_max"], -right["lat_brake_min"]
    )
    d = (
        d_left
        - d_right
        + 0.5 * (left["lateral_fluctuation_margin"] + right["lateral_fluctuation_margin"])
    )
    return 0.0 if _lt(d, 0.0, DISTANCE_PRECISION) else d
