"""Small builders shared by the reach-set tests."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
import shapely

from reachsets import evaluate_frames
from reachsets.inputs import (
    EgoTrajectory,
    ObjectStates,
    ReachInputs,
    RoadLane,
    RoadLayout,
    TrackBounds,
)

if TYPE_CHECKING:
    from reachsets.engine import ReachResult, RuleState
    from reachsets.params import ReachParams


def objects(*rows: tuple[float, float, float, float], length=4.7, width=2.0) -> ObjectStates:
    """Objects from ``(x, y, yaw, speed)`` rows."""
    arr = np.asarray(rows, dtype=float).reshape(-1, 4)
    n = len(arr)
    return ObjectStates(
        ids=np.array([f"o{i}" for i in range(n)]) if n else np.zeros(0, "<U1"),
        x_m=arr[:, 0],
        y_m=arr[:, 1],
        yaw_rad=arr[:, 2],
        speed_mps=arr[:, 3],
        length_m=np.full(n, length),
        width_m=np.full(n, width),
    )


def straight_ego(*, x0=0.0, y0=0.0, speed=10.0, yaw=0.0, points=30, horizon=4.0) -> EgoTrajectory:
    """A constant-speed straight plan timed explicitly."""
    t = np.linspace(0.0, horizon, points)
    return EgoTrajectory(
        x_m=x0 + np.cos(yaw) * speed * t,
        y_m=y0 + np.sin(yaw) * speed * t,
        yaw_rad=np.full(points, yaw),
        speed_mps=np.full(points, speed),
        t_s=t,
    )


def straight_track(length=600.0, half_width=6.0, x0=-100.0) -> TrackBounds:
    """A straight track along +x centred on y = 0."""
    x = np.linspace(x0, x0 + length, 121)
    return TrackBounds(
        left_m=np.stack([x, np.full_like(x, half_width)], axis=1),
        right_m=np.stack([x, np.full_like(x, -half_width)], axis=1),
    )


def inputs(ego: EgoTrajectory, objs: ObjectStates, track: TrackBounds | None = None) -> ReachInputs:
    return ReachInputs(ego=ego, objects=objs, track=track)


def evaluate_one(
    inp: ReachInputs, params: ReachParams, state: RuleState | None = None
) -> tuple[ReachResult, RuleState]:
    """One frame through ``evaluate_frames`` (frame by frame, as an online supervisor calls it)."""
    results, state = evaluate_frames([inp], params, state)
    return results[0], state


def two_lane_road() -> RoadLayout:
    """Two 4 m lanes along x in opposite directions, split by one solid line at y = 0."""
    x = np.linspace(-50, 300, 36)
    right_lane = RoadLane(
        "r",
        np.concatenate(
            [np.stack([x, np.zeros_like(x)], 1), np.stack([x[::-1], np.full_like(x, -4.0)], 1)]
        ),
        np.stack([x, np.full_like(x, -2.0)], 1),
        speed_limit_mps=15.0,
    )
    left_lane = RoadLane(
        "l",
        np.concatenate(
            [np.stack([x, np.full_like(x, 4.0)], 1), np.stack([x[::-1], np.zeros_like(x)], 1)]
        ),
        np.stack([x[::-1], np.full_like(x, 2.0)], 1),
        speed_limit_mps=15.0,
    )
    solid = (np.stack([x, np.zeros_like(x)], 1),)
    return RoadLayout(lanes=(right_lane, left_lane), solid_lines_m=solid)


def same_sets(got: np.ndarray, want: np.ndarray, tol: float) -> None:
    """Cell by cell the same geometry within ``tol`` (area in m2, boundary Hausdorff in m).

    ``None`` (nothing left, full geometry) or an empty geometry on both sides also agree.
    """
    assert got.shape == want.shape
    for g, w in zip(got.ravel(), want.ravel(), strict=True):
        if g is None or w is None:
            assert g is None
            assert w is None
            continue
        assert g.is_valid
        assert abs(g.area - w.area) <= tol
        assert g.is_empty == w.is_empty
        if not g.is_empty:
            assert shapely.hausdorff_distance(g.boundary, w.boundary) <= tol
