"""``match_route`` never puts a lane twice on a route (issue 17, ``USA_Peach-4_8_T-1``).

Where two lanes overlap (a lane splitting into straight on and a turn), a plan's waypoints
can pick one, then the other, then the first again. The route used to keep ``a, b, a``;
scene creation then built a road area holding lane ``a`` twice, which the RSS check
rejects ("lane id=13: duplicate or negative") and the whole drive failed.
"""

from __future__ import annotations

import itertools
from typing import TYPE_CHECKING

import numpy as np
import pytest

from loaders.open import open_drive
from rss.params import RssParams
from rss.scene import create_scene, prepare
from rss.scene.matching import match_route
from rss.structured.stacking import stack_constellations
from tests.rss.scene.synthetic import straight_road
from workbench.engines.ids import ActorIds
from workbench.engines.rss.adapter import frame_to_scene, lane_graph_from_map

if TYPE_CHECKING:
    from rss.model import Constellation


def test_a_return_to_a_lane_drops_the_detour():
    prep = prepare(straight_road(3))
    y = [float(np.mean(c[:, 1])) for c in prep.graph.centre_m]
    xs = np.linspace(10.0, 150.0, 15)
    lane = np.repeat([1, 0, 1, 2], [4, 3, 4, 4])  # lane 1, over to 0, back to 1, on to 2
    xy = np.stack([xs, np.array(y)[lane]], axis=1)
    route = match_route(prep, xy, np.zeros(len(xs)))
    assert route == [(1, True), (2, True)]


@pytest.mark.external
def test_peach_4_8_routes_and_constellations(external_dir):
    drive = open_drive(external_dir / "commonroad_ngsim" / "USA_Peach-4_8_T-1.xml")
    try:
        assert drive.lane_map is not None
        graph = lane_graph_from_map(drive.lane_map)
        prep, params, ids = prepare(graph), RssParams(), ActorIds()
        frames = list(itertools.islice(drive.frames(), 4))
    finally:
        drive.close()
    constellations: list[Constellation] = []
    for frame in frames:
        ego, objects, _ = frame_to_scene(frame, prep, params, ids)
        lanes = [lane for lane, _ in ego.route]
        assert len(lanes) == len(set(lanes))
        scene = create_scene(prep, ego, objects, params.scene)
        for c in scene.constellations:
            for road in (c.ego_road, c.intersecting_road):
                on_road = [lane.lane_id for segment in road for lane in segment.lanes]
                assert len(on_road) == len(set(on_road))
        constellations += scene.constellations
    # the plan runs straight on through the split (lanelet 43343 -> 43594), not into the turn
    first = frames[0]
    ego, _, _ = frame_to_scene(first, prep, params, ids)
    assert [graph.ids[lane] for lane, _ in ego.route] == ["43343", "43594"]
    assert stack_constellations(constellations).size == len(constellations) > 0
