import math

import numpy as np
import pytest

from loaders.errors import MapError
from loaders.maps.lanelet2 import read_lanelet2
from loaders.maps.model import LaneDirection, LaneKind, LineType

# Tiny map in local coordinates (metres):
#
#   y=9   n9 ------------ n10        D (one_way=no): left w14 (n8->n7), right w15 reversed
#   y=6   n7 ------------ n8         B: left w14 given reversed (n8->n7), right w11
#   y=3   n4 ------------ n5 ---- n6 A: left w11, right w10;  C (successor): left w13, right w12
#   y=0   n1 ------------ n2 ---- n3
#         x=0            x=10    x=20
NODES = {1: (0, 0), 2: (10, 0), 3: (20, 0), 4: (0, 3), 5: (10, 3), 6: (20, 3)}
NODES |= {7: (0, 6), 8: (10, 6), 9: (0, 9), 10: (10, 9)}
WAYS = {
    10: ((1, 2), {"type": "curbstone", "subtype": "high"}),
    11: ((4, 5), {"type": "line_thin", "subtype": "dashed"}),
    12: ((2, 3), {"type": "road_border"}),
    13: ((5, 6), {"type": "virtual"}),
    14: ((8, 7), {"type": "line_thin", "subtype": "solid"}),
    15: ((9, 10), {"type": "road_border"}),
    16: ((1, 2), {"type": "traffic_sign", "subtype": "de274_1"}),
}
LANELETS = {
    100: (11, 10, {"subtype": "road", "one_way": "yes", "speed_limit": "50"}, (200, 201)),
    101: (14, 11, {"subtype": "road", "one_way": "yes"}, (201,)),
    102: (13, 12, {"subtype": "road", "one_way": "yes"}, (202,)),
    103: (14, 15, {"subtype": "road", "one_way": "no"}, ()),
}


def _tags(tags: dict[str, object]) -> str:
    return "".join(f"<tag k='{k}' v='{v}'/>" for k, v in tags.items())


def osm(*, local=True, nodes=NODES, ways=WAYS, lanelets=LANELETS, extra="") -> bytes:
    out = ["<?xml version='1.0'?><osm version='0.6'>"]
    for nid, (x, y) in nodes.items():
        if local:
            out.append(
                f"<node id='{nid}' lat='0' lon='0'>{_tags({'local_x': x, 'local_y': y})}</node>"
            )
        else:
            out.append(f"<node id='{nid}' lat='{49 + y * 1e-5}' lon='{8.4 + x * 1e-5}'/>")
    for wid, (refs, tags) in ways.items():
        nds = "".join(f"<nd ref='{r}'/>" for r in refs)
        out.append(f"<way id='{wid}'>{nds}{_tags(tags)}</way>")
    for lid, (left, right, tags, regs) in lanelets.items():
        members = f"<member type='way' ref='{left}' role='left'/>"
        members += f"<member type='way' ref='{right}' role='right'/>"
        members += "".join(
            f"<member type='relation' ref='{r}' role='regulatory_element'/>" for r in regs
        )
        out.append(f"<relation id='{lid}'>{members}{_tags({'type': 'lanelet', **tags})}</relation>")
    out.append(
        "<relation id='200'><member type='way' ref='16' role='refers'/>"
        + _tags({"type": "regulatory_element", "subtype": "traffic_light"})
        + "</relation>"
        "<relation id='201'><member type='relation' ref='100' role='right_of_way'/>"
        "<member type='relation' ref='101' role='yield'/>"
        + _tags({"type": "regulatory_element", "subtype": "right_of_way"})
        + "</relation>"
        "<relation id='202'><member type='way' ref='16' role='refers'/>"
        + _tags({"type": "regulatory_element", "subtype": "speed_limit"})
        + "</relation>"
    )
    out.append(extra + "</osm>")
    return "".join(out).encode()


@pytest.fixture(scope="module")
def tiny():
    return read_lanelet2(osm(), name="tiny.osm")


def test_tiny_map_lanes_and_borders(tiny):
    assert sorted(tiny.lanes) == ["100", "101", "102", "103"]
    assert tiny.format == "lanelet2"
    assert tiny.source == "tiny.osm"
    a = tiny.lanes["100"]
    np.testing.assert_allclose(a.left_m, [[0, 3], [10, 3]])
    np.testing.assert_allclose(a.right_m, [[0, 0], [10, 0]])
    np.testing.assert_allclose(a.centre_m, [[0, 1.5], [10, 1.5]])
    # B's left way is stored n8->n7 and gets aligned with its right border.
    np.testing.assert_allclose(tiny.lanes["101"].left_m, [[0, 6], [10, 6]])
    # D runs towards -x: its left border (n8->n7) is on its left that way.
    np.testing.assert_allclose(tiny.lanes["103"].left_m, [[10, 6], [0, 6]])
    np.testing.assert_allclose(tiny.lanes["103"].right_m, [[10, 9], [0, 9]])


def test_tiny_map_topology(tiny):
    a, b, c, d = (tiny.lanes[k] for k in ("100", "101", "102", "103"))
    assert a.successors == ("102",)
    assert c.predecessors == ("100",)
    assert a.predecessors == ()
    assert (a.left_neighbour, a.left_neighbour_opposite) == ("101", False)
    assert (b.right_neighbour, b.right_neighbour_opposite) == ("100", False)
    assert (b.left_neighbour, b.left_neighbour_opposite) == ("103", True)
    assert (d.left_neighbour, d.left_neighbour_opposite) == ("101", True)
    assert a.right_neighbour is None
    assert c.left_neighbour is None


def test_tiny_map_attributes(tiny):
    a, b, c, d = (tiny.lanes[k] for k in ("100", "101", "102", "103"))
    assert (a.left_line, a.right_line) == (LineType.DASHED, LineType.ROAD_BORDER)
    assert (b.left_line, c.left_line) == (LineType.SOLID, LineType.VIRTUAL)
    assert a.direction is LaneDirection.POSITIVE
    assert d.direction is LaneDirection.BIDIRECTIONAL
    assert a.kind is LaneKind.ROAD
    assert a.speed_limit_mps == pytest.approx(50 / 3.6)
    assert c.speed_limit_mps == pytest.approx(30 / 3.6)  # de274.1: 30 km/h zone
    assert math.isnan(b.speed_limit_mps)
    assert [(t.id, t.controlled_lanes) for t in tiny.traffic_lights] == [("200", ("100",))]
    (row,) = tiny.right_of_way
    assert (row.id, row.priority_lanes, row.yield_lanes) == ("201", ("100",), ("101",))


def test_lat_lon_is_projected_about_the_first_node():
    lane_map = read_lanelet2(osm(local=False))
    a = lane_map.lanes["100"]
    np.testing.assert_allclose(a.right_m[0], [0, 0], atol=1e-6)
    # 1e-5 degrees: about 1.11 m north per unit y, about 0.73 m east per unit x at 49 deg.
    assert a.left_m[0][1] == pytest.approx(3 * 1.1121, abs=1e-3)
    assert a.right_m[1][0] == pytest.approx(10 * 0.7317, abs=1e-3)


def test_pedestrian_lanelets_default_to_bidirectional():
    lanelets = {**LANELETS, 100: (11, 10, {"subtype": "crosswalk"}, ())}
    lane = read_lanelet2(osm(lanelets=lanelets)).lanes["100"]
    assert (lane.kind, lane.direction) == (LaneKind.CROSSWALK, LaneDirection.BIDIRECTIONAL)


def test_read_from_path(tmp_path):
    path = tmp_path / "tiny.osm"
    path.write_bytes(osm())
    assert read_lanelet2(path).source == str(path)


def test_malformed_xml_names_the_file(tmp_path):
    path = tmp_path / "broken.osm"
    path.write_bytes(osm()[:-20])
    with pytest.raises(MapError, match=r"broken\.osm.*malformed XML"):
        read_lanelet2(path)


def test_missing_node_names_way_and_node():
    ways = {**WAYS, 12: ((2, 99), {"type": "road_border"})}
    with pytest.raises(MapError, match=r"m\.osm.*way 12 of lanelet 102: missing node 99"):
        read_lanelet2(osm(ways=ways), name="m.osm")


def test_missing_way_names_the_lanelet():
    ways = {k: v for k, v in WAYS.items() if k != 13}
    with pytest.raises(MapError, match="lanelet 102 refers to missing way 13"):
        read_lanelet2(osm(ways=ways))


def test_node_without_coordinates_is_named():
    with pytest.raises(MapError, match="node 11 has no valid lat/lon"):
        read_lanelet2(osm(local=False, extra="<node id='11'/>"))


def test_missing_file_is_a_map_error(tmp_path):
    with pytest.raises(MapError, match="cannot open"):
        read_lanelet2(tmp_path / "absent.osm")


@pytest.fixture(scope="module")
def mapping_example(external_dir):
    return read_lanelet2(external_dir / "maps" / "mapping_example.osm")


@pytest.mark.external
def test_mapping_example_loads_every_lanelet(mapping_example):
    lanes = mapping_example.lanes
    assert len(lanes) == 371
    kinds = [lane.kind for lane in lanes.values()]
    assert kinds.count(LaneKind.CROSSWALK) == 8
    assert kinds.count(LaneKind.BICYCLE) == 14
    assert kinds.count(LaneKind.RAIL) == 2
    directions = [lane.direction for lane in lanes.values()]
    assert directions.count(LaneDirection.BIDIRECTIONAL) == 98
    assert len(mapping_example.traffic_lights) == 6
    assert len(mapping_example.right_of_way) == 2
    lo_x, lo_y, hi_x, hi_y = mapping_example.bounds_m()
    assert 3000 < hi_x - lo_x < 4000
    assert 900 < hi_y - lo_y < 1200


@pytest.mark.external
def test_mapping_example_topology_facts(mapping_example):
    # Checked by hand in the file: lanelet 45006's right way (43760) ends at node 41024
    # where 45008's right way (43594) starts; its left way (43758) is stored reversed.
    lanes = mapping_example.lanes
    assert lanes["45006"].successors == ("45008",)
    assert lanes["45008"].predecessors == ("45006",)
    # 44970's right way is 44968's left way (43658).
    assert (lanes["44968"].left_neighbour, lanes["44968"].left_neighbour_opposite) == (
        "44970",
        False,
    )
    assert lanes["44968"].successors == ("44978",)
    assert (lanes["45082"].left_neighbour, lanes["45082"].right_neighbour) == ("45070", "45088")
    # 45104 (road) and 45140 (bidirectional bicycle lane) share way 43862 as right border.
    assert (lanes["45104"].right_neighbour, lanes["45104"].right_neighbour_opposite) == (
        "45140",
        True,
    )
    lights = {light.id: light.controlled_lanes for light in mapping_example.traffic_lights}
    assert lights["45224"] == ("44968", "44970")
    rows = {row.id: row for row in mapping_example.right_of_way}
    assert "44968" in rows["45230"].priority_lanes
    assert rows["45230"].yield_lanes == ("45014", "45016")


@pytest.mark.external
def test_mapping_example_geometry_is_consistent(mapping_example):
    lanes = mapping_example.lanes
    for lane in lanes.values():
        if lane.direction is not LaneDirection.POSITIVE:
            continue
        for succ_id in lane.successors:
            succ = lanes[succ_id]
            if succ.direction is LaneDirection.POSITIVE:
                np.testing.assert_allclose(lane.left_m[-1], succ.left_m[0], atol=1e-9)
                np.testing.assert_allclose(lane.right_m[-1], succ.right_m[0], atol=1e-9)
        if lane.left_neighbour is not None and not lane.left_neighbour_opposite:
            np.testing.assert_allclose(lane.left_m, lanes[lane.left_neighbour].right_m)
        # The left border lies to the left of the centre line's direction.
        heading = lane.centre_m[-1] - lane.centre_m[0]
        offset = lane.left_m.mean(axis=0) - lane.right_m.mean(axis=0)
        assert heading[0] * offset[1] - heading[1] * offset[0] > 0, lane.id
