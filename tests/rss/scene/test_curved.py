import numpy as np
import pytest

from rss.model import ConstellationType
from rss.params import DEFAULT_EGO_DYNAMICS, RestrictSpeedLimitMode, SceneSettings
from rss.scene import LaneGraph, create_scene, prepare
from rss.structured.engine import check_frame
from rss.structured.stacking import stack_constellations

from .synthetic import ego, objects

SETTINGS = SceneSettings(restrict_speed_limit_mode=RestrictSpeedLimitMode.NONE)
R = 100.0
W = 3.5


def _arc_lane(r_centre: float, n: int = 91) -> tuple[np.ndarray, ...]:
    phi = np.linspace(-np.pi / 2, 0.0, n)  # counter-clockwise quarter circle around the origin
    left = np.stack([(r_centre - W / 2) * np.cos(phi), (r_centre - W / 2) * np.sin(phi)], axis=1)
    right = np.stack([(r_centre + W / 2) * np.cos(phi), (r_centre + W / 2) * np.sin(phi)], axis=1)
    return left, right, (left + right) / 2


def curve() -> LaneGraph:
    """Two lanes curving left: lane 0 inner (left), lane 1 outer (right)."""
    lanes = [_arc_lane(R - W / 2), _arc_lane(R + W / 2)]
    return LaneGraph(
        ids=("inner", "outer"),
        left_m=tuple(ln[0] for ln in lanes),
        right_m=tuple(ln[1] for ln in lanes),
        centre_m=tuple(ln[2] for ln in lanes),
        direction=np.ones(2, dtype=np.int64),
        speed_limit_mps=np.full(2, 20.0),
        successors=((), ()),
        predecessors=((), ()),
        left_neighbour=np.array([-1, 0]),
        right_neighbour=np.array([1, -1]),
        left_opposite=np.zeros(2, dtype=bool),
        right_opposite=np.zeros(2, dtype=bool),
        is_intersection=np.zeros(2, dtype=bool),
        priority=np.zeros(2, dtype=np.int64),
        traffic_light=np.full(2, -1, dtype=np.int64),
    )


def _pose(angle: float, radius: float) -> tuple[float, float, float]:
    return radius * np.cos(angle), radius * np.sin(angle), angle + np.pi / 2


def test_follow_in_a_curve_distance_close_to_arc_gap():
    prep = prepare(curve())
    r = R + W / 2
    ex, ey, eyaw = _pose(-1.2, r)
    ox, oy, oyaw = _pose(-0.8, r)
    scene = create_scene(prep, ego(ex, ey, eyaw, 10.0), objects((ox, oy, oyaw, 10.0)), SETTINGS)
    (c,) = scene.constellations
    assert c.constellation_type == ConstellationType.SameDirection
    lane = c.ego_road[0].lanes[0]
    assert lane.length_min_m < lane.length_max_m  # curvature -> length interval
    result = check_frame(stack_constellations([c]), DEFAULT_EGO_DYNAMICS)[0]
    gap = 0.4 * r - 4.0
    # the restricted road area keeps the worst-case stretch small (< 5 %)
    assert result.relative.lon_distance_m[0] == pytest.approx(gap, rel=0.05)
    assert result.relative.lon_distance_m[0] <= gap + 0.05


def test_velocity_conversion_at_20_degrees():
    prep = prepare(curve())
    r = R + W / 2
    ex, ey, eyaw = _pose(-1.2, r)
    ox, oy, oyaw = _pose(-0.8, r)
    obj = objects((ox, oy, oyaw - np.deg2rad(20.0), 10.0))
    (c,) = create_scene(prep, ego(ex, ey, eyaw, 10.0), obj, SETTINGS).constellations
    # as ad-rss: relative to the road heading where the connecting route reaches the
    # object (its rear, about half its projected length before its centre on the arc;
    # the footprint's rearmost vertex lies a little further back: +-0.5 degrees)
    rear = (2.0 * np.cos(np.deg2rad(20.0)) + 1.0 * np.sin(np.deg2rad(20.0))) / r
    delta = np.deg2rad(20.0) - rear
    assert c.other.speed.lon_min_mps == pytest.approx(10.0 * np.cos(delta), abs=0.03)
    assert c.other.speed.lat_min_mps == pytest.approx(10.0 * np.sin(delta), abs=0.1)
    assert np.hypot(c.other.speed.lon_min_mps, c.other.speed.lat_min_mps) == pytest.approx(10.0)
