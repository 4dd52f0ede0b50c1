"""Every generated Lanelet2 map loads with our reader with the expected lanes and topology."""

from __future__ import annotations

import itertools
from collections import Counter

import pytest

from loaders.maps.lanelet2 import read_lanelet2
from loaders.maps.model import LaneDirection, LaneKind
from tests.workbench.samples.conftest import SAMPLE_DIR
from workbench.samples.generate import SCENARIOS

KINDS = {
    "highway_cut_in": {LaneKind.ROAD: 12},
    "hard_braking_lead": {LaneKind.ROAD: 4},
    "wrong_way_oncoming": {LaneKind.ROAD: 6},
    "urban_intersection": {LaneKind.ROAD: 13},
    "pedestrian_crossing": {LaneKind.ROAD: 6, LaneKind.CROSSWALK: 1, LaneKind.SIDEWALK: 6},
    "parking_lot": {LaneKind.ROAD: 2, LaneKind.PARKING: 24},
}


@pytest.mark.parametrize("name", list(SCENARIOS))
def test_map_loads_with_expected_lane_counts(name):
    lane_map = read_lanelet2(SAMPLE_DIR / f"{name}.osm")
    assert Counter(lane.kind for lane in lane_map.lanes.values()) == KINDS[name]
    assert SCENARIOS[name]().road_lanelets == KINDS[name][LaneKind.ROAD]


@pytest.mark.parametrize("name", list(SCENARIOS))
def test_ego_route_is_a_successor_chain(name):
    lane_map = read_lanelet2(SAMPLE_DIR / f"{name}.osm")
    route = [str(lid) for lid in SCENARIOS[name]().ego.lanes]
    for a, b in itertools.pairwise(route):
        assert b in lane_map.lanes[a].successors, (name, a, b)


def test_highway_topology():
    lane_map = read_lanelet2(SAMPLE_DIR / "highway_cut_in.osm")
    lanes = lane_map.lanes.values()
    assert sum(1 for lane in lanes if not lane.successors) == 3
    assert sum(1 for lane in lanes if lane.left_neighbour and lane.right_neighbour) == 4
    assert all(lane.direction == LaneDirection.POSITIVE for lane in lanes)


def test_rural_road_has_oncoming_neighbours():
    lane_map = read_lanelet2(SAMPLE_DIR / "wrong_way_oncoming.osm")
    assert all(lane.left_neighbour_opposite for lane in lane_map.lanes.values())


def test_regulatory_elements():
    junction = read_lanelet2(SAMPLE_DIR / "urban_intersection.osm")
    (rule,) = junction.right_of_way
    assert (len(rule.priority_lanes), len(rule.yield_lanes)) == (2, 3)
    crossing = read_lanelet2(SAMPLE_DIR / "pedestrian_crossing.osm")
    (light,) = crossing.traffic_lights
    assert len(light.controlled_lanes) == 1
