"""Reachable sets contain the true future positions of real vehicles (CommonRoad NGSIM drives).

For every vehicle present at a start frame (every second of each drive) and for the whole
4 s horizon after it, the observed motion is first checked against the method's limits:

* ``simple``: the point-mass accelerations implied by the positions on the 0.2 s grid (the
  first one against the reported initial velocity) stay within ``a_max_mps2``, the speed
  stays >= 0 and the heading within 90 degrees of the initial one (the set's rear edge never
  moves back, i.e. no reversing);
* ``turn``: the same with ``ax_max_mps2``, and the path curvature stays below
  ``1 / turn_radius_m`` and the lateral acceleration below ``ay_max_mps2``.

Each qualifying vehicle's centre at every frame inside step ``k``'s interval
``[t_{k-1}, t_k]`` must lie in its untrimmed, unpatched set of step ``k``. ``turn`` uses the
sound ``keep_object_body`` funnel (the reference's deletes the body and everything beside it,
so a slow car's own next positions; see docs/reachsets.md). ``bound`` is ``turn`` off a
racing track. The data are raw NGSIM tracks (noisy), so some windows do not qualify; the test
counts them and requires a meaningful number that do (1058 of 1088 windows for ``simple``,
935 for ``turn`` when written). A control checks that the reference's default funnel fails.
"""

from __future__ import annotations

from functools import cache
from typing import TYPE_CHECKING

import numpy as np
import pytest
import shapely

from loaders.open import open_drive
from reachsets.inputs import ObjectStates
from reachsets.params import ReachMethod, ReachParams
from reachsets.reachable import reachable_sets

if TYPE_CHECKING:
    from pathlib import Path

    from numpy.typing import NDArray

pytestmark = pytest.mark.external

#: Start frames are this far apart (s).
START_EVERY_S = 1.0
#: Fewer qualifying (vehicle, start) windows than this over all drives would make the test
#: meaningless (half of the 1088 windows of the 11 drives).
MIN_QUALIFYING = 544


@cache
def _tracks(path: Path) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.str_]]:
    """Per-vehicle columns over the drive: ``(t_s (F,), table (V, F, 6), ids (V,))``.

    Table columns: x, y, yaw, speed, length, width; NaN where the vehicle is absent.
    """
    drive = open_drive(path)
    try:
        frames = list(drive.frames())
    finally:
        drive.close()
    ids = sorted({str(i) for f in frames for i in f.actors.ids})
    row = {i: r for r, i in enumerate(ids)}
    table = np.full((len(ids), len(frames), 6), np.nan)
    for k, f in enumerate(frames):
        a = f.actors
        for j in np.flatnonzero(np.asarray(a.valid, dtype=bool)):
            cols = (a.x_m, a.y_m, a.yaw_rad, a.speed_mps, a.length_m, a.width_m)
            table[row[str(a.ids[j])], k] = [float(c[j]) for c in cols]
    t = np.array([(f.t_ns - frames[0].t_ns) / 1e9 for f in frames])
    return t, table, np.asarray(ids)


def _wrap(angle_rad: NDArray[np.float64]) -> NDArray[np.float64]:
    return np.asarray((angle_rad + np.pi) % (2 * np.pi) - np.pi)


def _within_limits(
    win: NDArray[np.float64], grid: NDArray[np.intp], dt_s: float, params: ReachParams
) -> NDArray[np.bool_]:
    """Whether each vehicle's window ``(V, F_h, 6)`` stays within the method's limits."""
    p = win[:, grid, :2]  # (V, T, 2) positions on the grid
    yaw0, v0 = win[:, 0, 2], win[:, 0, 3]
    heading0 = np.stack([np.cos(yaw0), np.sin(yaw0)], axis=1)
    # p1 = p0 + v0 dt + a dt^2 / 2, then central second differences
    first = 2 * (p[:, 1] - p[:, 0] - dt_s * v0[:, None] * heading0) / dt_s**2
    later = (p[:, 2:] - 2 * p[:, 1:-1] + p[:, :-2]) / dt_s**2
    acc = np.hypot(*np.concatenate([first[:, None], later], axis=1).T)
    turned = np.abs(_wrap(win[..., 2] - yaw0[:, None]))
    ok = np.all(win[..., 3] >= 0, axis=1) & np.all(turned < np.pi / 2, axis=1)
    if params.method == ReachMethod.SIMPLE:
        return np.asarray(ok & np.all(acc <= params.a_max_mps2, axis=0))
    step = np.diff(win[:, grid, :2], axis=1)
    dist = np.hypot(step[..., 0], step[..., 1])
    dyaw = np.abs(_wrap(np.diff(win[:, grid, 2], axis=1)))
    kappa = dyaw / np.maximum(dist, 1e-9)
    speed = dist / dt_s
    return np.asarray(
        ok
        & np.all(acc <= params.ax_max_mps2, axis=0)
        & np.all(kappa <= 1 / params.turn_radius_m, axis=1)
        & np.all(speed**2 * kappa <= params.ay_max_mps2, axis=1)
    )


def _check_drive(path: Path, params: ReachParams) -> tuple[int, int, list[str]]:
    """``(windows, qualifying windows, failures)`` of one drive."""
    t, table, ids = _tracks(path)
    times = params.times_array_s
    frame_dt = float(np.median(np.diff(t)))
    per_step = round(params.dt_s / frame_dt)
    horizon = per_step * (len(times) - 1)
    assert np.allclose(np.diff(t), frame_dt, atol=1e-3)
    grid = np.arange(len(times)) * per_step
    windows = qualifying = 0
    failures: list[str] = []
    for start in range(0, len(t) - horizon, round(START_EVERY_S / frame_dt)):
        win = table[:, start : start + horizon + 1]
        present = np.all(np.isfinite(win), axis=(1, 2))
        windows += int(present.sum())
        good = np.flatnonzero(present)
        good = good[_within_limits(win[good], grid, params.dt_s, params)]
        qualifying += len(good)
        if len(good) == 0:
            continue
        w = win[good]
        objs = ObjectStates(ids[good], *(w[:, 0, c] for c in range(6)))
        sets = reachable_sets(objs, times, params, None)  # (V, T)
        # frames inside step k's interval [t_{k-1}, t_k]
        for k in range(1, len(times)):
            cols = np.arange((k - 1) * per_step, k * per_step + 1)
            inside = shapely.intersects_xy(sets[:, k, None], w[:, cols, 0], w[:, cols, 1])
            failures.extend(
                f"{path.name} frame {start} {ids[good[v]]} step {k}"
                for v in np.flatnonzero(~np.all(inside, axis=1))
            )
    return windows, qualifying, failures


@pytest.mark.parametrize("method", [ReachMethod.SIMPLE, ReachMethod.TURN])
def test_sets_contain_true_future_positions_on_ngsim(external_dir, method):
    paths = sorted((external_dir / "commonroad_ngsim").glob("*.xml"))
    assert paths, "no CommonRoad NGSIM scenarios found"
    params = ReachParams(
        method=method, trim_to_drivable=False, rules_enabled=False, keep_object_body=True
    )
    windows = qualifying = 0
    failures: list[str] = []
    for path in paths:
        n, q, bad = _check_drive(path, params)
        windows += n
        qualifying += q
        failures += bad
    assert qualifying >= MIN_QUALIFYING, (qualifying, windows)
    assert failures == []


def test_reference_turn_funnel_misses_the_cars_own_positions_on_ngsim(external_dir):
    """Control: the reference's ``turn`` deletion (body deleted) fails the same check."""
    path = external_dir / "commonroad_ngsim" / "USA_Lanker-1_1_T-1.xml"
    params = ReachParams(method=ReachMethod.TURN, trim_to_drivable=False, rules_enabled=False)
    _, qualifying, failures = _check_drive(path, params)
    assert qualifying > 0
    assert len(failures) > 0
