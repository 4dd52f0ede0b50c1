"""Which touched lanes start a vehicle's predicted routes (ad-map ``predictRoutes``).

ad-map predicts from every occupied region of a box, along the lane's traffic direction
when the heading lies within 90 degrees of it (against it otherwise, which gives no
route on a one-way lane). The junction below has, besides the crossing of
``test_intersection``, a diagonal lane 6 at 60 degrees to the eastbound crossing lane 4
and a diagonal lane 7 driven the other way (120 degrees)::

              2 (north exit)
              |     6 ↗ (60 deg)
    3 ──▶ ────┼──── 4 ──▶ 5
              |     7 ↙ (240 deg)
              1 ▲ (northbound crossing)
              0 (south approach, the ego)
"""

from __future__ import annotations

import dataclasses

import numpy as np

from rss.model import ConstellationType
from rss.params import RestrictSpeedLimitMode, SceneSettings
from rss.scene import LaneGraph, create_scene, prepare
from rss.scene.create import scene_boxes
from rss.scene.frame import FrameContext, lane_headings
from rss.scene.matching import match_boxes
from rss.scene.memo import SceneMemo
from rss.scene.routes import RouteTree

from .synthetic import ego, objects
from .synthetic import straight_lane as _lane
from .test_intersection import crossing

SETTINGS = SceneSettings(restrict_speed_limit_mode=RestrictSpeedLimitMode.NONE)
ANGLE = np.radians(60.0)


def _with_diagonals() -> LaneGraph:
    """``crossing(0, 0)`` plus junction lanes 6 (60 degrees) and 7 (240 degrees)."""
    base = crossing(0, 0)
    d = 5.0 * np.array([np.cos(ANGLE), np.sin(ANGLE)])
    extra = [_lane(tuple(-d), tuple(d)), _lane(tuple(d), tuple(-d))]
    n = len(base) + len(extra)
    return dataclasses.replace(
        base,
        ids=(*base.ids, "6", "7"),
        left_m=(*base.left_m, *(ln[0] for ln in extra)),
        right_m=(*base.right_m, *(ln[1] for ln in extra)),
        centre_m=(*base.centre_m, *(ln[2] for ln in extra)),
        direction=np.ones(n, dtype=np.int64),
        speed_limit_mps=np.full(n, 14.0),
        successors=(*base.successors, (), ()),
        predecessors=(*base.predecessors, (), ()),
        left_neighbour=np.full(n, -1, dtype=np.int64),
        right_neighbour=np.full(n, -1, dtype=np.int64),
        left_opposite=np.zeros(n, dtype=bool),
        right_opposite=np.zeros(n, dtype=bool),
        is_intersection=np.array([False, True, False, False, True, False, True, True]),
        priority=np.zeros(n, dtype=np.int64),
        traffic_light=np.full(n, -1, dtype=np.int64),
    )


def _frame(graph: LaneGraph, other: tuple[float, float, float, float]) -> FrameContext:
    prep = prepare(graph)
    e, o = ego(0.0, -30.0, np.pi / 2, 10.0), objects(other)
    m = match_boxes(prep, scene_boxes(e, o))
    headings = lane_headings(m, 2)
    return FrameContext(prep, SceneMemo(), e, o, SETTINGS, m, RouteTree(), headings, (0.0, 10.0))


def test_lanes_within_90_degrees_along_traffic_start_routes():
    f = _frame(_with_diagonals(), (3.9, 0.5, 0.0, 5.0))
    touched = {f.prep.graph.ids[lane] for lane in f.lanes_of(1)}
    assert touched == {"4", "5", "6", "7"}
    starts = {f.prep.graph.ids[lane]: fwd for lane, fwd, _ in f.starts(1)}
    # anchor 4 (along the heading) first; 5 ahead and 6 at 60 degrees along their
    # traffic; 7 (traffic at 120 degrees to the heading) starts no route
    assert f.prep.graph.ids[f.starts(1)[0][0]] == "4"
    assert starts == {"4": True, "5": True, "6": True}


def test_a_route_from_a_lane_at_60_degrees_gives_its_intersection_constellation():
    prep = prepare(_with_diagonals())
    scene = create_scene(
        prep, ego(0.0, -30.0, np.pi / 2, 10.0), objects((3.9, 0.5, 0.0, 5.0)), SETTINGS
    )
    kinds = [c.constellation_type for c in scene.constellations]
    assert kinds.count(ConstellationType.IntersectionObjectHasPriority) == 2
    lanes = {
        prep.graph.ids[c.intersecting_road[-1].lanes[0].lane_id - len(prep.graph)]
        for c in scene.constellations
    }
    assert lanes == {"4", "6"}


def test_lanes_at_right_angles_start_no_route():
    f = _frame(_with_diagonals(), (3.9, 0.5, np.pi / 2, 5.0))
    touched = {f.prep.graph.ids[lane] for lane in f.lanes_of(1)}
    assert {"4", "6", "7"} <= touched
    starts = {f.prep.graph.ids[lane]: fwd for lane, fwd, _ in f.starts(1)}
    # heading north: 6 lies 30 degrees off (the anchor), 4 and 5 at right angles, 7's
    # traffic at 150 degrees
    assert starts == {"6": True}
