"""Vehicle trajectory sets of a few agents, point by point (compiled with mypyc).

One frame per call (an on-line monitor, the conformance command, a what-if), the batched
builder :func:`rss.unstructured.vehicle_batch.vehicle_sets_batch` spends its time in about a
hundred numpy calls on arrays of a few dozen values. This twin computes the same poses with
the scalar kernels of :mod:`rss.unstructured.scalar_motion` — every row of the footprint
table, in the same operations and order, the step grid shared by the whole batch as in
the batched call — then their footprint corners (the scalar twin
:func:`rss.unstructured.scalar_motion.corner_table`) and the same piece plan, so the sets
are equal to the bit. :func:`rss.unstructured.engine.trajectory_sets` chooses it by size
(:data:`SMALL_SETS_MAX`) when the compiled modules are in use.
"""

from __future__ import annotations

import functools
import math
from typing import TYPE_CHECKING

from rss.physics import SPEED_PRECISION
from rss.unstructured.batch import plan_sets
from rss.unstructured.scalar_motion import (
    DYNAMICS_COLUMNS,
    State,
    arc,
    corners_of,
    drive,
    finish,
    is_negative_zero,
    phase_grid,
    step_accelerations,
    time_in_movement,
    time_to_stop,
)
from rss.unstructured.vehicle_batch import (
    SPLIT_MIN_AGENTS,
    vehicle_counts,
    vehicle_layout,
    vehicle_plan,
)

if TYPE_CHECKING:
    from rss.dynamics import UnstructuredSettings
    from rss.unstructured.agents import UnstructuredAgents
    from rss.unstructured.batch import AgentDynamics
    from rss.unstructured.sets import TrajectorySets

__all__ = ["SMALL_SETS_MAX", "vehicle_sets_small"]

#: Largest batch (agents sharing one settings) built point by point; the batched builder
#: integrates the response-time rows apart from :data:`SPLIT_MIN_AGENTS` agents on.
SMALL_SETS_MAX = min(8, SPLIT_MIN_AGENTS - 1)


class _Rows:
    """The row layout of :func:`rss.unstructured.vehicle_batch.vehicle_layout` as lists."""

    def __init__(self, u: UnstructuredSettings) -> None:
        lay = vehicle_layout(u)
        self.front: list[bool] = [int(r) == 0 for r in lay.rows1.tolist()]
        self.ratio1: list[float] = lay.ratio1[:, 0].tolist()
        self.accel2_pick: list[int] = lay.accel2_pick.tolist()
        self.timed2: list[bool] = lay.timed2[:, 0].tolist()
        self.ratio2: list[float] = lay.ratio2[:, 0].tolist()
        self.response: int = int(lay.response.size)
        self.centre: int = 2 * vehicle_counts(u)[0]  # the front centre row (2 nf)
        self.arc_starts: list[int] = lay.arc_starts.tolist()
        self.arc_accel_pick: list[int] = lay.arc_accel_pick.tolist()
        self.arc_time_pick: list[int] = lay.arc_time_pick.tolist()


@functools.lru_cache(maxsize=16)
def _rows(u: UnstructuredSettings) -> _Rows:
    return _Rows(u)


class _Agent:
    """One vehicle's values (floats) and its per-row inputs of the two-phase integration."""

    def __init__(self, values: list[float], u: UnstructuredSettings, rows: _Rows) -> None:
        x, y, yaw, vmin, vmax, rate, rho, vcap, amax, bmax, bmin = values
        self.pose = (x, y, yaw)
        self.rate, self.vcap, self.amax, self.bmax = rate, vcap, amax, bmax
        _, _, kb, kc, _ = vehicle_counts(u)
        stop = time_to_stop(vmax, rho, vcap, amax, bmin) - rho
        self.t_after = max(0.0, stop)
        self.cf = step_accelerations(bmin, amax, kc - 1)
        self.side = step_accelerations(bmax, bmin, kb - 1)
        self.bmin = bmin
        accel2 = [0.0, amax, *self.cf]
        front_t, back_t = time_in_movement(vmax, amax, rho), time_in_movement(vmin, bmax, rho)
        self.start: list[tuple[float, float, float]] = []  # (speed, accel, duration)
        self.second: list[tuple[float, float]] = []  # (accel, duration)
        for r, front in enumerate(rows.front):
            self.start.append((vmax, amax, front_t) if front else (vmin, bmax, back_t))
            self.second.append(
                (accel2[rows.accel2_pick[r]], self.t_after if rows.timed2[r] else 0.0)
            )

    def poses(
        self, rows: _Rows, grids: tuple[list[float], list[float]], u: UnstructuredSettings
    ) -> list[tuple[float, float, float]]:
        """Poses of the footprint table's rows: arcs, continue-forward extremes, current."""
        step, change, min_r = (
            u.vehicle_trajectory_calculation_step,
            u.vehicle_yaw_rate_change,
            u.vehicle_min_radius,
        )
        limits = (step, change, self.vcap, min_r)
        ends = []  # (x, y, yaw, speed, rate) of every integrated row
        first: dict[tuple[bool, float, float], State] = {}  # rows sharing their first phase
        for r, (speed, accel, duration) in enumerate(self.start):
            ratio = rows.ratio1[r]
            key = (rows.front[r], ratio, math.copysign(1.0, ratio))
            state = first.get(key)
            if state is None:
                state = (0.0, 0.0, self.pose[2], speed, self.rate, 0)
                state = drive(state, (grids[0], accel, duration, ratio), limits)
                first[key] = state
            accel2, duration2 = self.second[r]
            state = drive(state, (grids[1], accel2, duration2, rows.ratio2[r]), limits)
            ends.append(finish(self.pose, state))
        response = ends[: rows.response]
        v_centre = response[rows.centre][3]
        v_back = response[-1][3]
        t_back = v_back / -self.bmax if v_back - 0.0 >= SPEED_PRECISION else 0.0
        accels = [self.bmax, self.bmin, *self.side, self.amax, *self.cf]
        times = [t_back, self.t_after]
        times.extend(time_in_movement(v_centre, a, self.t_after) for a in self.side + self.cf)
        out = []
        for i, start in enumerate(rows.arc_starts):
            sx, sy, syaw, sv, srate = response[start]
            accel, duration = accels[rows.arc_accel_pick[i]], times[rows.arc_time_pick[i]]
            out.append(arc(sx, sy, syaw, sv, srate, accel, duration, self.vcap, min_r))
        out.extend((e[0], e[1], e[2]) for e in ends[rows.response :])
        out.append(self.pose)
        return out


_FIELDS = (
    "x_m",
    "y_m",
    "yaw_rad",
    "speed_min_mps",
    "speed_max_mps",
    "yaw_rate_radps",
)


def vehicle_sets_small(agents: UnstructuredAgents, dyn: AgentDynamics) -> TrajectorySets | None:
    """:func:`rss.unstructured.vehicle_batch.vehicle_sets_batch`, point by point.

    Args:
        agents: The vehicles ``(N,)``, ``N <= SMALL_SETS_MAX``.
        dyn: Their dynamics ``(N,)`` (one settings).

    Returns:
        The same pieces, or ``None`` when a speed or speed cap is ``-0.0`` (the batched
        builder's running-sum guess may turn it into ``+0.0``; it takes those batches).
    """
    u = dyn.settings
    rows = _rows(u)
    columns = [getattr(agents, f).tolist() for f in _FIELDS]
    columns += [getattr(dyn, f).tolist() for f in DYNAMICS_COLUMNS]
    n = len(agents)
    values = [[float(c[j]) for c in columns] for j in range(n)]
    for v in values:
        if is_negative_zero(v[3]) or is_negative_zero(v[4]) or is_negative_zero(v[7]):
            return None
    fleet = [_Agent(v, u, rows) for v in values]
    longest = [0.0, 0.0]
    for a in fleet:
        for _, _, duration in a.start:
            longest[0] = max(longest[0], duration)
        for _, duration in a.second:
            longest[1] = max(longest[1], duration)
    step = u.vehicle_trajectory_calculation_step
    grids = (phase_grid(longest[0], step), phase_grid(longest[1], step))
    poses = [a.poses(rows, grids, u) for a in fleet]
    return plan_sets(corners_of(poses, agents, dyn), vehicle_plan(u))
