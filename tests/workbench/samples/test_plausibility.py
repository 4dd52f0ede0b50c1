"""Every scenario is physically plausible and stays on its lanes."""

from __future__ import annotations

import numpy as np
import pytest
import shapely

from loaders.records import ObjectClass
from workbench.samples.generate import SCENARIOS
from workbench.samples.motion import DT_S, Track

VEHICLES = {ObjectClass.CAR, ObjectClass.TRUCK, ObjectClass.BUS, ObjectClass.MOTORCYCLE}
EPS = 1e-6


@pytest.fixture(scope="module", params=list(SCENARIOS))
def scenario(request):
    return SCENARIOS[request.param]()


def test_duration_rates_and_actor_count(scenario):
    assert 15.0 <= scenario.t_s[-1] <= 25.0
    assert np.allclose(np.diff(scenario.t_s), DT_S)
    assert len(scenario.actors) >= 3
    ids = [tr.id for tr in scenario.tracks]
    assert len(set(ids)) == len(ids)


@pytest.mark.parametrize("kind", ["accel", "yaw_rate", "lateral"])
def test_vehicle_limits(scenario, kind):
    for tr in scenario.tracks:
        if tr.object_class not in VEHICLES | {ObjectClass.BICYCLE}:
            continue
        if kind == "accel":
            assert tr.accel_mps2.max() <= 4.0 + EPS, tr.id
            assert tr.accel_mps2.min() >= -8.0 - EPS, tr.id
        elif kind == "yaw_rate":
            assert np.abs(tr.yaw_rate_radps).max() <= 1.0, tr.id
        else:
            assert np.abs(tr.motion.speed_mps * tr.yaw_rate_radps).max() <= 4.0, tr.id


def test_pedestrians_walk(scenario):
    for tr in scenario.tracks:
        if tr.object_class == ObjectClass.PEDESTRIAN:
            assert np.abs(tr.motion.speed_mps).max() <= 2.0
            assert np.abs(tr.accel_mps2).max() <= 1.5


def test_positions_match_speeds(scenario):
    for tr in scenario.tracks:
        m = tr.motion
        step = np.hypot(np.diff(m.x_m), np.diff(m.y_m)) / DT_S
        mean_speed = np.abs(m.speed_mps[1:] + m.speed_mps[:-1]) / 2
        assert np.abs(step - mean_speed).max() < 0.15, tr.id


def test_parking_lot_is_slow():
    sc = SCENARIOS["parking_lot"]()
    for tr in sc.tracks:
        assert np.abs(tr.motion.speed_mps).max() < 3.0
    assert sc.actors[0].motion.speed_mps.min() < 0  # the reversing car


def test_agents_stay_on_their_lanes(scenario):
    lane_map = scenario.lane_map
    for tr in scenario.tracks:
        area = shapely.union_all(
            [shapely.Polygon(lane_map.polygon_m(lid)) for lid in tr.lanes]
        ).buffer(0.05)
        check = tr.visible & ~tr.motion.lane_change
        points = shapely.points(tr.motion.x_m[check], tr.motion.y_m[check])
        inside = shapely.contains(area, points)
        assert inside.all(), (tr.id, scenario.t_s[check][~inside][:5])


def _boxes(tr: Track, k: int) -> shapely.Polygon:
    m = tr.motion
    c, s = np.cos(m.yaw_rad[k]), np.sin(m.yaw_rad[k])
    hl, hw = tr.length_m / 2, tr.width_m / 2
    corners = np.array([[hl, hw], [-hl, hw], [-hl, -hw], [hl, -hw]])
    rot = np.array([[c, -s], [s, c]])
    return shapely.Polygon(corners @ rot.T + [m.x_m[k], m.y_m[k]])


def test_nobody_collides_with_the_ego(scenario):
    for k in range(0, len(scenario.t_s), 2):
        ego = _boxes(scenario.ego, k)
        for tr in scenario.actors:
            assert not ego.intersects(_boxes(tr, k)), (tr.id, scenario.t_s[k])
