"""Heading feasibility of connecting routes (ad-map ``getHeadingFeasibility``).

ad-rss drops connecting routes with a feasibility below 0.1 while another remains. Here
the ego approaches a fork: lane 1 goes straight on (north), lane 6 turns off at 45
degrees; the object stands in the fork heading almost east, across lane 1 and along
lane 6 by 42 degrees::

        1 ▲   ↗ 6
          |  ↗  [object ▶]
          | ↗
          0 ▲ (ego)
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

from rss.model import ConstellationType
from rss.scene import LaneGraph, create_scene, prepare
from rss.scene.connecting import MIN_FEASIBILITY, Connecting, Kind, _drop_infeasible, heading_rating

from .synthetic import ego, objects
from .synthetic import straight_lane as _lane
from .test_intersection import SETTINGS

YAW = 0.05


def _fork() -> LaneGraph:
    """Lanes: 0 south approach, 1 straight on (north), 6 turning off to the north-east."""
    pts = [((0, -100), (0, -5)), ((0, -5), (0, 100)), ((0, -5), (60, 55))]
    lanes = [_lane(a, b) for a, b in pts]
    n = len(lanes)
    return LaneGraph(
        ids=("0", "1", "6"),
        left_m=tuple(ln[0] for ln in lanes),
        right_m=tuple(ln[1] for ln in lanes),
        centre_m=tuple(ln[2] for ln in lanes),
        direction=np.ones(n, dtype=np.int64),
        speed_limit_mps=np.full(n, 14.0),
        successors=((1, 2), (), ()),
        predecessors=((), (0,), (0,)),
        left_neighbour=np.full(n, -1, dtype=np.int64),
        right_neighbour=np.full(n, -1, dtype=np.int64),
        left_opposite=np.zeros(n, dtype=bool),
        right_opposite=np.zeros(n, dtype=bool),
        is_intersection=np.array([False, True, True]),
        priority=np.zeros(n, dtype=np.int64),
        traffic_light=np.full(n, -1, dtype=np.int64),
    )


def test_heading_rating_is_linear_in_the_angle_to_the_nearer_axis_direction():
    assert heading_rating(0.3, 0.3) == pytest.approx(1.0)
    assert heading_rating(0.3, 0.3 + math.pi) == pytest.approx(1.0)
    assert heading_rating(0.0, math.pi / 4) == pytest.approx(0.5)
    assert heading_rating(0.0, math.pi / 2) == pytest.approx(0.0, abs=1e-12)


def test_infeasible_routes_go_while_another_remains():
    good = Connecting(Kind.EGO_FOLLOWS, 1, 10.0, False, 0.5)
    bad = Connecting(Kind.OPPOSING, 2, 8.0, False, MIN_FEASIBILITY / 2)
    worse = Connecting(Kind.OPPOSING, 3, 9.0, False, MIN_FEASIBILITY / 10)
    assert _drop_infeasible([bad, good]) == [good]
    assert _drop_infeasible([bad]) == [bad]
    # all infeasible: ad-rss drops them in descending feasibility, the last one stays
    assert _drop_infeasible([bad, worse]) == [worse]


def test_the_route_across_the_object_heading_is_dropped():
    prep = prepare(_fork())
    scene = create_scene(
        prep, ego(0.0, -30.0, np.pi / 2, 10.0), objects((1.5, -3.0, YAW, 5.0)), SETTINGS
    )
    (c,) = scene.constellations
    assert c.constellation_type == ConstellationType.SameDirection
    lanes = {prep.graph.ids[s.lane_id] for seg in c.ego_road for s in seg.lanes}
    assert "6" in lanes
    assert "1" not in lanes


def test_with_the_turn_off_lane_gone_the_route_across_is_kept():
    graph = _fork()
    graph = dataclasses.replace(graph, successors=((1,), (), ()), predecessors=((), (0,), ()))
    prep = prepare(graph)
    scene = create_scene(
        prep, ego(0.0, -30.0, np.pi / 2, 10.0), objects((1.5, -3.0, YAW, 5.0)), SETTINGS
    )
    (c,) = scene.constellations
    lanes = {prep.graph.ids[s.lane_id] for seg in c.ego_road for s in seg.lanes}
    assert "1" in lanes
