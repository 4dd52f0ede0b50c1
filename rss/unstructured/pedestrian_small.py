"""Moving pedestrians' trajectory sets of a few agents, point by point (compiled with mypyc).

The twin of ``rss.unstructured.pedestrian_batch._moving`` for small batches (see
:mod:`rss.unstructured.vehicle_small`): the poses of every row of the footprint table with
the scalar kernels of :mod:`rss.unstructured.scalar_motion`, in the same operations and
order, then their footprint corners point by point and the same piece plan; the sets are
equal to the bit.
"""

from __future__ import annotations

import functools
from typing import TYPE_CHECKING

from rss.physics import DISTANCE_PRECISION, SPEED_PRECISION
from rss.structured.scalar_physics import accelerated_limited_movement
from rss.unstructured.batch import plan_sets
from rss.unstructured.pedestrian_batch import (
    pedestrian_counts,
    pedestrian_layout,
    pedestrian_plan,
)
from rss.unstructured.scalar_motion import (
    DYNAMICS_COLUMNS,
    corners_of,
    pedestrian_move,
    time_to_stop,
)

if TYPE_CHECKING:
    from rss.dynamics import UnstructuredSettings
    from rss.unstructured.agents import UnstructuredAgents
    from rss.unstructured.batch import AgentDynamics
    from rss.unstructured.sets import TrajectorySets

__all__ = ["pedestrian_moving_small"]


class _Rows:
    """The row layout of :func:`rss.unstructured.pedestrian_batch.pedestrian_layout` as lists."""

    def __init__(self, u: UnstructuredSettings) -> None:
        lay = pedestrian_layout(u)
        nf, _, sb, kc, _ = pedestrian_counts(u)
        self.front: list[bool] = [int(r) == 0 for r in lay.phase.tolist()]
        self.ratio_rt: list[float] = lay.ratio_rt[:, 0].tolist()
        self.starts: list[int] = lay.starts.tolist()
        self.dist_pick: list[int] = lay.dist_pick.tolist()
        self.ratio: list[float] = lay.ratio[:, 0].tolist()
        self.centre: int = 2 * nf
        self.sides: int = sb
        self.cf: int = kc


@functools.lru_cache(maxsize=16)
def _rows(u: UnstructuredSettings) -> _Rows:
    return _Rows(u)


def _poses(values: list[float], rows: _Rows, radius_m: float) -> list[tuple[float, float, float]]:
    """Poses of one pedestrian's footprint-table rows (``values``: see :data:`_FIELDS`)."""
    x, y, yaw, vmin, vmax, rho, vcap, amax, bmax, bmin = values
    pose = (x, y, yaw)
    rt: list[tuple[float, float, float]] = []
    speeds: list[float] = []
    for r, front in enumerate(rows.front):
        speed, accel = (vmax, amax) if front else (vmin, bmax)
        v1, dist = accelerated_limited_movement(speed, vcap, accel, rho)
        rt.append(pedestrian_move(pose, dist, rows.ratio_rt[r], radius_m))
        speeds.append(v1)
    v_back, v_front = speeds[-1], speeds[rows.centre]
    t_back = v_back / -bmax if v_back - 0.0 >= SPEED_PRECISION else 0.0
    stop = time_to_stop(vmax, rho, vcap, amax, bmin) - rho
    t_after = max(0.0, stop)
    _, brake_max_d = accelerated_limited_movement(v_back, vcap, bmax, t_back)
    _, brake_min_d = accelerated_limited_movement(v_front, vcap, bmin, t_after)
    _, accel_max_d = accelerated_limited_movement(v_front, vcap, amax, t_after)
    _, rho_d = accelerated_limited_movement(vmax, vcap, amax, rho)
    palette = [brake_min_d, brake_max_d, accel_max_d]
    palette.extend(rho_d / (1.0 + rows.sides) * float(k) for k in range(1, rows.sides + 1))
    width = (accel_max_d - brake_max_d) / (rows.cf - 1.0)
    for k in range(rows.cf):
        d = brake_max_d + width * float(k)
        palette.append(d if d - accel_max_d < DISTANCE_PRECISION else accel_max_d)
    palette.append(0.0)
    starts = [*rt, pose]
    return [
        pedestrian_move(starts[s], palette[rows.dist_pick[i]], rows.ratio[i], radius_m)
        for i, s in enumerate(rows.starts)
    ]


_FIELDS = ("x_m", "y_m", "yaw_rad", "speed_min_mps", "speed_max_mps")


def pedestrian_moving_small(agents: UnstructuredAgents, dyn: AgentDynamics) -> TrajectorySets:
    """Sets of moving pedestrians ``(N,)`` (``rss.unstructured.pedestrian_batch._moving``)."""
    rows = _rows(dyn.settings)
    columns = [getattr(agents, f).tolist() for f in _FIELDS]
    columns += [getattr(dyn, f).tolist() for f in DYNAMICS_COLUMNS]
    radius = dyn.settings.pedestrian_turning_radius
    poses = [_poses([float(c[j]) for c in columns], rows, radius) for j in range(len(agents))]
    return plan_sets(corners_of(poses, agents, dyn), pedestrian_plan(dyn.settings))
