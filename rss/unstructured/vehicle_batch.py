"""Vehicle trajectory sets, fast: every point of a batch in two (wide batches: three) kernel calls.

Same model and pieces as the step-by-step :func:`rss.unstructured.reference_vehicle.vehicle_sets`
(its reference; ``tests/rss/unstructured/test_batch.py`` holds them equal), but the agents
may have different dynamics values (one batch for the ego and every vehicle sharing the
unstructured settings) and the points are computed in two stacked calls:

1. :func:`vehicle_integrate` with two phases: response time, front (``accel_max`` from
   ``speed_max``) and back (``brake_max`` from ``speed_min``) for every yaw-rate ratio,
   and the continue-forward extremes (the outermost front rows continued after rho with
   a further yaw-rate change); in wide batches (many frames) the response-time rows get a
   call of their own (:data:`SPLIT_MIN_AGENTS`), so they do not idle through the second
   phase;
2. :func:`vehicle_arc`: every arc after the response time (back to standstill, front with
   ``brake_min`` and ``accel_max``, the side accelerations).

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
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from rss.physics import ACCELERATION_PRECISION, SPEED_PRECISION, gt, lt
from rss.unstructured.batch import PiecePlan, RowPieces, constant, sets_of_points, span
from rss.unstructured.kinematics import (
    Phase,
    Points,
    change_ratios,
    time_in_movement,
    time_to_stop,
    vehicle_arc,
    vehicle_integrate,
)
from rss.unstructured.sets import front_and_sides

if TYPE_CHECKING:
    from rss.arrays import BoolArray, FloatArray, IntArray
    from rss.dynamics import UnstructuredSettings
    from rss.unstructured.agents import UnstructuredAgents
    from rss.unstructured.batch import AgentDynamics
    from rss.unstructured.sets import TrajectorySets

__all__ = [
    "SPLIT_MIN_AGENTS",
    "VehicleLayout",
    "step_accelerations_batch",
    "vehicle_counts",
    "vehicle_layout",
    "vehicle_plan",
    "vehicle_sets_batch",
    "vehicle_sets_of_points",
]


def step_accelerations_batch(low: FloatArray, high: FloatArray, steps: int) -> FloatArray:
    """``(steps + 1, N)`` accelerations: ``low + k·Δ`` (k = 1..steps) below ``high``, then ``high``.

    :func:`rss.unstructured.reference_vehicle.step_accelerations` per agent, with dropped steps
    replaced by ``high`` (a repeated last step).
    """
    k = np.arange(1, steps + 1, dtype=np.float64)[:, None]
    values = low + (high - low) / (1.0 + steps) * k
    values = np.where(lt(values, high, ACCELERATION_PRECISION), values, high)
    return np.concatenate((values, high[None]))


def vehicle_counts(u: UnstructuredSettings) -> tuple[int, int, int, int, int]:
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
    nf, nb, kb, kc, ncf = vehicle_counts(u)
    rf, rb = 2 * nf + 1, 2 * nb + 1
    o_fb = rb
    o_sides = o_fb + rf
    o_cf = o_sides + 3 * kb
    o_cfc = o_cf + rf
    o_el = o_cfc + kc
    o_er = o_el + ncf
    o_lr = o_er + ncf
    current = o_lr + 2 * kc

    pieces = RowPieces()
    b_right, b_left, b_centre = span(0, nb), span(nb, 2 * nb), rb - 1
    pieces.add(b_left, b_centre, brake=True)
    pieces.add(b_centre, b_right, brake=True)
    brake_max_loc = (b_left[-1], b_centre, b_right[0])
    sides = [(o_sides + 3 * k, o_sides + 3 * k + 1, o_sides + 3 * k + 2) for k in range(kb)]
    front = (span(o_fb + nf, o_fb + 2 * nf), o_fb + rf - 1, span(o_fb, o_fb + nf))
    brake_min_loc = front_and_sides(pieces, brake_max_loc, sides, front, brake=True)
    pieces.add(*brake_max_loc, current, brake=True)
    cf_front = (
        span(o_cf + nf, o_cf + 2 * nf) + span(o_el, o_el + ncf),
        o_cf + rf - 1,
        span(o_er, o_er + ncf) + span(o_cf, o_cf + nf),
    )
    cf_sides = [(o_lr + 2 * k, o_cfc + k, o_lr + 2 * k + 1) for k in range(kc)]
    front_and_sides(pieces, brake_min_loc, cf_sides, cf_front, brake=False)
    pieces.add(*brake_min_loc, current, brake=False)
    return pieces.plan()


@dataclass(frozen=True)
class VehicleLayout:
    """Constant row arrays of one settings (see :func:`vehicle_sets_batch`).

    ``*_pick`` arrays index a per-agent palette of values (rows of a ``(V, N)`` stack).
    """

    rows1: IntArray  # (R,) start speed / accel / duration: 0 = front, 1 = back
    ratio1: FloatArray  # (R, 1)
    accel2_pick: IntArray  # (R,) into [0, accel_max, cf accels (Kc)]
    timed2: BoolArray  # (R, 1) rows with a second phase (duration t_after)
    ratio2: FloatArray  # (R, 1)
    response: IntArray  # (rf + rb,) the response-time rows of the output
    extras: IntArray  # (2 Ncf + 2 Kc,) the continue-forward extremes
    arc_starts: IntArray  # (A,) start row of every arc
    arc_accel_pick: IntArray  # (A,) into [brake_max, brake_min, side (Kb), accel_max, cf (Kc)]
    arc_time_pick: IntArray  # (A,) into [t_back, t_after, side times (Kb), cf times (Kc)]


@functools.lru_cache(maxsize=16)
def vehicle_layout(u: UnstructuredSettings) -> VehicleLayout:
    """The row layout of :func:`vehicle_sets_batch` for one settings (cached)."""
    nf, nb, kb, kc, ncf = vehicle_counts(u)
    rf, rb = 2 * nf + 1, 2 * nb + 1
    n_extra = 2 * ncf + 2 * kc
    f_right, f_left = change_ratios(nf - 1)
    b_right, b_left = change_ratios(nb - 1)
    cf_right, cf_left = change_ratios(ncf - 1)
    outer = [f_left[-1], f_right[0]]
    left, centre, right = 2 * nf - 1, rf - 1, 0
    front = list(range(rf))

    return VehicleLayout(
        rows1=constant([0] * rf + [1] * rb + [0] * n_extra),
        ratio1=constant(
            [*f_right, *f_left, 0.0, *b_right, *b_left, 0.0, *np.repeat(outer, ncf), *outer * kc],
            np.float64,
        )[:, None],
        accel2_pick=constant(
            [0] * (rf + rb) + [1] * (2 * ncf) + [2 + k for k in range(kc) for _ in "lr"]
        ),
        timed2=constant([False] * (rf + rb) + [True] * n_extra, bool)[:, None],
        ratio2=constant([0.0] * (rf + rb) + [*cf_left, *cf_right] + [1.0, -1.0] * kc, np.float64)[
            :, None
        ],
        response=constant(range(rf + rb)),
        extras=constant(range(rf + rb, rf + rb + n_extra)),
        arc_starts=constant(
            [*range(rf, rf + rb), *front, *[left, centre, right] * kb, *front, *[centre] * kc]
        ),
        arc_accel_pick=constant(
            [0] * rb
            + [1] * rf
            + [2 + k for k in range(kb) for _ in "lcr"]
            + [2 + kb] * rf
            + [3 + kb + k for k in range(kc)]
        ),
        arc_time_pick=constant(
            [0] * rb
            + [1] * rf
            + [2 + k for k in range(kb) for _ in "lcr"]
            + [1] * rf
            + [2 + kb + k for k in range(kc)]
        ),
    )


def _take(p: Points, rows: IntArray) -> Points:
    """Rows of ``(R, N)`` points."""
    return Points(
        p.x_m[rows], p.y_m[rows], p.yaw_rad[rows], p.speed_mps[rows], p.yaw_rate_radps[rows]
    )


#: Agents from which the response-time rows are integrated apart from the two-phase rows.
SPLIT_MIN_AGENTS = 16

_FIELDS = ("x_m", "y_m", "yaw_rad", "speed_mps", "yaw_rate_radps")


def _integrate(  # noqa: PLR0917  (the arguments of vehicle_integrate)
    u: UnstructuredSettings,
    p: Points,
    accel: FloatArray,
    duration: FloatArray,
    ratio: FloatArray,
    vcap: FloatArray,
    then: Phase,
    single: int,
) -> Points:
    """:func:`vehicle_integrate` of the ``(R, N)`` rows, the first ``single`` without ``then``.

    The step grid spans the longest phases of all rows, so in one call the response-time
    rows idle through the whole second phase. From :data:`SPLIT_MIN_AGENTS` agents on (a
    batch of many frames) they get their own call: the same points, about half the work.
    """

    def call(rows: slice, phase: Phase | None) -> Points:
        def cut(v: FloatArray) -> FloatArray:
            return v[rows] if np.ndim(v) == 2 else v  # noqa: PLR2004  ((R, N) or (N,))

        return vehicle_integrate(
            Points(*(cut(getattr(p, f)) for f in _FIELDS)),
            cut(accel),
            cut(duration),
            cut(ratio),
            u.vehicle_yaw_rate_change,
            u.vehicle_trajectory_calculation_step,
            vcap,
            u.vehicle_min_radius,
            phase and Phase(*(cut(v) for v in (phase.accel_mps2, phase.duration_s, phase.ratio))),
        )

    if np.shape(vcap)[0] < SPLIT_MIN_AGENTS:
        return call(slice(None), then)
    first, rest = call(slice(0, single), None), call(slice(single, None), then)
    return Points(*(np.concatenate((getattr(first, f), getattr(rest, f))) for f in _FIELDS))


def vehicle_sets_batch(agents: UnstructuredAgents, dyn: AgentDynamics) -> TrajectorySets:
    """Brake and continue-forward sets of ``N`` vehicles (per-agent dynamics values).

    1. One stepped integration (two phases): the response time of the front rows
       ``[right nf | left nf | centre]`` and of the back rows (likewise), and the
       continue-forward extremes, which continue the outermost front rows with a second
       phase (further yaw-rate change; its duration is ``t_after`` also for braking
       intermediate accelerations, where the reference cuts it at standstill: the same
       end points up to rounding).
    2. One arc call for everything after the response time.
    3. Footprints of all rows, then the pieces of :func:`vehicle_plan`.

    Args:
        agents: The vehicles ``(N,)``.
        dyn: Their dynamics ``(N,)`` (one settings).

    Returns:
        The pieces (owner = index into ``agents``).
    """
    u, a = dyn.settings, agents
    nf, _, kb, kc, _ = vehicle_counts(u)
    lay = vehicle_layout(u)
    rho, vcap = dyn.response_time_s, dyn.max_speed_mps
    amax, bmax, bmin = dyn.accel_max_mps2, dyn.brake_max_mps2, dyn.brake_min_mps2
    t_after = np.maximum(0.0, time_to_stop(a.speed_max_mps, rho, vcap, amax, bmin) - rho)
    cf_accels = step_accelerations_batch(bmin, amax, kc - 1)
    speed = np.stack((a.speed_max_mps, a.speed_min_mps))
    accel = np.stack((amax, bmax))
    out = _integrate(
        u,
        Points(a.x_m, a.y_m, a.yaw_rad, speed[lay.rows1], a.yaw_rate_radps),
        accel[lay.rows1],
        time_in_movement(speed, accel, rho)[lay.rows1],
        lay.ratio1,
        vcap,
        Phase(
            np.concatenate((np.zeros((1, len(a))), amax[None], cf_accels))[lay.accel2_pick],
            np.where(lay.timed2, t_after, 0.0),
            lay.ratio2,
        ),
        lay.response.size,
    )
    rt = _take(out, lay.response)
    v_centre = rt.speed_mps[2 * nf]  # the front centre row
    v_back = rt.speed_mps[-1]
    t_back = np.where(gt(v_back, 0.0, SPEED_PRECISION), v_back / -bmax, 0.0)
    side_accels = step_accelerations_batch(bmax, bmin, kb - 1)
    times = time_in_movement(v_centre, np.concatenate((side_accels, cf_accels)), t_after)
    arcs = vehicle_arc(
        _take(rt, lay.arc_starts),
        np.concatenate((bmax[None], bmin[None], side_accels, amax[None], cf_accels))[
            lay.arc_accel_pick
        ],
        np.concatenate((t_back[None], t_after[None], times))[lay.arc_time_pick],
        vcap,
        u.vehicle_min_radius,
    )
    extra_points = _take(out, lay.extras)
    x, y, yaw = (
        np.concatenate((getattr(arcs, f), getattr(extra_points, f), getattr(a, f)[None]))
        for f in ("x_m", "y_m", "yaw_rad")
    )
    return vehicle_sets_of_points(x, y, yaw, agents, dyn)


def vehicle_sets_of_points(
    x_m: FloatArray,
    y_m: FloatArray,
    yaw_rad: FloatArray,
    agents: UnstructuredAgents,
    dyn: AgentDynamics,
) -> TrajectorySets:
    """The pieces from the poses ``(R, N)`` of the table's rows (arcs, extras, current)."""
    return sets_of_points(x_m, y_m, yaw_rad, agents, dyn, plan=vehicle_plan(dyn.settings))
