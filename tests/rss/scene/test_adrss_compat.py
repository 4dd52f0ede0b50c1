"""``[scene] reproduce_adrss_5_0_defects``: ad-rss 5.0's two documented defects, by hand.

Every expected number below is derived in the comments from the defect as documented
(docs/rss_scene.md, deviations; ``rss.scene.admap_heading``), not taken from our output:

* ad-map's ENU heading of a lane chord ``end -> start`` measured at the lane's end ``b``
  against the direction from ``b`` to the point 1 m east of the map origin, i.e. the true
  heading plus ``atan2(b_y, 1 - b_x)``; relative arm angles wrapped once only;
* ad-rss' lane-frame speeds of an object following the ego resolved along the road
  direction at the *other* vehicle's end of the connecting route.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

from rss.model import ConstellationType, LaneDrivingDirection, RoadSegmentType
from rss.params import RestrictSpeedLimitMode, SceneSettings
from rss.scene import SceneMemo, create_scene, prepare
from rss.scene.admap_heading import defective_enu_heading, lane_chord_heading
from rss.scene.cut_areas import cut_area_spans
from rss.scene.junction_arms import (
    Arm,
    _bucket,
    _bucket_wrapped_once,
    intersection_arms,
)
from rss.scene.segment_plans import SegmentPlan

from .synthetic import ego, objects, straight_lanes
from .test_intersection import crossing

DEFAULT = SceneSettings(restrict_speed_limit_mode=RestrictSpeedLimitMode.NONE)
COMPAT = SceneSettings(
    restrict_speed_limit_mode=RestrictSpeedLimitMode.NONE, reproduce_adrss_5_0_defects=True
)
#: The Earth-curvature part of the model moves these cases by < 1e-7 rad.
TOL = 1e-6


def test_defect_vanishes_at_the_map_origin() -> None:
    # b = (0, 0): "east" = (1, 0) - b is east; a chord pointing west reads pi.
    assert defective_enu_heading((-10.0, 0.0), (0.0, 0.0)) == pytest.approx(math.pi, abs=TOL)
    # a chord pointing north-east reads 45 degrees
    assert defective_enu_heading((5.0, 5.0), (0.0, 0.0)) == pytest.approx(math.pi / 4, abs=TOL)


def test_east_axis_is_taken_towards_the_origin() -> None:
    # b = (1, 10): "east" = (0, -10) points south; an eastward chord lies 90 degrees
    # counter-clockwise of it and reads pi / 2 (true heading 0 + atan2(10, 0)).
    assert defective_enu_heading((11.0, 10.0), (1.0, 10.0)) == pytest.approx(math.pi / 2, abs=TOL)
    # b = (-99, 100): "east" = (100, -100) points south-east (-45 degrees); a northward
    # chord reads 90 + 45 = 135 degrees (true heading pi / 2 + atan2(100, 100)).
    got = defective_enu_heading((-99.0, 110.0), (-99.0, 100.0))
    assert got == pytest.approx(3 * math.pi / 4, abs=TOL)


def test_lane_chord_runs_from_the_end_to_the_start_in_driving_direction() -> None:
    # Driven north from (-99, 90) to b = (-99, 100): the chord end -> start points south
    # (-90 degrees), plus atan2(100, 1 + 99) = 45 degrees: -45 degrees; the same lane
    # stored the other way round and driven against its point order reads the same.
    along = straight_lanes([((-99.0, 90.0), (-99.0, 100.0))], ((),))
    against = straight_lanes([((-99.0, 100.0), (-99.0, 90.0))], ((),))
    against = dataclasses.replace(
        against, direction=np.array([LaneDrivingDirection.Negative], dtype=np.int64)
    )
    for graph in (along, against):
        assert lane_chord_heading(prepare(graph), 0) == pytest.approx(-math.pi / 4, abs=TOL)


def test_negative_angles_are_wrapped_once_only() -> None:
    # -450 degrees: one turn added gives -90 degrees, still below 45: a U-turn, where the
    # angle taken modulo a turn (270 degrees) is a left turn.
    assert _bucket_wrapped_once(math.radians(-450.0)) == Arm.UTURN
    assert _bucket(math.radians(-450.0)) == Arm.LEFT
    # -270 degrees: one turn added gives 90 degrees, a right turn either way
    assert _bucket_wrapped_once(math.radians(-270.0)) == Arm.RIGHT
    assert _bucket_wrapped_once(math.radians(270.0)) == Arm.LEFT


def test_left_turn_far_from_the_origin_becomes_a_u_turn() -> None:
    """A junction at (100, -300), as on CARLA Town01 (geo reference at latitude/longitude 0).

    Entry A (lane 0) drives north to b = (100, -305): chord south (-90) plus
    atan2(-305, -99) = -107.98 gives -197.98 = 162.02 degrees, the reference; exits are
    measured against 162.02 + 180 = 342.02 degrees.

    * W (lane 4) drives west to b = (0, -300): chord east (0) + atan2(-300, 1) = -89.81;
      -89.81 - 342.02 = -431.83, plus one turn -71.83, still negative: U-turn (true: left).
    * N (lane 5) drives north to (100, -200): -90 + atan2(-200, -99) = -90 - 116.34 =
      153.66; 153.66 - 342.02 + 360 = 171.64: straight.
    * E (lane 6) drives east to (200, -300): 180 + atan2(-300, -199) = 180 - 123.56 =
      56.44; 56.44 - 342.02 + 360 = 74.42: right.
    """
    graph = straight_lanes(
        [
            ((100.0, -400.0), (100.0, -305.0)),
            ((100.0, -305.0), (95.0, -300.0)),
            ((100.0, -305.0), (100.0, -295.0)),
            ((100.0, -305.0), (105.0, -300.0)),
            ((95.0, -300.0), (0.0, -300.0)),
            ((100.0, -295.0), (100.0, -200.0)),
            ((105.0, -300.0), (200.0, -300.0)),
        ],
        ((1, 2, 3), (4,), (5,), (6,), (), (), ()),
        junction=(1, 2, 3),
    )
    prep = prepare(graph)
    j = prep.junction_list[1]
    assert intersection_arms(prep, SceneMemo(), j, 0) == {
        0: Arm.UTURN,
        4: Arm.LEFT,
        5: Arm.STRAIGHT,
        6: Arm.RIGHT,
    }
    assert intersection_arms(prep, SceneMemo(), j, 0, admap_defects=True) == {
        0: Arm.UTURN,
        4: Arm.UTURN,
        5: Arm.STRAIGHT,
        6: Arm.RIGHT,
    }


def test_following_object_gets_the_ego_heading_and_vice_versa() -> None:
    """An object follows the ego round a corner: east on lane 0, then north on lane 2.

    Ego on lane 2 at (50, 30) heading north at 10 m/s; the object behind on lane 0 at
    (20, 0) heading east at 5 m/s. Each vehicle's own road direction: ego lon 10 / lat 0,
    object lon 5 / lat 0. ad-rss 5.0 gives the ego the road direction at the object's end
    (east): ego velocity (0, 10) against east: lon |0| = 0, lat (0, 10) . right-of-east
    (0, -1) = -10 (moving left); the object gets north: lon 0, lat (5, 0) . right-of-north
    (1, 0) = +5. The default mode keeps the own directions and adds ad-rss' swapped ones
    (the engine merges the two into their worst case: never safe where ad-rss is
    dangerous by its swapped speeds).
    """
    graph = straight_lanes(
        [((0.0, 0.0), (40.0, 0.0)), ((40.0, 0.0), (50.0, 10.0)), ((50.0, 10.0), (50.0, 60.0))],
        ((1,), (2,), ()),
    )
    prep = prepare(graph)
    args = (ego(50.0, 30.0, math.pi / 2, 10.0), objects((20.0, 0.0, 0.0, 5.0)))
    own, swapped = (10.0, 0.0, 5.0, 0.0), (0.0, -10.0, 0.0, 5.0)
    expected = {DEFAULT: (own, swapped), COMPAT: (swapped,)}
    for settings, rows in expected.items():
        found = create_scene(prep, *args, settings).constellations
        assert len(found) == len(rows)
        for c, (ego_lon, ego_lat, obj_lon, obj_lat) in zip(found, rows, strict=True):
            assert c.constellation_type == ConstellationType.SameDirection
            speeds = (c.ego.speed, c.other.speed)
            assert speeds[0].lon_min_mps == pytest.approx(ego_lon, abs=1e-9)
            assert speeds[0].lat_min_mps == pytest.approx(ego_lat, abs=1e-9)
            assert speeds[1].lon_min_mps == pytest.approx(obj_lon, abs=1e-9)
            assert speeds[1].lat_min_mps == pytest.approx(obj_lat, abs=1e-9)


def test_intersecting_area_is_measured_within_the_cut_windows() -> None:
    """ad-rss 5.0 cuts a vehicle's intersection road area at its rear on its conflict lane.

    Crossing of ``test_intersection``: junction lane 1 runs north along x = 0 (y from -5
    to 5), lane 4 east along y = 0 (x from -5 to 5), both 10 m long and 3.5 m wide, so
    each lies inside the other for 3.5 m in the middle (|x|, |y| <= 1.75): 3.25 m before
    and after it on both (``area_span``, the uncut values).

    The object on lane 4 has its rear at x = 0.5 (fraction 0.55): of the common part
    x in [-1.75, 1.75] only [0.5, 1.75] is left in its window, so nothing before it and
    5 - 1.75 = 3.25 m after it. Lane 1 keeps 3.25 / 3.25: the window of lane 4 still
    spans all of lane 1's width (y in [-1.75, 1.75]). With the ego's rear also inside, at
    y = -0.5 (fraction 0.45), lane 1 has nothing before it either.
    """
    prep = prepare(crossing(0, 0))

    def plans(ego_p0: float) -> tuple[SegmentPlan, SegmentPlan]:
        kind = RoadSegmentType.Intersection
        return (
            SegmentPlan([(1, True)], kind, before_m=3.25, after_m=3.25, p0=ego_p0),
            SegmentPlan([(4, True)], kind, before_m=3.25, after_m=3.25, p0=0.55),
        )

    ego_plan, obj_plan = plans(0.0)
    assert cut_area_spans(prep, SceneMemo(), ego_plan, obj_plan)
    assert (ego_plan.before_m, ego_plan.after_m) == pytest.approx((3.25, 3.25), abs=1e-6)
    assert (obj_plan.before_m, obj_plan.after_m) == pytest.approx((0.0, 3.25), abs=1e-6)
    ego_plan, obj_plan = plans(0.45)
    cut_area_spans(prep, SceneMemo(), ego_plan, obj_plan)
    assert (ego_plan.before_m, ego_plan.after_m) == pytest.approx((0.0, 3.25), abs=1e-6)
    assert (obj_plan.before_m, obj_plan.after_m) == pytest.approx((0.0, 3.25), abs=1e-6)
    # lane 1 run against its point order (south, from y = 5) and kept down to y = -0.5:
    # 5 - 1.75 = 3.25 m before the common part, which reaches the window's end
    ego_plan = SegmentPlan([(1, False)], RoadSegmentType.Intersection, p0=0.0, p1=0.55)
    obj_plan = SegmentPlan([(4, True)], RoadSegmentType.Intersection, p0=0.55)
    cut_area_spans(prep, SceneMemo(), ego_plan, obj_plan)
    assert (ego_plan.before_m, ego_plan.after_m) == pytest.approx((3.25, 0.0), abs=1e-6)
    # the object's rear at x = 2 (fraction 0.7), past lane 1 (|x| <= 1.75): the windows no
    # longer intersect, and ad-rss gives the pair no intersection constellation
    ego_plan, obj_plan = plans(0.0)
    obj_plan.p0 = 0.7
    assert not cut_area_spans(prep, SceneMemo(), ego_plan, obj_plan)
