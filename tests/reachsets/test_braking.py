"""The braking trajectory: the stop the ego can still make, along its path."""

from __future__ import annotations

import numpy as np
import pytest

from reachsets.braking import braking_trajectory


@pytest.mark.parametrize("v_kmh", [30.0, 50.0, 100.0, 130.0])
def test_stopping_distance_is_the_type_approval_limit(v_kmh):
    """UN R13-H type-0 test: s <= 0.1 v + 0.0060 v^2 (v km/h, s m); the defaults meet it."""
    v = v_kmh / 3.6
    (x, _, _, speed), t = braking_trajectory(
        0.0, 0.0, 0.0, v, np.zeros(0), np.zeros(0), np.zeros(0), horizon_s=12.0
    )
    limit = 0.1 * v_kmh + 0.0060 * v_kmh**2
    assert speed[-1] == 0.0
    assert x[-1] == pytest.approx(limit, rel=2e-3)
    assert np.all(np.diff(x) >= 0)
    assert t[0] == 0.0


def test_it_follows_the_path_and_runs_straight_on_beyond_it():
    # an L-shaped path: 10 m east, then north
    px = np.array([0.0, 10.0, 10.0])
    py = np.array([0.0, 0.0, 10.0])
    pyaw = np.array([0.0, np.pi / 2, np.pi / 2])
    (x, y, yaw, _), t = braking_trajectory(0.0, 0.0, 0.0, 20.0, px, py, pyaw)
    travelled = np.concatenate([[0.0], np.cumsum(np.hypot(np.diff(x), np.diff(y)))])
    # 20 m/s for 0.36 s, then 6.43 m/s^2: 7.2 m + 400 / 12.86 m in all (corner cut by the chords)
    assert travelled[-1] <= 7.2 + 400 / 12.86 + 1e-9
    on_first_leg = y < 1e-9
    assert np.all(x[on_first_leg] <= 10.0 + 1e-9)
    assert np.allclose(x[~on_first_leg], 10.0)  # north along x = 10, past the path's end
    assert y.max() == pytest.approx(7.2 + 400 / 12.86 - 10.0)
    assert yaw[-1] == pytest.approx(np.pi / 2)
    assert len(t) == len(x)


def test_it_starts_at_the_ego_not_at_an_older_plan_point():
    px = np.linspace(-5.0, 100.0, 22)
    (x, y, _, _), _ = braking_trajectory(2.0, 0.5, 0.0, 10.0, px, np.zeros(22), np.zeros(22))
    assert (x[0], y[0]) == (2.0, 0.5)
    assert np.all(np.diff(x) >= 0)


def test_a_standing_or_unknown_speed_ego_stays_put():
    for v in (0.0, float("nan")):
        (x, y, _, speed), _ = braking_trajectory(
            1.0, 2.0, 0.3, v, np.zeros(0), np.zeros(0), np.zeros(0)
        )
        assert np.all(x == 1.0)
        assert np.all(y == 2.0)
        assert np.all(speed == 0.0)
