import numpy as np
import pytest

from rss.model import ConstellationType, LaneDrivingDirection
from rss.params import DEFAULT_EGO_DYNAMICS, RestrictSpeedLimitMode, SceneSettings
from rss.scene import Scene, create_scene, prepare
from rss.structured.engine import FrameResult, check_frame
from rss.structured.stacking import stack_constellations
from rss.structured.states import LongitudinalPosition

from .synthetic import WIDTH, ego, objects, straight_road

SETTINGS = SceneSettings(restrict_speed_limit_mode=RestrictSpeedLimitMode.NONE)


def _check(scene: Scene) -> FrameResult:
    batch = stack_constellations(scene.constellations)
    return check_frame(batch, DEFAULT_EGO_DYNAMICS)[0]


def test_follow_same_lane_distance_is_metric_gap():
    prep = prepare(straight_road())
    scene = create_scene(prep, ego(50.0, 0.0), objects((90.0, 0.0, 0.0, 10.0)), SETTINGS)
    (c,) = scene.constellations
    assert c.constellation_type == ConstellationType.SameDirection
    result = _check(scene)
    assert result.relative.lon_position[0] == LongitudinalPosition.AtBack
    assert result.relative.lon_distance_m[0] == pytest.approx(36.0, abs=0.05)
    assert c.other.speed.lon_min_mps == pytest.approx(10.0)


def test_ego_in_front_and_neighbour_lane():
    prep = prepare(straight_road())
    scene = create_scene(prep, ego(50.0, 0.0), objects((30.0, WIDTH, 0.0, 12.0)), SETTINGS)
    (c,) = scene.constellations
    assert c.constellation_type == ConstellationType.SameDirection
    assert len(c.ego_road[0].lanes) == 2  # restricted to the two lanes used
    result = _check(scene)
    assert result.relative.lon_position[0] == LongitudinalPosition.InFront
    assert result.relative.lat_distance_m[0] == pytest.approx(WIDTH - 2.0, abs=0.05)


def test_oncoming_on_reversed_left_lane_is_opposite_direction():
    prep = prepare(straight_road(2, opposite_left=True))
    y_left = WIDTH / 2
    scene = create_scene(prep, ego(50.0, -y_left), objects((120.0, y_left, np.pi, 15.0)), SETTINGS)
    (c,) = scene.constellations
    assert c.constellation_type == ConstellationType.OppositeDirection
    directions = [lane.driving_direction for lane in c.ego_road[0].lanes]
    assert directions == [LaneDrivingDirection.Negative, LaneDrivingDirection.Positive]
    assert c.other.speed.lon_min_mps == pytest.approx(15.0)


def test_far_objects_and_off_map_objects_are_not_relevant():
    prep = prepare(straight_road(length=1000.0))
    scene = create_scene(
        prep, ego(50.0, 0.0), objects((600.0, 0.0, 0.0, 0.0), (50.0, 40.0, 0.0, 0.0)), SETTINGS
    )
    assert scene.constellations == ()
    assert scene.not_relevant == (1, 2)


def test_partly_off_map_vehicle_keeps_its_on_map_part():
    prep = prepare(straight_road())
    rightmost = -WIDTH
    scene = create_scene(
        prep, ego(50.0, 0.0), objects((70.0, rightmost - WIDTH / 2, 0.0, 5.0)), SETTINGS
    )
    (c,) = scene.constellations
    assert c.other.regions
    assert all(r.lat_max <= 1.0 for r in c.other.regions)


@pytest.mark.parametrize(
    ("mode", "cap"),
    [
        (RestrictSpeedLimitMode.NONE, 100.0),
        (RestrictSpeedLimitMode.EXACT_SPEED_LIMIT, 30.0),
        (RestrictSpeedLimitMode.INCREASED_SPEED_LIMIT_5, 31.5),
        (RestrictSpeedLimitMode.INCREASED_SPEED_LIMIT_10, 33.0),
    ],
)
def test_speed_limit_modes(mode, cap):
    prep = prepare(straight_road())
    scene = create_scene(
        prep,
        ego(50.0, 0.0),
        objects((90.0, 0.0, 0.0, 10.0)),
        SceneSettings(restrict_speed_limit_mode=mode),
    )
    (c,) = scene.constellations
    assert c.ego_dynamics.max_speed_on_acceleration_mps == pytest.approx(cap)
    assert c.other_dynamics.max_speed_on_acceleration_mps == pytest.approx(cap)


def test_lateral_speed_sign_positive_to_the_right():
    prep = prepare(straight_road())
    obj = objects((70.0, WIDTH, -0.1, 10.0))  # heading slightly right (clockwise)
    (c,) = create_scene(prep, ego(50.0, 0.0), obj, SETTINGS).constellations
    assert c.other.speed.lat_min_mps == pytest.approx(10.0 * np.sin(0.1), abs=1e-6)


def test_vehicle_straddling_lanes_keeps_every_region_at_the_cut():
    # Yawed across the border of lanes 0 and 1, the object starts further back in one
    # lane than in the other; the road area ends at its rearmost point, and its part in
    # the other lane is kept as a zero-length region at the end (as ad-rss cuts every lane
    # at the vehicle's region in that lane), not dropped.
    prep = prepare(straight_road())
    scene = create_scene(prep, ego(50.0, 0.0), objects((80.0, WIDTH / 2, 0.4, 5.0)), SETTINGS)
    # one per connecting route (lanes 0 and 1), merged later; the route to lane 1 (the
    # ego's) is restricted to that lane, the route to lane 0 spans both
    assert sorted(len(c.other.regions) for c in scene.constellations) == [1, 2]
    for c in scene.constellations:
        assert c.constellation_type == ConstellationType.SameDirection
        assert {r.lane_id for r in c.other.regions} == {
            lane.lane_id for lane in c.ego_road[-1].lanes
        }
        for region in c.other.regions:
            assert region.lon_min == pytest.approx(1.0)
            assert region.lon_max == pytest.approx(1.0)
