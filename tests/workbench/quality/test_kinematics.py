"""The vectorised window estimates against slow scalar references on uneven random tracks."""

from __future__ import annotations

import numpy as np
import pytest

from workbench.quality.kinematics import chord_speed, neighbours, window_slope
from workbench.quality.tracks import Tracks


def _random_tracks(seed: int) -> Tracks:
    rng = np.random.default_rng(seed)
    obj, t = [], []
    for k in range(4):
        times = np.cumsum(rng.integers(20_000_000, 150_000_000, size=int(rng.integers(5, 40))))
        obj.extend([k] * len(times))
        t.extend(times.tolist())
    m = len(obj)
    return Tracks(
        ids=np.array(["a", "b", "c", "d"]),
        object_class=np.ones(4, dtype=np.int8),
        obj=np.array(obj, dtype=np.int64),
        frame=np.arange(m, dtype=np.int64),
        t_ns=np.array(t, dtype=np.int64),
        x_m=rng.normal(size=m).cumsum(),
        y_m=rng.normal(size=m).cumsum(),
        yaw_rad=np.zeros(m),
        speed_mps=rng.uniform(0, 20, size=m),
    )


def _slope_reference(tr: Tracks, values: np.ndarray, half_ns: int) -> np.ndarray:
    out = np.full(len(tr), np.nan)
    for i in range(len(tr)):
        near = [
            j
            for j in range(len(tr))
            if tr.obj[j] == tr.obj[i] and abs(tr.t_ns[j] - tr.t_ns[i]) <= half_ns
        ]
        dt = (tr.t_ns[near] - tr.t_ns[i]) / 1e9
        if len(near) >= 3 and dt.min() < 0 < dt.max():
            out[i] = np.polyfit(dt, values[near], 1)[0]
    return out


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_window_slope_is_the_least_squares_slope(seed):
    tr = _random_tracks(seed)
    fast = window_slope(tr, tr.speed_mps, 250_000_000)
    slow = _slope_reference(tr, tr.speed_mps, 250_000_000)
    assert np.array_equal(np.isnan(fast), np.isnan(slow))
    assert np.allclose(fast[~np.isnan(fast)], slow[~np.isnan(slow)], rtol=1e-7, atol=1e-7)
    assert np.isfinite(fast).sum() > 20


@pytest.mark.parametrize("seed", [4, 5])
def test_neighbours_and_chord_speed(seed):
    tr = _random_tracks(seed)
    span = 100_000_000
    back, ahead = neighbours(tr, span)
    for i in range(len(tr)):
        same = np.flatnonzero(tr.obj == tr.obj[i])
        before = [j for j in same if tr.t_ns[j] <= tr.t_ns[i] - span]
        after = [j for j in same if tr.t_ns[j] >= tr.t_ns[i] + span]
        assert back[i] == (before[-1] if before else -1)
        assert ahead[i] == (after[0] if after else -1)
    speed = chord_speed(tr, back, ahead)
    ok = (back >= 0) & (ahead >= 0)
    dist = np.hypot(tr.x_m[ahead[ok]] - tr.x_m[back[ok]], tr.y_m[ahead[ok]] - tr.y_m[back[ok]])
    assert np.allclose(speed[ok], dist / ((tr.t_ns[ahead[ok]] - tr.t_ns[back[ok]]) / 1e9))
