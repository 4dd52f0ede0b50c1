"""Pedestrian trajectory sets (ad-rss ``TrajectoryPedestrian``), step by step.

The reference of :mod:`rss.unstructured.pedestrian_batch` (which the engine runs): one
dynamics per call, one kernel call per step in ad-rss' order.

During the response time rho the heading change is bounded by circles of radius
``pedestrian_turning_radius / ratio``; after rho the pedestrian walks straight (the
continue-forward front also keeps turning). A standing pedestrian (``speed_max == 0``)
gets circles (20-gons) around its centre, ignoring its footprint: brake radius with
``accel_max`` during rho and ``brake_min`` after, continue-forward radius with ``accel_max``
throughout, both over the stop horizon.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from rss.physics import (
    DISTANCE_PRECISION,
    SPEED_PRECISION,
    accelerated_limited_movement,
    eq,
    gt,
    le,
)
from rss.unstructured.kinematics import (
    CIRCLE_VERTICES,
    Points,
    change_ratios,
    footprints,
    pedestrian_move,
    pedestrian_move_timed,
    straight_move,
    time_to_stop,
)
from rss.unstructured.sets import Location, PieceCollector, TrajectorySets, front_and_sides

if TYPE_CHECKING:
    from rss.arrays import FloatArray
    from rss.dynamics import RssDynamics
    from rss.unstructured.agents import UnstructuredAgents
    from rss.unstructured.kinematics import Real

__all__ = ["pedestrian_sets"]


def _rows(p: Points, index: slice | int | np.ndarray) -> Points:
    return Points(
        p.x_m[index], p.y_m[index], p.yaw_rad[index], p.speed_mps[index], p.yaw_rate_radps[index]
    )


def _speed_distance(
    speed: Real, vcap: Real, accel: Real, duration: Real
) -> tuple[FloatArray, FloatArray]:
    return accelerated_limited_movement(speed, vcap, accel, duration)


def _distance(speed: Real, vcap: Real, accel: Real, duration: Real) -> FloatArray:
    return _speed_distance(speed, vcap, accel, duration)[1]


def _circle(agents: UnstructuredAgents, radius: Real) -> FloatArray:
    angles = np.arange(CIRCLE_VERTICES) * (2.0 * np.pi / CIRCLE_VERTICES)
    x = agents.x_m[:, None] + np.cos(angles) * radius[:, None]
    y = agents.y_m[:, None] + np.sin(angles) * radius[:, None]
    return np.stack((x, y), axis=-1)


def _standing(
    agents: UnstructuredAgents, dyn: RssDynamics, pieces: PieceCollector, t_stop: Real
) -> None:
    d, rho = dyn, dyn.response_time_s
    t_rho = np.minimum(t_stop, rho)
    t_post = np.maximum(t_stop - rho, 0.0)
    v_rho, d_rho = _speed_distance(
        agents.speed_max_mps, d.max_speed_on_acceleration_mps, d.accel_max_mps2, t_rho
    )
    after = gt(t_stop, rho, 1e-3)
    brake_r = d_rho + np.where(
        after, _distance(v_rho, d.max_speed_on_acceleration_mps, d.brake_min_mps2, t_post), 0.0
    )
    cf_r = d_rho + np.where(
        after, _distance(v_rho, d.max_speed_on_acceleration_mps, d.accel_max_mps2, t_post), 0.0
    )
    pieces.add_points(_circle(agents, brake_r), brake=True)
    pieces.add_points(_circle(agents, cf_r), brake=False)


def pedestrian_sets(
    agents: UnstructuredAgents, dyn: RssDynamics, front_extra_m: Real
) -> TrajectorySets:
    """Brake and continue-forward sets of ``N`` pedestrians sharing one dynamics.

    Args:
        agents: The pedestrians ``(N,)``.
        dyn: Their dynamics.
        front_extra_m: ``(N,)`` footprint extension in front (0 for non-ego agents).

    Returns:
        The pieces (owner = index into ``agents``); standing and moving pedestrians
        both produce their pieces in one collector (unused ones are degenerate).
    """
    d, rho = dyn, dyn.response_time_s
    n = len(agents)
    standing = eq(agents.speed_max_mps, 0.0, SPEED_PRECISION)
    t_stop_max = time_to_stop(
        agents.speed_max_mps,
        rho,
        d.max_speed_on_acceleration_mps,
        d.accel_max_mps2,
        d.brake_min_mps2,
    )
    sets = []
    if standing.any():
        idx = np.flatnonzero(standing)
        sub = agents.take(idx)
        pieces = PieceCollector(len(idx))
        _standing(sub, dyn, pieces, t_stop_max[idx])
        sets.append((pieces.build(), idx))
    idx = np.flatnonzero(~standing)
    if idx.size:
        sub = agents.take(idx)
        sets.append((_moving(sub, dyn, front_extra_m[idx], t_stop_max[idx]), idx))
    return TrajectorySets.concat(sets, n)


def _moving(
    agents: UnstructuredAgents, dyn: RssDynamics, extra: Real, t_stop_max: FloatArray
) -> TrajectorySets:
    d, u, rho = dyn, dyn.unstructured, dyn.response_time_s
    vcap, radius = d.max_speed_on_acceleration_mps, u.pedestrian_turning_radius
    pieces = PieceCollector(len(agents))

    def fp(p: Points) -> FloatArray:
        return footprints(p, agents.length_m, agents.width_m, extra)

    def start(speed: Real) -> Points:
        return Points(agents.x_m, agents.y_m, agents.yaw_rad, speed, np.zeros_like(speed))

    def at_rho(speed: Real, accel: float, steps: int) -> tuple[Points, int]:
        right, left = change_ratios(steps)
        ratios = np.concatenate((right, left, [0.0]))[:, None]
        return pedestrian_move_timed(start(speed), accel, rho, ratios, radius, vcap), steps + 1

    front, nf = at_rho(
        agents.speed_max_mps,
        d.accel_max_mps2,
        u.pedestrian_front_intermediate_heading_change_ratio_steps,
    )
    back, nb = at_rho(
        agents.speed_min_mps,
        d.brake_max_mps2,
        u.pedestrian_back_intermediate_heading_change_ratio_steps,
    )
    v_bc, v_fc = back.speed_mps[-1], front.speed_mps[-1]
    t_bm = np.where(gt(v_bc, 0.0, SPEED_PRECISION), v_bc / -d.brake_max_mps2, 0.0)
    brake_max_dist = _distance(v_bc, vcap, d.brake_max_mps2, t_bm)
    t_after = np.maximum(0.0, t_stop_max - rho)
    brake_min_dist = _distance(v_fc, vcap, d.brake_min_mps2, t_after)
    accel_max_dist = _distance(v_fc, vcap, d.accel_max_mps2, t_after)
    # brake: front straight by the brake_min distance
    b_front = fp(straight_move(front, brake_min_dist))
    # brake sides: along the response-time arcs from the current pose
    dist_rho = _distance(agents.speed_max_mps, vcap, d.accel_max_mps2, rho)
    width = dist_rho / (1.0 + u.pedestrian_brake_intermediate_acceleration_steps)
    sides = []
    ratios = np.array([1.0, 0.0, -1.0])[:, None]
    for k in range(1, u.pedestrian_brake_intermediate_acceleration_steps + 1):
        dist = width * k
        fps = fp(pedestrian_move(start(agents.speed_max_mps), dist, ratios, radius))
        sides.append((fps[0], fps[1], fps[2]))
    # brake back: the extreme back points straight by the brake_max distance
    back_fp = fp(straight_move(back, brake_max_dist))
    brake_max_loc: Location = (back_fp[2 * nb - 1], back_fp[-1], back_fp[0])
    left_b, right_b = brake_max_loc[0], brake_max_loc[2]
    pieces.add_points(np.concatenate((right_b[:, [3, 0]], left_b[:, [2, 1]]), axis=1), brake=True)
    front_and_sides(
        pieces, brake_max_loc, sides, (b_front[nf : 2 * nf], b_front[-1], b_front[:nf]), brake=True
    )
    current = fp(start(agents.speed_min_mps))
    pieces.add(*brake_max_loc, current, brake=True)
    # continue forward: front straight by the accel_max distance plus turning extremes
    cf = fp(straight_move(front, accel_max_dist))
    right_r, left_r = change_ratios(
        u.pedestrian_continue_forward_intermediate_heading_change_ratio_steps
    )
    f_left, f_centre, f_right = _rows(front, 2 * nf - 1), _rows(front, -1), _rows(front, 0)
    extra_left = fp(pedestrian_move(f_left, accel_max_dist, left_r[:, None], radius))
    extra_right = fp(pedestrian_move(f_right, accel_max_dist, right_r[:, None], radius))
    cf_front = (
        np.concatenate((cf[nf : 2 * nf], extra_left)),
        cf[-1],
        np.concatenate((cf[:nf], extra_right)),
    )
    steps = u.pedestrian_continue_forward_intermediate_acceleration_steps
    width = (accel_max_dist - brake_max_dist) / (1.0 + steps)
    cf_sides = []
    lr = np.array([1.0, 0.0, -1.0])[:, None]
    for k in range(steps + 2):
        dist = brake_max_dist + width * k
        keep = le(dist, accel_max_dist, DISTANCE_PRECISION)
        dist = np.where(keep, dist, accel_max_dist)
        pts = Points(
            np.stack((f_left.x_m, f_centre.x_m, f_right.x_m)),
            np.stack((f_left.y_m, f_centre.y_m, f_right.y_m)),
            np.stack((f_left.yaw_rad, f_centre.yaw_rad, f_right.yaw_rad)),
            np.stack((f_left.speed_mps, f_centre.speed_mps, f_right.speed_mps)),
            np.zeros((3, len(agents))),
        )
        fps = fp(pedestrian_move(pts, dist, lr, radius))
        cf_sides.append((fps[0], fps[1], fps[2]))
    front_and_sides(pieces, brake_max_loc, cf_sides, cf_front, brake=False)
    return pieces.build()
