"""Vehicle trajectory sets T(C_b) and T(C_f) (ad-rss ``TrajectoryVehicle``), step by step.

The reference of :mod:`rss.unstructured.vehicle_batch` (which the engine runs): one
dynamics per call, one kernel call per step in ad-rss' order.

1. Response time rho: yaw rate changes linearly (ratio ∈ [-1, 1] of
   ``vehicle_yaw_rate_change``), integrated in ``vehicle_trajectory_calculation_step``
   steps. Front: ``speed_max`` with ``accel_max``; back: ``speed_min`` with ``brake_max``.
2. After rho: each point keeps its yaw rate (arc) with the phase acceleration: back with
   ``brake_max`` to standstill, front with ``brake_min`` (brake set) or ``accel_max``
   (continue-forward set) for the stop horizon of ``speed_max``; the sides are sampled
   with intermediate accelerations.
3. Pieces: see :func:`rss.unstructured.sets.front_and_sides`, plus the hull closing the
   gap to the current footprint.
"""

from __future__ import annotations

import itertools
from typing import TYPE_CHECKING

import numpy as np

from rss.physics import ACCELERATION_PRECISION, SPEED_PRECISION, gt, lt
from rss.unstructured.kinematics import (
    Points,
    change_ratios,
    footprints,
    time_in_movement,
    time_to_stop,
    vehicle_arc,
    vehicle_integrate,
)
from rss.unstructured.sets import Location, PieceCollector, TrajectorySets, front_and_sides

if TYPE_CHECKING:
    from collections.abc import Sequence

    from rss.arrays import FloatArray
    from rss.dynamics import RssDynamics
    from rss.unstructured.agents import UnstructuredAgents
    from rss.unstructured.kinematics import Real

__all__ = ["step_accelerations", "vehicle_sets"]

#: One integration job: start points, acceleration, duration, yaw-rate change ratios.
Job = tuple[Points, "Real", "Real", "FloatArray"]


def step_accelerations(low: float, high: float, steps: int) -> list[float]:
    """``low + k·Δ`` for k >= 1 while below ``high`` (tolerant), then ``high``."""
    delta = (high - low) / (1.0 + steps)
    values = [low + delta * k for k in range(1, steps + 2)]
    return [a for a in values if lt(a, high, ACCELERATION_PRECISION)] + [high]


class _Vehicle:
    """The per-group constants and footprint helper."""

    def __init__(self, agents: UnstructuredAgents, dyn: RssDynamics, front_extra_m: Real) -> None:
        self.a, self.dyn, self.extra = agents, dyn, front_extra_m
        u = dyn.unstructured
        self.settings = u
        self.rho = dyn.response_time_s
        self.vcap = dyn.max_speed_on_acceleration_mps
        self.rmin = u.vehicle_min_radius

    def start(self, speed: Real) -> Points:
        a = self.a
        return Points(a.x_m, a.y_m, a.yaw_rad, speed, a.yaw_rate_radps)

    def fp(self, p: Points) -> FloatArray:
        return footprints(p, self.a.length_m, self.a.width_m, self.extra)

    def integrate_many(self, jobs: Sequence[Job]) -> list[Points]:
        """Integrate every job in one :func:`vehicle_integrate` call.

        A job is ``(start (N,), accel, duration (N,) or scalar, ratios (R,))``; its result
        is ``(R, N)`` points.
        """
        n = len(self.a)
        sizes = [len(ratios) for *_, ratios in jobs]

        def column(values: Sequence[Real]) -> FloatArray:
            return np.concatenate(
                [np.broadcast_to(v, (r, n)) for v, r in zip(values, sizes, strict=True)]
            )

        start = Points(
            *(
                column([getattr(p, f) for p, *_ in jobs])
                for f in ("x_m", "y_m", "yaw_rad", "speed_mps", "yaw_rate_radps")
            )
        )
        accel = column([a for _, a, _, _ in jobs])
        duration = column([d for _, _, d, _ in jobs])
        ratio = np.concatenate([np.asarray(r, dtype=np.float64) for *_, r in jobs])[:, None]
        u = self.settings
        out = vehicle_integrate(
            start,
            accel,
            duration,
            ratio,
            u.vehicle_yaw_rate_change,
            u.vehicle_trajectory_calculation_step,
            self.vcap,
            self.rmin,
        )
        bounds = np.cumsum([0, *sizes])
        return [_rows(out, slice(lo, hi)) for lo, hi in itertools.pairwise(bounds)]

    def arc(self, p: Points, accel: float, duration: Real) -> Points:
        return vehicle_arc(p, accel, duration, self.vcap, self.rmin)

    def response_time_job(self, speed: Real, accel: float, steps: int) -> Job:
        """Job of the points at rho for ratios right..left then centre (``2 (steps + 1) + 1``)."""
        right, left = change_ratios(steps)
        ratios = np.concatenate((right, left, [0.0]))
        return self.start(speed), accel, time_in_movement(speed, accel, self.rho), ratios


def _rows(p: Points, index: slice | int | np.ndarray) -> Points:
    return Points(
        p.x_m[index], p.y_m[index], p.yaw_rad[index], p.speed_mps[index], p.yaw_rate_radps[index]
    )


def vehicle_sets(
    agents: UnstructuredAgents, dyn: RssDynamics, front_extra_m: Real
) -> TrajectorySets:
    """Brake and continue-forward sets of ``N`` vehicles sharing one dynamics.

    Args:
        agents: The vehicles ``(N,)``.
        dyn: Their dynamics (incl. unstructured settings).
        front_extra_m: ``(N,)`` footprint extension in front (ego: min longitudinal
            safety distance, others 0).

    Returns:
        The pieces (owner = index into ``agents``).
    """
    v = _Vehicle(agents, dyn, front_extra_m)
    u, d = v.settings, dyn
    n = len(agents)
    pieces = PieceCollector(n)
    t_after = np.maximum(
        0.0,
        time_to_stop(agents.speed_max_mps, v.rho, v.vcap, d.accel_max_mps2, d.brake_min_mps2)
        - v.rho,
    )
    nf = u.vehicle_front_intermediate_yaw_rate_change_ratio_steps + 1
    nb = u.vehicle_back_intermediate_yaw_rate_change_ratio_steps + 1
    front, back = v.integrate_many(
        [
            v.response_time_job(agents.speed_max_mps, d.accel_max_mps2, nf - 1),
            v.response_time_job(agents.speed_min_mps, d.brake_max_mps2, nb - 1),
        ]
    )
    f_left, f_centre, f_right = _rows(front, -2), _rows(front, -1), _rows(front, 0)
    # brake: back side, brake_max to standstill
    v_bc = back.speed_mps[-1]
    t_bm = np.where(gt(v_bc, 0.0, SPEED_PRECISION), v_bc / -d.brake_max_mps2, 0.0)
    back_fp = v.fp(v.arc(back, d.brake_max_mps2, t_bm))
    b_right, b_left, b_centre = back_fp[:nb], back_fp[nb : 2 * nb], back_fp[-1]
    pieces.add(b_left, b_centre, brake=True)
    pieces.add(b_centre, b_right, brake=True)
    brake_max_loc: Location = (b_left[-1], b_centre, b_right[0])
    # brake: front (brake_min) and sides (brake_max .. brake_min)
    front_fp = v.fp(v.arc(front, d.brake_min_mps2, t_after))
    corner_rows = np.array([nf + nf - 1, 2 * nf, 0])  # max left, centre, max right
    corners = _rows(front, corner_rows)
    sides = []
    for accel in step_accelerations(
        d.brake_max_mps2, d.brake_min_mps2, u.vehicle_brake_intermediate_acceleration_steps
    ):
        t = time_in_movement(f_centre.speed_mps, accel, t_after)
        fp = v.fp(v.arc(corners, accel, t))
        sides.append((fp[0], fp[1], fp[2]))
    brake_min_loc = front_and_sides(
        pieces,
        brake_max_loc,
        sides,
        (front_fp[nf : 2 * nf], front_fp[-1], front_fp[:nf]),
        brake=True,
    )
    current = v.fp(v.start(agents.speed_min_mps))
    pieces.add(*brake_max_loc, current, brake=True)
    # continue forward: front with accel_max (further yaw-rate change), sides up to accel_max
    cf_fp = v.fp(v.arc(front, d.accel_max_mps2, t_after))
    right_r, left_r = change_ratios(
        u.vehicle_continue_forward_intermediate_yaw_rate_change_ratio_steps
    )
    cf_accels = step_accelerations(
        d.brake_min_mps2,
        d.accel_max_mps2,
        u.vehicle_continue_forward_intermediate_acceleration_steps,
    )
    cf_times = [time_in_movement(f_centre.speed_mps, a, t_after) for a in cf_accels]
    one, minus_one = np.ones(1), -np.ones(1)
    extra_left, extra_right, *cf_lr = v.integrate_many(
        [
            (f_left, d.accel_max_mps2, t_after, left_r),
            (f_right, d.accel_max_mps2, t_after, right_r),
            *(
                job
                for a, t in zip(cf_accels, cf_times, strict=True)
                for job in ((f_left, a, t, one), (f_right, a, t, minus_one))
            ),
        ]
    )
    cf_front = (
        np.concatenate((cf_fp[nf : 2 * nf], v.fp(extra_left))),
        cf_fp[-1],
        np.concatenate((v.fp(extra_right), cf_fp[:nf])),
    )
    cf_sides = [
        (v.fp(cf_lr[2 * k]), v.fp(v.arc(f_centre, a, t)), v.fp(cf_lr[2 * k + 1]))
        for k, (a, t) in enumerate(zip(cf_accels, cf_times, strict=True))
    ]
    front_and_sides(pieces, brake_min_loc, cf_sides, cf_front, brake=False)
    pieces.add(*brake_min_loc, current, brake=False)
    return pieces.build()
