"""Vectorised kinematic primitives with ad-physics' tolerant comparisons.

ad-physics compares every quantity with a precision: ``a == b`` means ``|a - b| < p`` and
``a > b`` means ``a > b`` *and not* ``a == b`` (so roughly ``a - b >= p``). The engine
reproduces this so that it agrees with ad-rss on boundary cases; all functions broadcast
over arrays of any shape ``(...)``.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from rss.arrays import FloatArray

__all__ = [
    "ACCELERATION_LOWEST_MPS2",
    "ACCELERATION_PRECISION",
    "DISTANCE_MAX_M",
    "DISTANCE_PRECISION",
    "DURATION_MAX_S",
    "DURATION_PRECISION",
    "SPEED_PRECISION",
    "accelerated_limited_movement",
    "eq",
    "ge",
    "gt",
    "le",
    "lt",
    "stated_braking_lateral",
    "stated_braking_longitudinal",
    "stopping_distance",
    "time_to_cover_distance",
    "tmax",
    "tmin",
]

DISTANCE_PRECISION = 1e-3
SPEED_PRECISION = 1e-3
DURATION_PRECISION = 1e-3
ACCELERATION_PRECISION = 1e-4
#: ``Distance::max()``: reported for a lateral side that is not evaluated.
DISTANCE_MAX_M = 1e9
#: ``Duration::max()``: "never" in time-to-cover computations.
DURATION_MAX_S = 1e6
#: ``Acceleration::lowest()``: an unbounded lower acceleration limit.
ACCELERATION_LOWEST_MPS2 = -1e3


def eq(a: FloatArray | float, b: FloatArray | float, precision: float) -> np.ndarray:
    """Tolerant ``a == b``: ``|a - b| < precision``."""
    return np.asarray(np.abs(np.subtract(a, b)) < precision)


def gt(a: FloatArray | float, b: FloatArray | float, precision: float) -> np.ndarray:
    """Tolerant ``a > b``: strictly greater and not equal within ``precision``.

    Computed as ``a - b >= precision`` (one subtraction: the rounded difference has the
    sign of the exact one and ``fl(b - a) == -fl(a - b)``, so this is the same set,
    NaN and infinities included).
    """
    return np.asarray(np.subtract(a, b) >= precision)


def lt(a: FloatArray | float, b: FloatArray | float, precision: float) -> np.ndarray:
    """Tolerant ``a < b`` (``b - a >= precision``, see :func:`gt`)."""
    return np.asarray(np.subtract(b, a) >= precision)


def ge(a: FloatArray | float, b: FloatArray | float, precision: float) -> np.ndarray:
    """Tolerant ``a >= b``: greater or equal within ``precision`` (``b - a < precision``)."""
    return np.asarray(np.subtract(b, a) < precision)


def le(a: FloatArray | float, b: FloatArray | float, precision: float) -> np.ndarray:
    """Tolerant ``a <= b`` (``a - b < precision``)."""
    return np.asarray(np.subtract(a, b) < precision)


def tmax(a: FloatArray | float, b: FloatArray | float, precision: float) -> FloatArray:
    """``std::max(a, b)`` with tolerant ``<``: returns ``a`` unless ``a < b``."""
    return np.where(lt(a, b, precision), b, a).astype(np.float64)


def tmin(a: FloatArray | float, b: FloatArray | float, precision: float) -> FloatArray:
    """``std::min(a, b)`` with tolerant ``<``: returns ``a`` unless ``b < a``."""
    return np.where(lt(b, a, precision), b, a).astype(np.float64)


def accelerated_limited_movement(
    speed_mps: FloatArray,
    max_speed_mps: FloatArray,
    accel_mps2: FloatArray,
    duration_s: FloatArray,
) -> tuple[FloatArray, FloatArray]:
    """Speed and distance after accelerating for a duration, capped and stopping at 0.

    The speed never drops below 0 (decelerating to standstill, then standing) and never
    rises above ``max(max_speed, speed)`` (a speed already above the cap is kept).

    Args:
        speed_mps: Initial speed v0 >= 0, shape ``(...)``.
        max_speed_mps: Speed cap of the acceleration phase.
        accel_mps2: Acceleration (negative = braking).
        duration_s: Duration t >= 0.

    Returns:
        ``(v1, d)``: final speed [m/s] and travelled distance [m].
    """
    v1 = np.asarray(speed_mps + accel_mps2 * duration_s, dtype=np.float64)
    # the tolerant comparisons against 0 compare the value itself (x - 0.0 is x)
    v1 = np.where(v1 < SPEED_PRECISION, 0.0, v1)  # le(v1, 0)
    # the cap is tmax(max_speed, speed), then v1 becomes tmin(cap, v1)
    cap = np.where(
        np.subtract(speed_mps, max_speed_mps) >= SPEED_PRECISION, speed_mps, max_speed_mps
    )
    v1 = np.where(np.subtract(cap, v1) >= SPEED_PRECISION, v1, cap)
    gained = v1 - speed_mps
    no_accel = np.abs(accel_mps2) < ACCELERATION_PRECISION  # eq(accel, 0)
    if np.any(no_accel):
        safe_a = np.where(no_accel, 1.0, accel_mps2)
        t_acc = np.where(no_accel, 0.0, gained / safe_a)
    else:
        t_acc = gained / accel_mps2
    distance = (
        speed_mps * duration_s + 0.5 * accel_mps2 * t_acc * t_acc + gained * (duration_s - t_acc)
    )
    return np.asarray(v1, dtype=np.float64), np.asarray(distance, dtype=np.float64)


def stopping_distance(speed_mps: FloatArray, decel_mps2: FloatArray) -> FloatArray:
    """Distance to stop: ``v² / (-2 a)`` (0 where the acceleration is 0).

    Args:
        speed_mps: Speed (sign gives the direction), shape ``(...)``.
        decel_mps2: Deceleration of opposite sign to the speed.

    Returns:
        Signed stopping distance [m] (sign of the speed).
    """
    zero = np.equal(decel_mps2, 0.0)
    if not np.any(zero):
        return np.asarray(speed_mps * speed_mps / (-2.0 * decel_mps2), dtype=np.float64)
    safe = np.where(zero, -1.0, decel_mps2)
    return np.asarray(np.where(zero, 0.0, speed_mps * speed_mps / (-2.0 * safe)), dtype=np.float64)


def _stop_if_moving_against(speed_mps: FloatArray, decel_mps2: FloatArray) -> FloatArray:
    """Stopping distance, applied only when speed and deceleration have different sign bits."""
    moving_along = np.signbit(speed_mps) == np.signbit(decel_mps2)
    distance = stopping_distance(speed_mps, decel_mps2)  # a fresh array of the broadcast shape
    distance[moving_along] = 0.0
    return distance


def stated_braking_longitudinal(
    speed_mps: FloatArray,
    max_speed_mps: FloatArray,
    response_time_s: FloatArray,
    accel_mps2: FloatArray,
    decel_mps2: FloatArray,
) -> FloatArray:
    """Distance of the longitudinal stated braking pattern [m] (shapes broadcast).

    Capped acceleration during the response time, then braking to standstill.
    """
    v_rho, d_rho = accelerated_limited_movement(
        speed_mps, max_speed_mps, accel_mps2, response_time_s
    )
    return np.asarray(d_rho + _stop_if_moving_against(v_rho, decel_mps2), dtype=np.float64)


def stated_braking_lateral(
    speed_mps: FloatArray,
    response_time_s: FloatArray,
    accel_mps2: FloatArray,
    decel_mps2: FloatArray,
) -> FloatArray:
    """Signed distance of the lateral stated braking pattern [m] (shapes broadcast).

    Plain kinematics during the response time (no cap, no clamp at a zero crossing), then
    braking if still moving in the acceleration direction.
    """
    v_rho = speed_mps + accel_mps2 * response_time_s
    d_rho = speed_mps * response_time_s + 0.5 * accel_mps2 * response_time_s * response_time_s
    return np.asarray(d_rho + _stop_if_moving_against(v_rho, decel_mps2), dtype=np.float64)


def _quadratic_time(
    speed_mps: FloatArray, accel_mps2: FloatArray, distance_m: FloatArray
) -> FloatArray:
    """Root of ``v t + a t² / 2 = s`` chosen as ad-physics does.

    The smaller root when both are (tolerantly) positive, else the larger one (so ``s ≈ 0``
    while braking yields the *second* crossing ``2 v / |a|`` — a reference quirk kept for
    agreement).
    """
    safe_a = np.where(accel_mps2 == 0.0, 1.0, accel_mps2)
    root = np.sqrt(np.maximum(speed_mps * speed_mps + 2.0 * accel_mps2 * distance_m, 0.0))
    r1 = (-speed_mps + root) / safe_a
    r2 = (-speed_mps - root) / safe_a
    both = gt(r1, 0.0, DURATION_PRECISION) & gt(r2, 0.0, DURATION_PRECISION)
    return np.asarray(np.where(both, np.minimum(r1, r2), np.maximum(r1, r2)), dtype=np.float64)


def _time_for_distance(
    speed_mps: FloatArray, max_speed_mps: FloatArray, accel_mps2: FloatArray, distance_m: FloatArray
) -> FloatArray:
    """Time to cover ``distance`` from ``speed`` with one constant acceleration.

    The speed is capped when accelerating; no stop check (the caller does it).
    """
    v, cap, a, s = np.broadcast_arrays(speed_mps, max_speed_mps, accel_mps2, distance_m)
    no_accel = eq(a, 0.0, ACCELERATION_PRECISION)
    standing = eq(v, 0.0, SPEED_PRECISION)
    safe_v = np.where(v > 0.0, v, 1.0)
    safe_a = np.where(a > 0.0, a, 1.0)
    t_const = np.where(standing, DURATION_MAX_S, s / safe_v)
    quadratic = _quadratic_time(v, a, s)
    t_cap = np.maximum((cap - v) / safe_a, 0.0)
    d_cap = v * t_cap + 0.5 * a * t_cap * t_cap
    safe_cap = np.where(cap > 0.0, cap, 1.0)
    t_accel = np.where(ge(d_cap, s, DISTANCE_PRECISION), quadratic, t_cap + (s - d_cap) / safe_cap)
    t_accel = np.where(ge(v, cap, SPEED_PRECISION), t_const, t_accel)
    result = np.where(no_accel, t_const, np.where(a < 0.0, quadratic, t_accel))
    return np.asarray(result, dtype=np.float64)


def time_to_cover_distance(  # noqa: PLR0917  (kernel over arrays)
    speed_mps: FloatArray,
    max_speed_mps: FloatArray,
    response_time_s: FloatArray,
    accel_during_mps2: FloatArray,
    accel_after_mps2: FloatArray,
    distance_m: FloatArray,
) -> FloatArray:
    """Time to travel a distance (ad-rss ``calculateTimeToCoverDistance``).

    One acceleration during the response time, a braking deceleration afterwards.

    Args:
        speed_mps: Initial speed >= 0, shape ``(...)``.
        max_speed_mps: Speed cap of accelerating phases.
        response_time_s: Response time.
        accel_during_mps2: Acceleration during the response time.
        accel_after_mps2: Deceleration (< 0) after the response time.
        distance_m: Distance to cover >= 0.

    Returns:
        Time [s]; :data:`DURATION_MAX_S` ("never") when the vehicle stops first.
    """
    v_rho, d_rho = accelerated_limited_movement(
        speed_mps, max_speed_mps, accel_during_mps2, response_time_s
    )
    within = ge(d_rho, distance_m, DISTANCE_PRECISION)
    t_within = _time_for_distance(speed_mps, max_speed_mps, accel_during_mps2, distance_m)
    remaining = distance_m - d_rho
    t_after = _time_for_distance(v_rho, max_speed_mps, accel_after_mps2, remaining)
    braking = np.asarray(accel_after_mps2) < 0.0
    stops_first = braking & le(
        stopping_distance(v_rho, accel_after_mps2), remaining, DISTANCE_PRECISION
    )
    never = stops_first | (t_after >= DURATION_MAX_S)
    t_after = np.where(never, DURATION_MAX_S, t_after + response_time_s)
    return np.asarray(np.where(within, t_within, t_after), dtype=np.float64)
