"""Searches kept per map by ``predict_routes`` are reused only where a fresh search agrees."""

import numpy as np
import pytest

from loaders.maps.opendrive import read_opendrive
from rss.scene import SceneMemo, prepare
from rss.scene.routes import _search, predict_routes
from workbench.engines.rss.adapter import lane_graph_from_map


@pytest.fixture(scope="module")
def town01(external_dir):
    return prepare(lane_graph_from_map(read_opendrive(external_dir / "maps" / "Town01.xodr")))


def test_replayed_searches_equal_fresh_ones(town01):
    rng = np.random.default_rng(5)
    replayed = 0
    memo = SceneMemo()
    for _ in range(40):
        lane = int(rng.integers(0, len(town01.graph)))
        forward = bool(rng.integers(0, 2))
        travelled = float(rng.uniform(0.0, 20.0))
        horizon = float(rng.uniform(0.0, 250.0))
        for _ in range(6):  # a vehicle moving along: travelled and horizon drift
            travelled += float(rng.uniform(0.0, 1.5))
            horizon += float(rng.uniform(-3.0, 3.0))
            searches = memo.route_searches.get((lane, forward), [])
            known = [entry[0] for entry in searches]
            got = predict_routes(
                town01, memo, lane, forward=forward, horizon_m=horizon, travelled_m=travelled
            )
            fresh, *_ = _search(town01, (lane, forward), horizon, travelled)
            assert got == fresh
            newest = memo.route_searches[lane, forward][0][0]
            replayed += any(newest is routes for routes in known)
    assert replayed > 0  # kept searches were actually reused
    assert all(len(v) <= 4 for v in memo.route_searches.values())
