import numpy as np
import pytest

from rss.model import ConstellationType, RoadSegmentType
from rss.params import DEFAULT_EGO_DYNAMICS, RestrictSpeedLimitMode, SceneSettings
from rss.scene import LaneGraph, Scene, create_scene, prepare
from rss.structured.engine import check_frame
from rss.structured.stacking import stack_constellations

from .synthetic import HALF, ego, objects, straight_lanes

SETTINGS = SceneSettings(restrict_speed_limit_mode=RestrictSpeedLimitMode.NONE)


def crossing(ego_priority: int, other_priority: int, *, light_on_ego: bool = False) -> LaneGraph:
    """Lanes: 0 south approach, 1 crossing northbound, 2 north exit,
    3 west approach, 4 crossing eastbound, 5 east exit."""
    pts = [
        ((0, -100), (0, -5)),
        ((0, -5), (0, 5)),
        ((0, 5), (0, 100)),
        ((-100, 0), (-5, 0)),
        ((-5, 0), (5, 0)),
        ((5, 0), (100, 0)),
    ]
    n = len(pts)
    light = np.full(n, -1, dtype=np.int64)
    if light_on_ego:
        light[1] = 0
    priority = np.zeros(n, dtype=np.int64)
    priority[1], priority[4] = ego_priority, other_priority
    return straight_lanes(
        pts,
        ((1,), (2,), (), (4,), (5,), ()),
        junction=(1, 4),
        priority=priority,
        traffic_light=light,
        light_ids=("tl",),
    )


def _scene(graph: LaneGraph, green: frozenset[int] = frozenset()) -> Scene:
    prep = prepare(graph)
    return create_scene(
        prep, ego(0.0, -30.0, np.pi / 2, 10.0), objects((-40.0, 0.0, 0.0, 10.0)), SETTINGS, green
    )


@pytest.mark.parametrize(
    ("ego_prio", "other_prio", "kind"),
    [
        (-1, 1, ConstellationType.IntersectionObjectHasPriority),
        (1, -1, ConstellationType.IntersectionEgoHasPriority),
        (-1, -1, ConstellationType.IntersectionSamePriority),
        (0, 0, ConstellationType.IntersectionObjectHasPriority),
    ],
)
def test_priority_from_right_of_way(ego_prio, other_prio, kind):
    (c,) = _scene(crossing(ego_prio, other_prio)).constellations
    assert c.constellation_type == kind
    assert [s.segment_type for s in c.ego_road] == [
        RoadSegmentType.Normal,
        RoadSegmentType.Intersection,
    ]
    assert c.intersecting_road[-1].segment_type == RoadSegmentType.Intersection


def test_distances_to_the_intersecting_area():
    (c,) = _scene(crossing(0, 0)).constellations
    inter = c.ego_road[-1]
    assert inter.min_length_before_intersecting_area_m == pytest.approx(5.0 - HALF, abs=0.05)
    assert inter.min_length_after_intersecting_area_m == pytest.approx(5.0 - HALF, abs=0.05)
    result = check_frame(stack_constellations([c]), DEFAULT_EGO_DYNAMICS)[0]
    assert result.invalid[0] == 0


def test_red_or_unknown_light_means_yield_green_means_priority():
    (c,) = _scene(crossing(0, -1, light_on_ego=True)).constellations
    assert c.constellation_type == ConstellationType.IntersectionSamePriority
    (c,) = _scene(crossing(0, -1, light_on_ego=True), frozenset({0})).constellations
    assert c.constellation_type == ConstellationType.IntersectionEgoHasPriority


def test_follower_through_the_intersection_is_same_direction():
    prep = prepare(crossing(0, 0))
    scene = create_scene(
        prep, ego(0.0, -30.0, np.pi / 2, 10.0), objects((0.0, 10.0, np.pi / 2, 10.0)), SETTINGS
    )
    (c,) = scene.constellations
    assert c.constellation_type == ConstellationType.SameDirection
