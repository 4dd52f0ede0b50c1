"""Lateral steps of the route tree cost the distance between the lanes' centre lines.

ad-map's route expansion (``RouteExpander::createNeighbor``) charges a lane change the
distance between the points at the same parametric offset on both lanes (at least
0.1 m), so a connecting route does not detour through neighbour lanes to a shorter
parallel lane when the lane changes cost more than the saving.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import pytest

from loaders.maps.opendrive import read_opendrive
from rss.scene import SceneMemo, prepare
from rss.scene.routes import connect
from tests.rss.scene.synthetic import WIDTH, straight_road
from workbench.engines.rss.adapter import lane_graph_from_map

if TYPE_CHECKING:
    from pathlib import Path

    from rss.scene import PreparedGraph


def test_lateral_step_costs_the_lane_width():
    prep = prepare(straight_road(3, 200.0))
    tree = connect(prep, SceneMemo(), 0, forward=True, horizon_m=50.0, start=0.5)
    # centre lines of neighbouring lanes lie WIDTH apart on the straight road
    assert tree.cost_m[1] == pytest.approx(WIDTH)
    assert tree.cost_m[2] == pytest.approx(2 * WIDTH)
    assert (tree.j[1], tree.j[2]) == (1, 2)


def test_lateral_step_into_an_opposite_lane_costs_the_lane_width():
    prep = prepare(straight_road(2, 200.0, opposite_left=True))
    tree = connect(prep, SceneMemo(), 1, forward=True, horizon_m=50.0, start=0.25)
    assert tree.cost_m[0] == pytest.approx(WIDTH)
    assert not tree.forward[0]


@pytest.fixture(scope="module")
def town01(external_dir: Path) -> PreparedGraph:
    return prepare(lane_graph_from_map(read_opendrive(external_dir / "maps" / "Town01.xodr")))


def test_route_keeps_the_junction_lane_rather_than_the_shorter_parallel_one(town01):
    # Town01 pair 397 of the cross-check: from lane -1 of road 21 back to lane -1 of
    # road 2, ad-map's connecting route stays on junction lane 128/-1 (23.8 m) although
    # the parallel junction lane 131/+1 between the opposite lanes is 6.9 m shorter: two
    # lane changes of one lane width (4 m in Town01) each cost more than that.
    ids = list(town01.graph.ids)
    root = ids.index("21_0_-1")
    tree = connect(town01, SceneMemo(), root, forward=True, horizon_m=60.0, start=0.03)
    path = [ids[lane] for lane in tree.path(ids.index("2_0_-1"))]
    assert path == ["21_0_-1", "128_0_-1", "2_0_-1"]
    assert tree.cost_m[ids.index("21_0_1")] == pytest.approx(4.0, abs=1e-6)
