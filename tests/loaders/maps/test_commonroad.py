import math

import numpy as np
import pytest

from loaders.errors import MapError
from loaders.maps.commonroad import read_commonroad_map
from loaders.maps.model import LaneDirection, LaneKind, LineType
from tests.loaders.maps.commonroad_xml import lanelet, scenario

NGSIM_LANES = {
    "USA_Lanker-1_1_T-1.xml": 91,
    "USA_Lanker-1_4_T-1.xml": 95,
    "USA_Lanker-2_23_T-1.xml": 116,
    "USA_Peach-3_1_T-1.xml": 75,
    "USA_Peach-4_8_T-1.xml": 79,
    "USA_US101-23_1_T-1.xml": 18,
    "USA_US101-24_2_T-1.xml": 18,
    "USA_US101-3_1_T-1.xml": 12,
    "USA_US101-3_3_T-1.xml": 12,
    "USA_US101-4_1_T-1.xml": 12,
    "USA_US101-5_1_T-1.xml": 5,
}


@pytest.mark.parametrize("version", ["2018b", "2020a"])
def test_synthetic_network(version):
    lane_map = read_commonroad_map(scenario(version, ""), name="net.xml")
    assert (lane_map.format, lane_map.source, sorted(lane_map.lanes)) == (
        "commonroad",
        "net.xml",
        ["1", "2", "3"],
    )
    one, two, three = (lane_map.lanes[k] for k in ("1", "2", "3"))
    np.testing.assert_allclose(one.right_m, [[0, 0], [5, 0], [10, 0]])
    np.testing.assert_allclose(one.centre_m, [[0, 1.5], [5, 1.5], [10, 1.5]])
    assert one.successors == ("2",)
    assert two.predecessors == ("1",)
    assert three.successors == ()  # dangling ref 404 dropped
    assert (one.left_neighbour, one.left_neighbour_opposite) == ("3", True)
    assert one.right_neighbour is None
    assert one.direction is LaneDirection.POSITIVE
    assert one.speed_limit_mps == pytest.approx(13.4112)
    assert math.isnan(two.speed_limit_mps)


def test_2020a_markings_signs_lights_and_intersections():
    lane_map = read_commonroad_map(scenario("2020a", ""))
    one, two, three = (lane_map.lanes[k] for k in ("1", "2", "3"))
    assert (one.left_line, one.right_line) == (LineType.DASHED, LineType.SOLID)
    assert two.left_line is LineType.UNKNOWN
    assert [(t.id, t.controlled_lanes) for t in lane_map.traffic_lights] == [("60", ("1",))]
    assert lane_map.intersections == (("2",),)
    assert two.kind is LaneKind.INTERSECTION
    assert one.kind is LaneKind.ROAD
    assert three.kind is LaneKind.CROSSWALK


def test_bidirectional_lanelet():
    body = lanelet(9, [(0, 1), (1, 1)], [(0, 0), (1, 0)], "<userBidirectional/>")
    doc = scenario("2020a", body, net=False)
    assert read_commonroad_map(doc).lanes["9"].direction is LaneDirection.BIDIRECTIONAL


def test_bad_bound_names_lanelet():
    body = lanelet(9, [(0, 1), (1, 1)], [(0, 0), (1, 0)]).replace("<x>1</x>", "<x>x</x>", 1)
    with pytest.raises(MapError, match=r"bad\.xml.*lanelet 9 leftBound point 1 is not numeric"):
        read_commonroad_map(scenario("2020a", body, net=False), name="bad.xml")


def test_short_bound_names_lanelet():
    body = lanelet(9, [(0, 1)], [(0, 0), (1, 0)])
    with pytest.raises(MapError, match="lanelet 9 leftBound has 1 points"):
        read_commonroad_map(scenario("2020a", body, net=False))


def test_malformed_xml(tmp_path):
    path = tmp_path / "cut.xml"
    path.write_bytes(scenario("2020a", "")[:-30])
    with pytest.raises(MapError, match=r"cut\.xml.*malformed XML"):
        read_commonroad_map(path)


@pytest.mark.external
@pytest.mark.parametrize("name", sorted(NGSIM_LANES))
def test_ngsim_networks(external_dir, name):
    lane_map = read_commonroad_map(external_dir / "commonroad_ngsim" / name)
    assert len(lane_map) == NGSIM_LANES[name]
    for lane in lane_map.lanes.values():
        assert np.isfinite(lane.centre_m).all()
        for succ in lane.successors:
            assert lane.id in lane_map.lanes[succ].predecessors


@pytest.mark.external
def test_ngsim_lankershim_facts(external_dir):
    folder = external_dir / "commonroad_ngsim"
    old = read_commonroad_map(folder / "USA_Lanker-1_1_T-1.xml").lanes["3419"]
    new_map = read_commonroad_map(folder / "USA_Lanker-1_4_T-1.xml")
    new = new_map.lanes["3419"]
    for lane in (old, new):
        assert lane.successors == ("3432",)
        assert (lane.left_neighbour, lane.left_neighbour_opposite) == ("3464", True)
        assert (lane.right_neighbour, lane.right_neighbour_opposite) == ("3422", False)
        assert lane.speed_limit_mps == pytest.approx(13.4112)  # 30 mph
    assert (new.left_line, new.right_line) == (LineType.SOLID, LineType.SOLID)
    assert len(new_map.traffic_lights) == 8
    assert [len(group) for group in new_map.intersections] == [20]
    assert new_map.lanes["3600"].kind is LaneKind.INTERSECTION
