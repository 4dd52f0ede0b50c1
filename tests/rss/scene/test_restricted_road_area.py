"""Restricted road areas: the lanes between the route's start and its destination lane.

ad-rss (``createNonIntersectionRoadArea``) keeps the lane segments whose route lane offset
lies between 0 (the lane the route starts in, at the ego) and the route's destination
lane offset (the object's lane where the route ends). An object straddling two lanes
ahead has a route to each of them; the one to the ego's own lane is one lane wide::

    lane 0   ─────────────────────────────
    lane 1   ──[ego]──────────────[obj]───   route to lane 1: lane 1 only
    lane 2   ─────────────────────[obj]───   route to lane 2: lanes 1 and 2
"""

from __future__ import annotations

from rss.model import ConstellationType
from rss.params import RestrictSpeedLimitMode, SceneSettings
from rss.scene import create_scene, prepare

from .synthetic import WIDTH, ego, objects, straight_road

SETTINGS = SceneSettings(restrict_speed_limit_mode=RestrictSpeedLimitMode.NONE)


def test_the_route_to_the_ego_lane_keeps_one_lane_the_route_beside_two():
    prep = prepare(straight_road())
    scene = create_scene(prep, ego(50.0, 0.0), objects((90.0, -WIDTH / 2, 0.0, 10.0)), SETTINGS)
    widths = sorted(
        {len(seg.lanes) for seg in c.ego_road}.pop()
        for c in scene.constellations
        if c.constellation_type == ConstellationType.SameDirection
    )
    assert widths == [1, 2]
    lanes = [
        {prep.graph.ids[s.lane_id] for seg in c.ego_road for s in seg.lanes}
        for c in scene.constellations
    ]
    assert {"1"} in lanes
    assert {"1", "2"} in lanes
