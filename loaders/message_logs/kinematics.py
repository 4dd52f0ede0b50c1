"""Ego speed, acceleration and yaw rate from a window of three ego samples.

Frames are emitted one ego message late so every frame sees its predecessor and its
successor (``prev``, ``cur``, ``nxt``; either neighbour may be missing at the ends):

- speed: the message's own (``Odometry``: ``twist.linear.x`` in the body frame); otherwise
  the central difference of positions projected on the heading;
- yaw rate: the message's own (``twist.angular.z``); otherwise the central difference of
  the unwrapped yaw;
- acceleration: the central difference of the message speeds over ``[prev, nxt]`` (a light
  smoothing over two intervals), or for pose-only messages the second difference of
  positions; one-sided at the ends and 0 for a single sample.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

from loaders.timebase import ns_to_s

if TYPE_CHECKING:
    from loaders.message_logs.samples import EgoSample

__all__ = ["TimedEgo", "ego_kinematics", "wrap_angle"]

TimedEgo = tuple[int, "EgoSample"]


def wrap_angle(angle_rad: float) -> float:
    """Wrap to ``[-pi, pi)``."""
    return (angle_rad + math.pi) % (2 * math.pi) - math.pi


def _along(a: TimedEgo, b: TimedEgo, yaw: float) -> float:
    dt = ns_to_s(b[0] - a[0])
    dx, dy = b[1].x_m - a[1].x_m, b[1].y_m - a[1].y_m
    return (dx * math.cos(yaw) + dy * math.sin(yaw)) / dt


def ego_kinematics(
    prev: TimedEgo | None, cur: TimedEgo, nxt: TimedEgo | None
) -> tuple[float, float, float]:
    """Return ``(speed_mps, accel_mps2, yaw_rate_radps)`` of ``cur``.

    Args:
        prev: Previous ``(t_ns, sample)``, if any.
        cur: The frame's ``(t_ns, sample)``.
        nxt: Next ``(t_ns, sample)``, if any.
    """
    sample = cur[1]
    a = prev or cur
    b = nxt or cur
    span = ns_to_s(b[0] - a[0])
    if span <= 0:
        speed = 0.0 if math.isnan(sample.speed_mps) else sample.speed_mps
        yaw_rate = 0.0 if math.isnan(sample.yaw_rate_radps) else sample.yaw_rate_radps
        return speed, 0.0, yaw_rate
    yaw_rate = sample.yaw_rate_radps
    if math.isnan(yaw_rate):
        yaw_rate = wrap_angle(b[1].yaw_rad - a[1].yaw_rad) / span
    if not math.isnan(sample.speed_mps):
        va = a[1].speed_mps if not math.isnan(a[1].speed_mps) else sample.speed_mps
        vb = b[1].speed_mps if not math.isnan(b[1].speed_mps) else sample.speed_mps
        return sample.speed_mps, (vb - va) / span, yaw_rate
    speed = _along(a, b, sample.yaw_rad)
    accel = 0.0
    if prev is not None and nxt is not None:
        accel = (_along(cur, nxt, sample.yaw_rad) - _along(prev, cur, sample.yaw_rad)) / (span / 2)
    return speed, accel, yaw_rate
