"""Intersection arms and route relations as ad-map defines them (geometric angles)."""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import pytest

from loaders.maps.opendrive import read_opendrive
from rss.scene import PreparedGraph, SceneMemo, prepare
from rss.scene.junction_arms import Arm, intersection_arms
from rss.scene.junction_relations import Relation, junctions_on, relation
from workbench.engines.rss.adapter import lane_graph_from_map

from .test_intersection import crossing

if TYPE_CHECKING:
    from pathlib import Path


@pytest.fixture(scope="module")
def town01(external_dir: Path) -> PreparedGraph:
    return prepare(lane_graph_from_map(read_opendrive(external_dir / "maps" / "Town01.xodr")))


def _lane(prep: PreparedGraph, name: str) -> int:
    return list(prep.graph.ids).index(name)


def _route(prep: PreparedGraph, *names: str) -> tuple[tuple[int, bool], ...]:
    return tuple((_lane(prep, name), True) for name in names)


def test_four_way_crossing_arms_follow_the_compass() -> None:
    prep = prepare(crossing(0, 0))
    j = prep.junction_list[1]
    # From the south approach (lane 0, heading north): the west approach enters from the
    # left, the north and east exits leave straight on and to the right.
    arms = intersection_arms(prep, SceneMemo(), j, 0)
    assert arms == {0: Arm.UTURN, 3: Arm.LEFT, 2: Arm.STRAIGHT, 5: Arm.RIGHT}
    # Seen from the west approach (heading east) the same lanes change arms.
    arms = intersection_arms(prep, SceneMemo(), j, 3)
    assert arms == {3: Arm.UTURN, 0: Arm.RIGHT, 2: Arm.LEFT, 5: Arm.STRAIGHT}


def test_crossing_route_is_crossing_and_same_arm_is_detected() -> None:
    prep = prepare(crossing(0, 0))
    north = ((0, True), (1, True), (2, True))
    east = ((3, True), (4, True), (5, True))
    (span,) = junctions_on(prep, SceneMemo(), north)
    assert relation(prep, SceneMemo(), north, span, east) == Relation.CROSSING
    assert relation(prep, SceneMemo(), north, span, north) == Relation.SAME_ARM
    assert relation(prep, SceneMemo(), north, span, ((2, True),)) == Relation.NONE


def test_town01_t_junction_arms(town01: PreparedGraph) -> None:
    prep = town01
    j = prep.junction_list[_lane(prep, "304_0_1")]
    arms = intersection_arms(prep, SceneMemo(), j, _lane(prep, "18_0_1"))
    named = {prep.graph.ids[lane]: arm for lane, arm in arms.items()}
    # Ego northbound on road 18: road 17 continues north, road 4 leaves to the west.
    assert named == {
        "18_0_1": Arm.UTURN,
        "18_0_-1": Arm.UTURN,
        "17_0_1": Arm.STRAIGHT,
        "17_0_-1": Arm.STRAIGHT,
        "4_0_1": Arm.LEFT,
        "4_0_-1": Arm.LEFT,
    }


def test_town01_left_turn_against_oncoming_traffic(town01: PreparedGraph) -> None:
    prep = town01
    left = _route(prep, "18_0_1", "304_0_1", "4_0_1")
    straight = _route(prep, "18_0_1", "295_0_1", "17_0_1")
    oncoming = _route(prep, "17_0_-1", "296_0_-1", "18_0_-1")
    oncoming_right = _route(prep, "17_0_-1", "279_0_-1", "4_0_1")
    (span,) = junctions_on(prep, SceneMemo(), left)
    # Turning left crosses the oncoming straight lane; ad-map 5.0 calls this pair
    # opposite on Town01 only because it takes the left turn for a U-turn.
    assert relation(prep, SceneMemo(), left, span, oncoming) == Relation.CROSSING
    assert relation(prep, SceneMemo(), left, span, oncoming_right) == Relation.CROSSING
    (span,) = junctions_on(prep, SceneMemo(), straight)
    assert relation(prep, SceneMemo(), straight, span, oncoming) == Relation.OPPOSITE
    # The oncoming right turn neither passes back to the ego's arm nor crosses its lane.
    assert relation(prep, SceneMemo(), straight, span, oncoming_right) == Relation.OPPOSITE


def test_bucket_boundaries_match_ad_map_sectors() -> None:
    from rss.scene.junction_arms import _bucket  # noqa: PLC0415 - the sector function

    assert _bucket(0.0) == Arm.UTURN
    assert _bucket(math.radians(44.9)) == Arm.UTURN
    assert _bucket(math.radians(90.0)) == Arm.RIGHT
    assert _bucket(math.radians(180.0)) == Arm.STRAIGHT
    assert _bucket(math.radians(270.0)) == Arm.LEFT
    assert _bucket(math.radians(315.1)) == Arm.UTURN
    assert _bucket(math.radians(-90.0)) == Arm.LEFT


def test_town01_compat_mode_takes_the_left_turn_for_a_u_turn(town01: PreparedGraph) -> None:
    """``[scene] reproduce_adrss_5_0_defects``: ad-map 5.0's arms on Town01.

    Measured with the oracle (``Intersection.turnDirection`` of its predicted routes): the
    left turn 180151 -> 40151 (our 18_0_1 -> 4_0_1) is a U-turn, and on that route the
    oncoming straight route 2960149 -> 180149 is opposite (it reaches the "outgoing" U-turn
    arm at 180149, which is also the arm the ego came from).
    """
    prep = town01
    left = _route(prep, "18_0_1", "304_0_1", "4_0_1")
    oncoming = _route(prep, "17_0_-1", "296_0_-1", "18_0_-1")
    j = prep.junction_list[_lane(prep, "304_0_1")]
    arms = intersection_arms(prep, SceneMemo(), j, _lane(prep, "18_0_1"), admap_defects=True)
    assert arms[_lane(prep, "4_0_1")] == Arm.UTURN
    (span,) = junctions_on(prep, SceneMemo(), left)
    assert (
        relation(prep, SceneMemo(), left, span, oncoming, admap_defects=True) == Relation.OPPOSITE
    )
    assert relation(prep, SceneMemo(), left, span, oncoming) == Relation.CROSSING


def test_town01_compat_mode_route_ending_inside_turns_where_its_lanes_lead(
    town01: PreparedGraph,
) -> None:
    """A route ending inside the junction takes the exit its junction lanes lead to.

    ``[scene] reproduce_adrss_5_0_defects`` (ad-map ``successorsOnRouteLeavingIntersection``):
    the left turn cut after its junction lane 304_0_1 leaves at 4_0_1 as the whole route
    does (a U-turn for ad-map 5.0), so the oncoming straight route is opposite as well.
    Regression: this path raised ``NameError`` (a local name shadowed the ``exits`` helper;
    Town01 drive cross-check, seed 1 drive 6).
    """
    prep = town01
    left = _route(prep, "18_0_1", "304_0_1")
    oncoming = _route(prep, "17_0_-1", "296_0_-1", "18_0_-1")
    (span,) = junctions_on(prep, SceneMemo(), left)
    assert (
        relation(prep, SceneMemo(), left, span, oncoming, admap_defects=True) == Relation.OPPOSITE
    )
