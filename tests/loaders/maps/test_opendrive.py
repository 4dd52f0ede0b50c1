# ruff: noqa: E501
import math
from collections import Counter

import numpy as np
import pytest

from loaders.errors import MapError
from loaders.maps.model import LaneKind
from loaders.maps.opendrive import read_opendrive


def _road(rid: str, geometry: str, length: float, links: str = "", junction: str = "-1") -> str:
    lanes = """
      <laneSection s="0">
        <left><lane id="1" type="driving"><link>{lp}</link><width sOffset="0" a="3.5" b="0" c="0" d="0"/></lane></left>
        <center><lane id="0" type="none"/></center>
        <right>
          <lane id="-1" type="driving"><link>{rp}</link><width sOffset="0" a="3.5" b="0" c="0" d="0"/></lane>
          <lane id="-2" type="sidewalk"><width sOffset="0" a="2.0" b="0" c="0" d="0"/></lane>
        </right>
      </laneSection>"""
    lp = rp = ""
    if links:
        lp = '<predecessor id="1"/><successor id="1"/>'
        rp = '<predecessor id="-1"/><successor id="-1"/>'
    return f"""
  <road id="{rid}" length="{length}" junction="{junction}">
    <link>{links}</link>
    <type s="0" type="town"><speed max="50" unit="km/h"/></type>
    <planView>{geometry}</planView>
    <lanes>{lanes.format(lp=lp, rp=rp)}</lanes>
  </road>"""


def _doc(*roads: str) -> bytes:
    return ("<?xml version='1.0'?><OpenDRIVE><header/>" + "".join(roads) + "</OpenDRIVE>").encode()


LINE = '<geometry s="0" x="0" y="0" hdg="0" length="50"><line/></geometry>'
ARC = f'<geometry s="0" x="50" y="0" hdg="0" length="{25 * math.pi}"><arc curvature="0.02"/></geometry>'


def test_line_road_lanes_borders_and_neighbours():
    m = read_opendrive(_doc(_road("1", LINE, 50.0)), name="line")
    assert sorted(m.lanes) == ["1_0_-1", "1_0_-2", "1_0_1"]
    right = m.lanes["1_0_-1"]
    left = m.lanes["1_0_1"]
    np.testing.assert_allclose(right.centre_m[[0, -1]], [[0.0, -1.75], [50.0, -1.75]], atol=1e-9)
    np.testing.assert_allclose(left.centre_m[[0, -1]], [[50.0, 1.75], [0.0, 1.75]], atol=1e-9)
    assert right.left_neighbour == "1_0_1"
    assert right.left_neighbour_opposite
    assert left.left_neighbour == "1_0_-1"
    assert left.left_neighbour_opposite
    assert right.right_neighbour == "1_0_-2"
    assert m.lanes["1_0_-2"].kind == LaneKind.SIDEWALK
    assert right.speed_limit_mps == pytest.approx(50 / 3.6)
    assert right.length_m == pytest.approx(50.0)


def test_arc_geometry_and_road_links_in_driving_direction():
    links1 = '<successor elementType="road" elementId="2" contactPoint="start"/>'
    links2 = '<predecessor elementType="road" elementId="1" contactPoint="end"/>'
    m = read_opendrive(_doc(_road("1", LINE, 50.0, links1), _road("2", ARC, 25 * math.pi, links2)))
    arc_right = m.lanes["2_0_-1"]
    np.testing.assert_allclose(arc_right.centre_m[-1], [100.0 + 1.75, 50.0], atol=0.05)
    assert m.lanes["1_0_-1"].successors == ("2_0_-1",)
    assert m.lanes["2_0_1"].successors == ("1_0_1",)
    assert m.lanes["1_0_1"].predecessors == ("2_0_1",)


@pytest.mark.parametrize(
    "geometry",
    [
        '<geometry s="0" x="0" y="0" hdg="0" length="40"><spiral curvStart="0" curvEnd="0"/></geometry>',
        '<geometry s="0" x="0" y="0" hdg="0" length="40"><poly3 a="0" b="0" c="0" d="0"/></geometry>',
        (
            '<geometry s="0" x="0" y="0" hdg="0" length="40"><paramPoly3 aU="0" bU="40" cU="0" '
            'dU="0" aV="0" bV="0" cV="0" dV="0" pRange="normalized"/></geometry>'
        ),
    ],
)
def test_degenerate_curves_are_straight(geometry):
    m = read_opendrive(_doc(_road("1", geometry, 40.0)))
    np.testing.assert_allclose(m.lanes["1_0_-1"].centre_m[-1], [40.0, -1.75], atol=1e-6)


def test_spiral_heading_grows_quadratically():
    geo = '<geometry s="0" x="0" y="0" hdg="0" length="40"><spiral curvStart="0" curvEnd="0.05"/></geometry>'
    m = read_opendrive(_doc(_road("1", geo, 40.0)))
    c = m.lanes["1_0_-1"].centre_m
    heading = math.atan2(c[-1, 1] - c[-2, 1], c[-1, 0] - c[-2, 0])
    chord = math.hypot(*(c[-1] - c[-2]))
    # the last chord's heading lies between the tangents 0.05 s^2 / 80 at its two ends
    assert 0.05 * (40 - chord) ** 2 / 80 < heading < 0.05 * 40**2 / 80


def test_not_opendrive_is_a_map_error():
    with pytest.raises(MapError, match="expected <OpenDRIVE>"):
        read_opendrive(b"<osm/>", name="x")


def test_town01_and_karlsruhe_load(external_dir):
    town = read_opendrive(external_dir / "maps" / "Town01.xodr")
    kinds = Counter(lane.kind for lane in town.lanes.values())
    assert kinds[LaneKind.ROAD] == 52
    assert kinds[LaneKind.INTERSECTION] == 72
    assert len(town.intersections) == 12
    drivable = [
        ln for ln in town.lanes.values() if ln.kind in (LaneKind.ROAD, LaneKind.INTERSECTION)
    ]
    assert all(ln.successors and ln.predecessors for ln in drivable)
    for lane in drivable:
        for nxt in lane.successors:
            gap = np.hypot(*(town.lanes[nxt].centre_m[0] - lane.centre_m[-1]))
            assert gap < 0.5
    karlsruhe = read_opendrive(external_dir / "maps" / "Karlsruhe.xodr")
    assert Counter(ln.kind for ln in karlsruhe.lanes.values())[LaneKind.ROAD] == 2


def _one_lane_road(rid: str, x: float, hdg: float, junction: str) -> str:
    return f"""
  <road id="{rid}" length="50" junction="{junction}">
    <planView><geometry s="0" x="{x}" y="0" hdg="{hdg}" length="50"><line/></geometry></planView>
    <lanes><laneSection s="0">
      <center><lane id="0" type="none"/></center>
      <right><lane id="-1" type="driving"><width sOffset="0" a="3.5" b="0" c="0" d="0"/></lane></right>
    </laneSection></lanes>
  </road>"""


@pytest.mark.parametrize(("junction", "linked"), [("7", True), ("-1", False)])
def test_junction_roads_on_one_reference_line_are_opposite_neighbours(junction, linked):
    """Two connecting roads of a junction drawn on the same line in opposite directions."""
    there = _one_lane_road("10", 0.0, 0.0, junction)
    back = _one_lane_road("11", 50.0, math.pi, junction)
    m = read_opendrive(_doc(there, back))
    a, b = m.lanes["10_0_-1"], m.lanes["11_0_-1"]
    if linked:
        assert (a.left_neighbour, b.left_neighbour) == ("11_0_-1", "10_0_-1")
        assert a.left_neighbour_opposite
        assert b.left_neighbour_opposite
    else:  # ordinary roads keep their own lanes only
        assert a.left_neighbour is None
        assert b.left_neighbour is None
    assert a.right_neighbour is None


def test_junction_lanes_meeting_only_at_their_ends_are_neighbours():
    """ad-map links junction lanes by their borders' end points only (Town01 1840151 /
    1830151 overlap, their borders apart by more than a metre in between)."""
    bend = 0.1
    curvature = 2.0 * math.sin(bend) / 50.0
    arc = f"""
  <road id="11" length="{2 * bend / curvature}" junction="7">
    <planView><geometry s="0" x="50" y="0" hdg="{math.pi + bend}" length="{2 * bend / curvature}">
      <arc curvature="{-curvature}"/></geometry></planView>
    <lanes><laneSection s="0">
      <center><lane id="0" type="none"/></center>
      <right><lane id="-1" type="driving"><width sOffset="0" a="3.5" b="0" c="0" d="0"/></lane></right>
    </laneSection></lanes>
  </road>"""
    m = read_opendrive(_doc(_one_lane_road("10", 0.0, 0.0, "7"), arc))
    a, b = m.lanes["10_0_-1"], m.lanes["11_0_-1"]
    assert float(np.abs(a.left_m[:, 1]).max()) < 1e-9
    assert float(np.abs(b.left_m[:, 1]).max()) > 1.0
    assert (a.left_neighbour, b.left_neighbour) == ("11_0_-1", "10_0_-1")
    assert a.left_neighbour_opposite
    assert b.left_neighbour_opposite


def test_town01_overlapping_junction_lanes_are_neighbours(external_dir):
    # the three pairs the whole-border rule left apart; with them all 72 junction lanes
    # have ad-map's left / right drivable neighbours (compared with the oracle's contacts)
    town = read_opendrive(external_dir / "maps" / "Town01.xodr")
    for a, b in (("184_0_1", "183_0_1"), ("128_0_-1", "131_0_1"), ("247_0_-1", "253_0_-1")):
        ends = {town.lanes[a].left_neighbour, town.lanes[a].right_neighbour}
        back = {town.lanes[b].left_neighbour, town.lanes[b].right_neighbour}
        assert b in ends
        assert a in back
