"""Pedestrian trajectory sets, fast: every point of a batch in two kernel calls.

Same model and pieces as the step-by-step
:func:`rss.unstructured.reference_pedestrian.pedestrian_sets` (its reference;
``tests/rss/unstructured/test_batch.py`` holds them equal), with per-agent dynamics values.
Moving pedestrians: one :func:`pedestrian_move_timed` for the response
time (front and back, every heading ratio) and one :func:`pedestrian_move` for everything
after it; the rows of the footprint table (``R`` rows of ``N`` agents)::

    b_front (rf) | sides (3 Sb) | back (rb) | cf front (rf) | extra left (Ncf)
    | extra right (Ncf) | cf sides (3 Kc) | current (1)

Straight moves are moves with ratio 0 (the same formula). Standing pedestrians get the two
circles of the reference.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass
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
from rss.unstructured.batch import (
    CORNERS,
    PiecePlan,
    RowPieces,
    constant,
    plan_sets,
    sets_of_points,
    span,
)
from rss.unstructured.kinematics import (
    CIRCLE_VERTICES,
    Points,
    change_ratios,
    pedestrian_move,
    pedestrian_move_timed,
    time_to_stop,
)
from rss.unstructured.sets import TrajectorySets, front_and_sides

if TYPE_CHECKING:
    from collections.abc import Callable

    from rss.arrays import FloatArray, IntArray
    from rss.dynamics import UnstructuredSettings
    from rss.unstructured.agents import UnstructuredAgents
    from rss.unstructured.batch import AgentDynamics

__all__ = [
    "PedestrianLayout",
    "pedestrian_counts",
    "pedestrian_layout",
    "pedestrian_plan",
    "pedestrian_sets_batch",
    "pedestrian_sets_of_points",
]

#: A standing pedestrian: the brake circle, then the continue-forward circle.
_CIRCLES = PiecePlan(
    np.arange(2 * CIRCLE_VERTICES).reshape(2, CIRCLE_VERTICES),
    np.full(2, CIRCLE_VERTICES),
    np.array([True, False]),
)


def pedestrian_counts(u: UnstructuredSettings) -> tuple[int, int, int, int, int]:
    """``(nf, nb, Sb, Kc, Ncf)``: ratios per side front / back, side steps, cf extremes."""
    return (
        u.pedestrian_front_intermediate_heading_change_ratio_steps + 1,
        u.pedestrian_back_intermediate_heading_change_ratio_steps + 1,
        u.pedestrian_brake_intermediate_acceleration_steps,
        u.pedestrian_continue_forward_intermediate_acceleration_steps + 2,
        u.pedestrian_continue_forward_intermediate_heading_change_ratio_steps + 1,
    )


@functools.lru_cache(maxsize=16)
def pedestrian_plan(u: UnstructuredSettings) -> PiecePlan:
    """The pieces of one moving pedestrian over the rows of the footprint table."""
    nf, nb, sb, kc, ncf = pedestrian_counts(u)
    rf, rb = 2 * nf + 1, 2 * nb + 1
    o_sides = rf
    o_back = o_sides + 3 * sb
    o_cf = o_back + rb
    o_el = o_cf + rf
    o_er = o_el + ncf
    o_cfs = o_er + ncf
    current = o_cfs + 3 * kc

    def triple(start: int) -> tuple[int, int, int]:
        return (start, start + 1, start + 2)

    pieces = RowPieces()
    left_b, right_b = o_back + 2 * nb - 1, o_back
    brake_max_loc = (left_b, o_back + rb - 1, right_b)
    pieces.add_corners(
        [CORNERS * right_b + 3, CORNERS * right_b, CORNERS * left_b + 2, CORNERS * left_b + 1],
        brake=True,
    )
    sides = [triple(o_sides + 3 * k) for k in range(sb)]
    front = (span(nf, 2 * nf), rf - 1, span(0, nf))
    front_and_sides(pieces, brake_max_loc, sides, front, brake=True)
    pieces.add(*brake_max_loc, current, brake=True)
    cf_front = (
        span(o_cf + nf, o_cf + 2 * nf) + span(o_el, o_el + ncf),
        o_cf + rf - 1,
        span(o_cf, o_cf + nf) + span(o_er, o_er + ncf),
    )
    cf_sides = [triple(o_cfs + 3 * k) for k in range(kc)]
    front_and_sides(pieces, brake_max_loc, cf_sides, cf_front, brake=False)
    return pieces.plan()


def pedestrian_sets_batch(
    agents: UnstructuredAgents,
    dyn: AgentDynamics,
    moving: Callable[[UnstructuredAgents, AgentDynamics], TrajectorySets] | None = None,
) -> TrajectorySets:
    """Brake and continue-forward sets of ``N`` pedestrians (per-agent dynamics values).

    Args:
        agents: The pedestrians ``(N,)``.
        dyn: Their dynamics ``(N,)`` (one settings).
        moving: Builder of the moving pedestrians' sets (``None``: the batched one; the
            point-by-point twin :func:`rss.unstructured.pedestrian_small.pedestrian_moving_small`
            gives the same sets).

    Returns:
        The pieces (owner = index into ``agents``).
    """
    n = len(agents)
    moving = moving or _moving
    standing = eq(agents.speed_max_mps, 0.0, SPEED_PRECISION)
    if not standing.any():
        return moving(agents, dyn)
    if standing.all():
        return _standing(agents, dyn)
    parts = []
    for mask, build in ((standing, _standing), (~standing, moving)):
        idx = np.flatnonzero(mask)
        parts.append((build(agents.take(idx), dyn.take(idx)), idx))
    return TrajectorySets.concat(parts, n)


def _t_stop(agents: UnstructuredAgents, dyn: AgentDynamics) -> FloatArray:
    return time_to_stop(
        agents.speed_max_mps,
        dyn.response_time_s,
        dyn.max_speed_mps,
        dyn.accel_max_mps2,
        dyn.brake_min_mps2,
    )


def _standing(agents: UnstructuredAgents, dyn: AgentDynamics) -> TrajectorySets:
    """Circles around the centre (:func:`rss.unstructured.reference_pedestrian._standing`)."""
    rho, vcap = dyn.response_time_s, dyn.max_speed_mps
    t_stop = _t_stop(agents, dyn)
    t_rho = np.minimum(t_stop, rho)
    v_rho, d_rho = accelerated_limited_movement(
        agents.speed_max_mps, vcap, dyn.accel_max_mps2, t_rho
    )
    after = gt(t_stop, rho, 1e-3)
    _, d_after = accelerated_limited_movement(
        v_rho,
        vcap,
        np.stack((dyn.brake_min_mps2, dyn.accel_max_mps2)),
        np.maximum(t_stop - rho, 0.0),
    )
    radius = d_rho + np.where(after, d_after, 0.0)  # (2, N): brake, continue forward
    angles = np.arange(CIRCLE_VERTICES) * (2.0 * np.pi / CIRCLE_VERTICES)
    x = agents.x_m + np.cos(angles)[None, :, None] * radius[:, None]
    y = agents.y_m + np.sin(angles)[None, :, None] * radius[:, None]
    table = np.stack((x, y), axis=-1).reshape(2 * CIRCLE_VERTICES, len(agents), 2)
    return plan_sets(table, _CIRCLES)


@dataclass(frozen=True)
class PedestrianLayout:
    """Constant row arrays of one settings (see :func:`_moving`)."""

    phase: IntArray  # (rf + rb,) 0 = front (speed_max, accel_max), 1 = back
    ratio_rt: FloatArray  # (rf + rb, 1) heading-change ratios during rho
    starts: IntArray  # (M,) start row of every move after rho (rf + rb = the current pose)
    dist_pick: IntArray  # (M,) into [brake_min, brake_max, accel_max, sides (Sb), cf (Kc), 0]
    ratio: FloatArray  # (M, 1) heading-change ratio of every move


@functools.lru_cache(maxsize=16)
def pedestrian_layout(u: UnstructuredSettings) -> PedestrianLayout:
    """The row layout of :func:`_moving` for one settings (cached)."""
    nf, nb, sb, kc, ncf = pedestrian_counts(u)
    rf, rb = 2 * nf + 1, 2 * nb + 1
    f_right, f_left = change_ratios(nf - 1)
    b_right, b_left = change_ratios(nb - 1)
    cf_right, cf_left = change_ratios(ncf - 1)
    start = rf + rb
    left, centre, right = 2 * nf - 1, rf - 1, 0
    front = list(range(rf))
    lr = [1.0, 0.0, -1.0]

    return PedestrianLayout(
        phase=constant([0] * rf + [1] * rb),
        ratio_rt=constant([*f_right, *f_left, 0.0, *b_right, *b_left, 0.0], np.float64)[:, None],
        starts=constant(
            [
                *front,
                *[start] * (3 * sb),
                *range(rf, rf + rb),
                *front,
                *[left] * ncf,
                *[right] * ncf,
                *[left, centre, right] * kc,
                start,
            ]
        ),
        dist_pick=constant(
            [0] * rf
            + [3 + k for k in range(sb) for _ in lr]
            + [1] * rb
            + [2] * (rf + 2 * ncf)
            + [3 + sb + k for k in range(kc) for _ in lr]
            + [3 + sb + kc]
        ),
        ratio=constant(
            [0.0] * rf + lr * sb + [0.0] * (rb + rf) + [*cf_left, *cf_right] + lr * kc + [0.0],
            np.float64,
        )[:, None],
    )


def _moving(agents: UnstructuredAgents, dyn: AgentDynamics) -> TrajectorySets:
    """Moving pedestrians (:func:`rss.unstructured.reference_pedestrian._moving`)."""
    u, a = dyn.settings, agents
    nf, _, sb, kc, _ = pedestrian_counts(u)
    lay = pedestrian_layout(u)
    rho, vcap, radius = dyn.response_time_s, dyn.max_speed_mps, u.pedestrian_turning_radius
    amax, bmax, bmin = dyn.accel_max_mps2, dyn.brake_max_mps2, dyn.brake_min_mps2
    zeros = np.zeros(len(a))
    # response time: front rows [right nf | left nf | centre], then back rows likewise
    rt = pedestrian_move_timed(
        Points(
            a.x_m, a.y_m, a.yaw_rad, np.stack((a.speed_max_mps, a.speed_min_mps))[lay.phase], zeros
        ),
        np.stack((amax, bmax))[lay.phase],
        rho,
        lay.ratio_rt,
        radius,
        vcap,
    )
    # distances after rho: back brake_max to standstill, front brake_min / accel_max, rho
    v_back, v_front = rt.speed_mps[-1], rt.speed_mps[2 * nf]
    t_back = np.where(gt(v_back, 0.0, SPEED_PRECISION), v_back / -bmax, 0.0)
    t_after = np.maximum(0.0, _t_stop(a, dyn) - rho)
    _, dist = accelerated_limited_movement(
        np.stack((v_back, v_front, v_front, a.speed_max_mps)),
        vcap,
        np.stack((bmax, bmin, amax, amax)),
        np.stack((t_back, t_after, t_after, rho)),
    )
    brake_max_d, brake_min_d, accel_max_d = dist[:3]
    side_d = dist[3] / (1.0 + sb) * np.arange(1, sb + 1)[:, None]
    width = (accel_max_d - brake_max_d) / (kc - 1.0)
    cf_d = brake_max_d + width * np.arange(kc)[:, None]
    cf_d = np.where(le(cf_d, accel_max_d, DISTANCE_PRECISION), cf_d, accel_max_d)
    palette = np.concatenate(
        (brake_min_d[None], brake_max_d[None], accel_max_d[None], side_d, cf_d, zeros[None])
    )
    # every move after rho starts from a response-time row or the current pose
    x, y, yaw, speed = (
        np.concatenate((getattr(rt, f), start[None]))[lay.starts]
        for f, start in (
            ("x_m", a.x_m),
            ("y_m", a.y_m),
            ("yaw_rad", a.yaw_rad),
            ("speed_mps", a.speed_min_mps),
        )
    )
    moved = pedestrian_move(
        Points(x, y, yaw, speed, zeros), palette[lay.dist_pick], lay.ratio, radius
    )
    return pedestrian_sets_of_points(moved.x_m, moved.y_m, moved.yaw_rad, agents, dyn)


def pedestrian_sets_of_points(
    x_m: FloatArray,
    y_m: FloatArray,
    yaw_rad: FloatArray,
    agents: UnstructuredAgents,
    dyn: AgentDynamics,
) -> TrajectorySets:
    """The pieces of moving pedestrians from the poses ``(R, N)`` of the footprint table's rows."""
    return sets_of_points(x_m, y_m, yaw_rad, agents, dyn, plan=pedestrian_plan(dyn.settings))
