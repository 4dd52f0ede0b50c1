"""The horizon-interval memo of ``predict_routes`` returns what a fresh search returns."""

import numpy as np
import pytest

from loaders.maps.opendrive import read_opendrive
from rss.scene import SceneMemo, prepare
from rss.scene.routes import RouteMemo, predict_routes
from workbench.engines.rss.adapter import lane_graph_from_map


@pytest.fixture(scope="module")
def town01(external_dir):
    return prepare(lane_graph_from_map(read_opendrive(external_dir / "maps" / "Town01.xodr")))


def test_memoised_routes_equal_fresh_search(town01):
    rng = np.random.default_rng(3)
    memo: RouteMemo = {}
    scene_memo = SceneMemo()
    hits = 0
    for _ in range(60):
        lane = int(rng.integers(0, len(town01.graph)))
        forward = bool(rng.integers(0, 2))
        travelled = float(rng.choice([0.0, 3.5, 12.0]))
        for horizon in rng.uniform(0.0, 300.0, 8):
            before = sum(len(v) for v in memo.values())
            got = predict_routes(
                town01,
                scene_memo,
                lane,
                forward=forward,
                horizon_m=horizon,
                travelled_m=travelled,
                frame_routes=memo,
            )
            hits += sum(len(v) for v in memo.values()) == before
            fresh = predict_routes(
                town01, SceneMemo(), lane, forward=forward, horizon_m=horizon, travelled_m=travelled
            )
            assert got == fresh
    assert hits > 0  # the memo was actually used
