"""Scalar twins of :mod:`rss.physics` and :mod:`rss.structured.formulas` (one constellation).

The small-frame path (:mod:`rss.structured.small`) evaluates a handful of constellations
with plain float arithmetic instead of a hundred small numpy calls; compiled with mypyc
(:mod:`rss.compiled`) these run at C speed. Every function performs the same IEEE
operations in the same order as its array twin and picks the branch the array twin's
``np.where`` picks, so both give the same floats; a branch whose value the array twin
discards is not computed here (no division by zero is ever evaluated).
"""

from __future__ import annotations

import math
from typing import Final

from rss.physics import (
    ACCELERATION_PRECISION,
    DISTANCE_PRECISION,
    DURATION_MAX_S,
    DURATION_PRECISION,
    SPEED_PRECISION,
)

__all__ = [
    "accelerated_limited_movement",
    "gt",
    "lt",
    "safe_lateral",
    "safe_longitudinal_opposite",
    "safe_longitudinal_same",
    "stated_braking_lateral",
    "stated_braking_longitudinal",
    "stopping_distance",
    "time_to_cover_distance",
    "tmax",
]

_AP: Final = ACCELERATION_PRECISION
_DURATION_MAX_S: Final = DURATION_MAX_S
_DP: Final = DURATION_PRECISION
_SP: Final = SPEED_PRECISION

_P: Final = DISTANCE_PRECISION


def gt(a: float, b: float, precision: float) -> bool:
    """Tolerant ``a > b`` (:func:`rss.physics.gt`)."""
    return a - b >= precision


def lt(a: float, b: float, precision: float) -> bool:
    """Tolerant ``a < b`` (:func:`rss.physics.lt`)."""
    return b - a >= precision


def tmax(a: float, b: float, precision: float) -> float:
    """``std::max`` with tolerant ``<`` (:func:`rss.physics.tmax`)."""
    return b if b - a >= precision else a


def stopping_distance(speed_mps: float, decel_mps2: float) -> float:
    """Signed stopping distance [m] (:func:`rss.physics.stopping_distance`)."""
    if decel_mps2 == 0.0:
        return 0.0
    return speed_mps * speed_mps / (-2.0 * decel_mps2)


def _negative_sign(value: float) -> bool:
    """``np.signbit`` (``math.copysign`` only for zeros: native comparisons otherwise)."""
    if value != 0.0:
        return value < 0.0
    return math.copysign(1.0, value) < 0.0


def _stop_if_moving_against(speed_mps: float, decel_mps2: float) -> float:
    if _negative_sign(speed_mps) != _negative_sign(decel_mps2):
        return stopping_distance(speed_mps, decel_mps2)
    return 0.0


def accelerated_limited_movement(
    speed_mps: float, max_speed_mps: float, accel_mps2: float, duration_s: float
) -> tuple[float, float]:
    """``(v1 [m/s], distance [m])`` (:func:`rss.physics.accelerated_limited_movement`)."""
    v1 = speed_mps + accel_mps2 * duration_s
    if v1 - 0.0 < _SP:
        v1 = 0.0
    cap = speed_mps if speed_mps - max_speed_mps >= _SP else max_speed_mps
    if cap - v1 >= _SP:
        cap = v1
    v1 = cap
    t_acc = 0.0 if abs(accel_mps2 - 0.0) < _AP else (v1 - speed_mps) / accel_mps2
    distance = (
        speed_mps * duration_s
        + 0.5 * accel_mps2 * t_acc * t_acc
        + (v1 - speed_mps) * (duration_s - t_acc)
    )
    return v1, distance


def stated_braking_longitudinal(
    speed_mps: float,
    max_speed_mps: float,
    response_time_s: float,
    accel_mps2: float,
    decel_mps2: float,
) -> float:
    """Longitudinal stated braking distance [m] (``rss.physics.stated_braking_longitudinal``)."""
    v_rho, d_rho = accelerated_limited_movement(
        speed_mps, max_speed_mps, accel_mps2, response_time_s
    )
    return d_rho + _stop_if_moving_against(v_rho, decel_mps2)


def stated_braking_lateral(
    speed_mps: float, response_time_s: float, accel_mps2: float, decel_mps2: float
) -> float:
    """Signed lateral stated braking distance [m] (:func:`rss.physics.stated_braking_lateral`)."""
    v_rho = speed_mps + accel_mps2 * response_time_s
    d_rho = speed_mps * response_time_s + 0.5 * accel_mps2 * response_time_s * response_time_s
    return d_rho + _stop_if_moving_against(v_rho, decel_mps2)


def safe_longitudinal_same(
    follower: list[float], speed_max: float, leader: list[float], speed_min: float
) -> float:
    """Safe distance behind a leader [m] (dynamics as :data:`DYNAMICS` rows of 10 floats)."""
    d_follower = stated_braking_longitudinal(
        speed_max, follower[8], follower[7], follower[0], follower[2]
    )
    d_leader = stopping_distance(speed_min, leader[1])
    return tmax(d_follower - d_leader, 0.0, _P) + follower[9]


def safe_longitudinal_opposite(
    correct: list[float], correct_speed_max: float, opposite: list[float], opposite_speed_max: float
) -> float:
    """Safe distance of two oncoming vehicles [m]."""
    d_correct = stated_braking_longitudinal(
        correct_speed_max, correct[8], correct[7], correct[0], correct[3]
    )
    d_opposite = stated_braking_longitudinal(
        opposite_speed_max, opposite[8], opposite[7], opposite[0], opposite[2]
    )
    return d_correct + d_opposite + tmax(correct[9], opposite[9], _P)


def safe_lateral(
    left: list[float], left_speed_max: float, right: list[float], right_speed_min: float
) -> float:
    """Safe lateral distance between a left and a right vehicle [m]."""
    d_left = stated_braking_lateral(left_speed_max, left[7], left[4], left[5])
    d_right = stated_braking_lateral(right_speed_min, right[7], -right[4], -right[5])
    margin = 0.5 * (left[6] + right[6])
    return tmax(d_left - d_right + margin, 0.0, _P)


def _quadratic_time(speed_mps: float, accel_mps2: float, distance_m: float) -> float:
    safe_a = 1.0 if accel_mps2 == 0.0 else accel_mps2
    root = math.sqrt(max(speed_mps * speed_mps + 2.0 * accel_mps2 * distance_m, 0.0))
    r1 = (-speed_mps + root) / safe_a
    r2 = (-speed_mps - root) / safe_a
    if r1 - 0.0 >= _DP and r2 - 0.0 >= _DP:
        return min(r1, r2)
    return max(r1, r2)


def _time_for_distance(
    speed_mps: float, max_speed_mps: float, accel_mps2: float, distance_m: float
) -> float:
    v, cap, a, s = speed_mps, max_speed_mps, accel_mps2, distance_m
    no_accel = abs(a - 0.0) < _AP
    if no_accel or (a >= 0.0 and cap - v < _SP):
        if abs(v - 0.0) < _SP:
            return _DURATION_MAX_S
        return s / (v if v > 0.0 else 1.0)
    if a < 0.0:
        return _quadratic_time(v, a, s)
    t_cap = max((cap - v) / (a if a > 0.0 else 1.0), 0.0)
    d_cap = v * t_cap + 0.5 * a * t_cap * t_cap
    if s - d_cap < _P:
        return _quadratic_time(v, a, s)
    return t_cap + (s - d_cap) / (cap if cap > 0.0 else 1.0)


def time_to_cover_distance(  # noqa: PLR0917 - the kernel's six scalars
    speed_mps: float,
    max_speed_mps: float,
    response_time_s: float,
    accel_during_mps2: float,
    accel_after_mps2: float,
    distance_m: float,
) -> float:
    """Time [s] to travel a distance (:func:`rss.physics.time_to_cover_distance`)."""
    v_rho, d_rho = accelerated_limited_movement(
        speed_mps, max_speed_mps, accel_during_mps2, response_time_s
    )
    if distance_m - d_rho < _P:
        return _time_for_distance(speed_mps, max_speed_mps, accel_during_mps2, distance_m)
    remaining = distance_m - d_rho
    t_after = _time_for_distance(v_rho, max_speed_mps, accel_after_mps2, remaining)
    stops_first = accel_after_mps2 < 0.0 and (
        stopping_distance(v_rho, accel_after_mps2) - remaining < _P
    )
    if stops_first or t_after >= _DURATION_MAX_S:
        return _DURATION_MAX_S
    return t_after + response_time_s
