"""Vehicle trajectory sets, fast: every point of a batch in three kernel calls.

Same model and pieces as the step-by-step :func:`rss.unstructured.vehicle.vehicle_sets`
(its reference; ``tests/rss/unstructured/test_batch.py`` holds them equal), but the agents
may have different dynamics values (one batch for the ego and every vehicle sharing the
unstructured settings) and the points are computed in three stacked calls:

1. :func:`vehicle_integrate`: response time, front (``accel_max`` from ``speed_max``) and
   back (``brake_max`` from ``speed_min``), every yaw-rate ratio;
2. :func:`vehicle_arc`: every arc after the response time (back to standstill, front with
   ``brake_min`` and ``accel_max``, the side accelerations);
3. :func:`vehicle_integrate`: the continue-forward extremes (further yaw-rate change).

The rows of the footprint table (``R`` rows of ``N`` agents)::

    arcs:    back (rb) | front brake_min (rf) | sides (3 Kb) | front accel_max (rf)
             | cf centres (Kc)
    extras:  left (Ncf) | right (Ncf) | cf left/right (2 Kc)
    current: 1

The side accelerations are ``(K, N)`` arrays: an agent whose intermediate steps collapse
(``brake_max == brake_min``) repeats its last step instead of dropping it, which adds
copies of pieces and leaves the union unchanged.
"""

from __future__ import annotations

import functools
from typing import TYPE_CHECKING

import numpy as np

from rss.physics import ACCELERATION_PRECISION, SPEED_PRECISION, gt, lt
from rss.unstructured.batch import PiecePlan, RowPieces, plan_sets
from rss.unstructured.kinematics import (
    Points,
    footprints,
    time_in_movement,
    time_to_stop,
    vehicle_arc,
    vehicle_integrate,
)
from rss.unstructured.sets import front_and_sides
from rss.unstructured.vehicle import ratio_pairs

if TYPE_CHECKING:
    from rss.batch import FloatArray
    from rss.dynamics import UnstructuredSettings
    from rss.unstructured.agents import UnstructuredAgents
    from rss.unstructured.batch import AgentDynamics
    from rss.unstructured.sets import TrajectorySets

__all__ = ["step_accelerations_batch", "vehicle_plan", "vehicle_sets_batch"]


def step_accelerations_batch(low: FloatArray, high: FloatArray, steps: int) -> FloatArray:
    """``(steps + 1, N)`` accelerations: ``low + k·Δ`` (k = 1..steps) below ``high``, then ``high``.

    :func:`rss.unstructured.vehicle.step_accelerations` per agent, with dropped steps
    replaced by ``high`` (a repeated last step).
    """
    k = np.arange(1, steps + 1, dtype=np.float64)[:, None]
    values = low + (high - low) / (1.0 + steps) * k
    values = np.where(lt(values, high, ACCELERATION_PRECISION), values, high)
    return np.concatenate((values, high[None]))


def _counts(u: UnstructuredSettings) -> tuple[int, int, int, int, int]:
    """``(nf, nb, Kb, Kc, Ncf)``: ratios per side front / back, side steps, cf extremes."""
    return (
        u.vehicle_front_intermediate_yaw_rate_change_ratio_steps + 1,
        u.vehicle_back_intermediate_yaw_rate_change_ratio_steps + 1,
        u.vehicle_brake_intermediate_acceleration_steps + 1,
        u.vehicle_continue_forward_intermediate_acceleration_steps + 1,
        u.vehicle_continue_forward_intermediate_yaw_rate_change_ratio_steps + 1,
    )


@functools.lru_cache(maxsize=16)
def vehicle_plan(u: UnstructuredSettings) -> PiecePlan:
    """The pieces of one vehicle over the rows of the footprint table (module docstring)."""
    nf, nb, kb, kc, ncf = _counts(u)
    rf, rb = 2 * nf + 1, 2 * nb + 1
    o_fb = rb
    o_sides = o_fb + rf
    o_cf = o_sides + 3 * kb
    o_cfc = o_cf + rf
    o_el = o_cfc + kc
    o_er = o_el + ncf
    o_lr = o_er + ncf
    current = o_lr + 2 * kc

    def rows(start: int, stop: int) -> list[int]:
        return list(range(start, stop))

    pieces = RowPieces()
    b_right, b_left, b_centre = rows(0, nb), rows(nb, 2 * nb), rb - 1
    pieces.add(b_left, b_centre, brake=True)
    pieces.add(b_centre, b_right, brake=True)
    brake_max_loc = (b_left[-1], b_centre, b_right[0])
    sides = [(o_sides + 3 * k, o_sides + 3 * k + 1, o_sides + 3 * k + 2) for k in range(kb)]
    front = (rows(o_fb + nf, o_fb + 2 * nf), o_fb + rf - 1, rows(o_fb, o_fb + nf))
    brake_min_loc = front_and_sides(pieces, brake_max_loc, sides, front, brake=True)
    pieces.add(*brake_max_loc, current, brake=True)
    cf_front = (
        rows(o_cf + nf, o_cf + 2 * nf) + rows(o_el, o_el + ncf),
        o_cf + rf - 1,
        rows(o_er, o_er + ncf) + rows(o_cf, o_cf + nf),
    )
    cf_sides = [(o_lr + 2 * k, o_cfc + k, o_lr + 2 * k + 1) for k in range(kc)]
    front_and_sides(pieces, brake_min_loc, cf_sides, cf_front, brake=False)
    pieces.add(*brake_min_loc, current, brake=False)
    return pieces.plan()


def _take(p: Points, rows: list[int]) -> Points:
    """Rows of ``(R, N)`` points."""
    return Points(
        p.x_m[rows], p.y_m[rows], p.yaw_rad[rows], p.speed_mps[rows], p.yaw_rate_radps[rows]
    )


def vehicle_sets_batch(agents: UnstructuredAgents, dyn: AgentDynamics) -> TrajectorySets:
    """Brake and continue-forward sets of ``N`` vehicles (per-agent dynamics values).

    Args:
        agents: The vehicles ``(N,)``.
        dyn: Their dynamics ``(N,)`` (one settings).

    Returns:
        The pieces (owner = index into ``agents``).
    """
    u = dyn.settings
    nf, nb, kb, kc, ncf = _counts(u)
    rf, rb = 2 * nf + 1, 2 * nb + 1
    rho, vcap = dyn.response_time_s, dyn.max_speed_mps
    amax, bmax, bmin = dyn.accel_max_mps2, dyn.brake_max_mps2, dyn.brake_min_mps2
    a = agents
    t_after = np.maximum(0.0, time_to_stop(a.speed_max_mps, rho, vcap, amax, bmin) - rho)

    def integrate(p: Points, accel: FloatArray, duration: FloatArray, ratio: FloatArray) -> Points:
        return vehicle_integrate(
            p,
            accel,
            duration,
            ratio[:, None],
            u.vehicle_yaw_rate_change,
            u.vehicle_trajectory_calculation_step,
            vcap,
            u.vehicle_min_radius,
        )

    # 1. response time: front rows [right nf | left nf | centre], then back rows likewise
    f_right, f_left = ratio_pairs(nf - 1)
    b_right, b_left = ratio_pairs(nb - 1)
    phase = np.repeat([0, 1], [rf, rb])
    speed = np.stack((a.speed_max_mps, a.speed_min_mps))
    accel = np.stack((amax, bmax))
    rt = integrate(
        Points(a.x_m, a.y_m, a.yaw_rad, speed[phase], a.yaw_rate_radps),
        accel[phase],
        time_in_movement(speed, accel, rho)[phase],
        np.concatenate((f_right, f_left, [0.0], b_right, b_left, [0.0])),
    )
    left, centre, right = 2 * nf - 1, rf - 1, 0
    v_centre = rt.speed_mps[centre]
    # 2. arcs after the response time
    v_back = rt.speed_mps[-1]
    t_back = np.where(gt(v_back, 0.0, SPEED_PRECISION), v_back / -bmax, 0.0)
    side_accels = step_accelerations_batch(bmax, bmin, kb - 1)
    cf_accels = step_accelerations_batch(bmin, amax, kc - 1)
    side_times = time_in_movement(v_centre, side_accels, t_after)
    cf_times = time_in_movement(v_centre, cf_accels, t_after)
    front_rows = list(range(rf))
    starts = [*range(rf, rf + rb), *front_rows, *[left, centre, right] * kb, *front_rows]
    arc_accel = np.concatenate(
        (
            np.broadcast_to(bmax, (rb, len(a))),
            np.broadcast_to(bmin, (rf, len(a))),
            np.repeat(side_accels, 3, axis=0),
            np.broadcast_to(amax, (rf, len(a))),
            cf_accels,
        )
    )
    arc_time = np.concatenate(
        (
            np.broadcast_to(t_back, (rb, len(a))),
            np.broadcast_to(t_after, (rf, len(a))),
            np.repeat(side_times, 3, axis=0),
            np.broadcast_to(t_after, (rf, len(a))),
            cf_times,
        )
    )
    arcs = vehicle_arc(
        _take(rt, starts + [centre] * kc), arc_accel, arc_time, vcap, u.vehicle_min_radius
    )
    # 3. continue-forward extremes: further yaw-rate change from the front corners
    cf_right, cf_left = ratio_pairs(ncf - 1)
    extras = integrate(
        _take(rt, [left] * ncf + [right] * ncf + [left, right] * kc),
        np.concatenate((np.broadcast_to(amax, (2 * ncf, len(a))), np.repeat(cf_accels, 2, axis=0))),
        np.concatenate(
            (np.broadcast_to(t_after, (2 * ncf, len(a))), np.repeat(cf_times, 2, axis=0))
        ),
        np.concatenate((cf_left, cf_right, np.tile([1.0, -1.0], kc))),
    )
    current = Points(a.x_m, a.y_m, a.yaw_rad, a.speed_min_mps, a.yaw_rate_radps)
    points = Points(
        *(
            np.concatenate((getattr(arcs, f), getattr(extras, f), getattr(current, f)[None]))
            for f in ("x_m", "y_m", "yaw_rad", "speed_mps", "yaw_rate_radps")
        )
    )
    corners = footprints(points, a.length_m, a.width_m, dyn.front_extra_m)
    table = np.moveaxis(corners, 2, 1).reshape(-1, len(a), 2)
    return plan_sets(table, vehicle_plan(u))
