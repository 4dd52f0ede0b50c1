"""Tiny synthetic lane graphs for scene-creation tests."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from rss.model import LaneDrivingDirection
from rss.params import DEFAULT_EGO_DYNAMICS, DEFAULT_VEHICLE_DYNAMICS
from rss.scene import LaneGraph, SceneEgo, SceneObjects

if TYPE_CHECKING:
    from collections.abc import Sequence

WIDTH = 3.5
#: Half width [m] of the lanes of :func:`straight_lane`.
HALF = 1.75


def straight_road(
    n_lanes: int = 3, length: float = 200.0, *, opposite_left: bool = False
) -> LaneGraph:
    """``n_lanes`` parallel lanes along +x, lane 0 leftmost (largest y).

    With ``opposite_left`` the leftmost lane is stored and driven in -x direction.
    """
    xs = np.linspace(0.0, length, 21)
    left, right, centre, direction = [], [], [], []
    for i in range(n_lanes):
        y_left = (n_lanes / 2 - i) * WIDTH
        y_right = y_left - WIDTH
        lane_l = np.stack([xs, np.full_like(xs, y_left)], axis=1)
        lane_r = np.stack([xs, np.full_like(xs, y_right)], axis=1)
        if opposite_left and i == 0:
            lane_l, lane_r = lane_r[::-1], lane_l[::-1]
        left.append(lane_l)
        right.append(lane_r)
        centre.append((lane_l + lane_r) / 2)
        direction.append(LaneDrivingDirection.Positive)
    left_nb = np.arange(-1, n_lanes - 1)
    right_nb = np.arange(1, n_lanes + 1)
    right_nb[-1] = -1
    left_opp = np.zeros(n_lanes, dtype=bool)
    right_opp = np.zeros(n_lanes, dtype=bool)
    if opposite_left:
        left_opp[1] = True
        right_opp[0] = False
        left_nb[0], right_nb[0] = 1, -1  # lane 0 reversed: its left is lane 1
        left_opp[0] = True
    empty: tuple[tuple[int, ...], ...] = tuple(() for _ in range(n_lanes))
    return LaneGraph(
        ids=tuple(str(i) for i in range(n_lanes)),
        left_m=tuple(left),
        right_m=tuple(right),
        centre_m=tuple(centre),
        direction=np.array(direction, dtype=np.int64),
        speed_limit_mps=np.full(n_lanes, 30.0),
        successors=empty,
        predecessors=empty,
        left_neighbour=left_nb.astype(np.int64),
        right_neighbour=right_nb.astype(np.int64),
        left_opposite=left_opp,
        right_opposite=right_opp,
        is_intersection=np.zeros(n_lanes, dtype=bool),
        priority=np.zeros(n_lanes, dtype=np.int64),
        traffic_light=np.full(n_lanes, -1, dtype=np.int64),
    )


def ego(x: float, y: float, yaw: float = 0.0, speed: float = 10.0) -> SceneEgo:
    return SceneEgo(
        object_id=1000,
        x_m=x,
        y_m=y,
        yaw_rad=yaw,
        speed_mps=speed,
        length_m=4.0,
        width_m=2.0,
        dynamics=DEFAULT_EGO_DYNAMICS,
    )


def objects(*rows: tuple[float, float, float, float]) -> SceneObjects:
    """Objects from ``(x, y, yaw, speed)`` rows (4 m x 2 m cars, ids 1, 2, ...)."""
    arr = np.array(rows, dtype=float).reshape(-1, 4)
    n = len(arr)
    return SceneObjects(
        ids=np.arange(1, n + 1, dtype=np.int64),
        object_type=np.full(n, 2, dtype=np.int64),
        x_m=arr[:, 0],
        y_m=arr[:, 1],
        yaw_rad=arr[:, 2],
        vx_mps=arr[:, 3] * np.cos(arr[:, 2]),
        vy_mps=arr[:, 3] * np.sin(arr[:, 2]),
        length_m=np.full(n, 4.0),
        width_m=np.full(n, 2.0),
        dynamics=(DEFAULT_VEHICLE_DYNAMICS,) * n,
    )


def straight_lane(
    start: tuple[float, float], end: tuple[float, float]
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``(left, right, centre)`` of a straight lane ``start -> end`` (11 points, 3.5 m wide)."""
    a, b = np.asarray(start, float), np.asarray(end, float)
    t = np.linspace(0.0, 1.0, 11)[:, None]
    centre = a + (b - a) * t
    d = (b - a) / np.linalg.norm(b - a)
    left = centre + np.array([-d[1], d[0]]) * HALF
    right = centre - np.array([-d[1], d[0]]) * HALF
    return left, right, centre


def straight_lanes(
    pts: Sequence[tuple[tuple[float, float], tuple[float, float]]],
    successors: tuple[tuple[int, ...], ...],
    *,
    junction: tuple[int, ...] = (),
    priority: np.ndarray | None = None,
    traffic_light: np.ndarray | None = None,
    light_ids: tuple[str, ...] = (),
) -> LaneGraph:
    """Straight lanes ``start -> end`` (driven that way, 14 m/s), linked by ``successors``.

    ``junction`` lists the intersection lanes; ``priority`` / ``traffic_light`` default to
    none anywhere.
    """
    lanes = [straight_lane(a, b) for a, b in pts]
    n = len(lanes)
    predecessors = tuple(tuple(a for a in range(n) if b in successors[a]) for b in range(n))
    return LaneGraph(
        ids=tuple(str(i) for i in range(n)),
        left_m=tuple(ln[0] for ln in lanes),
        right_m=tuple(ln[1] for ln in lanes),
        centre_m=tuple(ln[2] for ln in lanes),
        direction=np.ones(n, dtype=np.int64),
        speed_limit_mps=np.full(n, 14.0),
        successors=successors,
        predecessors=predecessors,
        left_neighbour=np.full(n, -1, dtype=np.int64),
        right_neighbour=np.full(n, -1, dtype=np.int64),
        left_opposite=np.zeros(n, dtype=bool),
        right_opposite=np.zeros(n, dtype=bool),
        is_intersection=np.array([i in junction for i in range(n)]),
        priority=np.zeros(n, dtype=np.int64) if priority is None else priority,
        traffic_light=np.full(n, -1, dtype=np.int64) if traffic_light is None else traffic_light,
        light_ids=light_ids,
    )


def lone_lane(left: np.ndarray, right: np.ndarray, centre: np.ndarray, name: str) -> LaneGraph:
    """One unlinked lane driven along its point order (10 m/s, no rules) from its lines [m]."""
    one = np.ones(1, dtype=np.int64)
    return LaneGraph(
        ids=(name,),
        left_m=(left,),
        right_m=(right,),
        centre_m=(centre,),
        direction=one * int(LaneDrivingDirection.Positive),
        speed_limit_mps=np.full(1, 10.0),
        successors=((),),
        predecessors=((),),
        left_neighbour=-one,
        right_neighbour=-one,
        left_opposite=np.zeros(1, dtype=bool),
        right_opposite=np.zeros(1, dtype=bool),
        is_intersection=np.zeros(1, dtype=bool),
        priority=0 * one,
        traffic_light=-one,
    )
