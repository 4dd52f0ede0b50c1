"""Seeded random placements on CARLA Town01 (OpenDRIVE): every scene checks cleanly."""

from collections import Counter

import numpy as np
import pytest

from loaders.maps.opendrive import read_opendrive
from rss.params import DEFAULT_EGO_DYNAMICS, DEFAULT_VEHICLE_DYNAMICS, SceneSettings
from rss.scene import PreparedGraph, SceneEgo, SceneObjects, create_scene, prepare
from rss.structured.engine import check_frame
from rss.structured.stacking import stack_constellations
from workbench.engines.rss.adapter import lane_graph_from_map


@pytest.fixture(scope="module")
def town01(external_dir):
    return prepare(lane_graph_from_map(read_opendrive(external_dir / "maps" / "Town01.xodr")))


def _on_lane(prep: PreparedGraph, rng: np.random.Generator) -> tuple[float, float, float]:
    g = prep.graph
    lane = int(rng.integers(0, len(g)))
    c = g.centre_m[lane]
    k = int(rng.integers(0, len(c) - 1))
    d = c[k + 1] - c[k]
    return float(c[k, 0]), float(c[k, 1]), float(np.arctan2(d[1], d[0]))


def test_random_pairs_build_valid_constellations(town01):
    rng = np.random.default_rng(2024)
    kinds: Counter[str] = Counter()
    for _ in range(300):
        x, y, yaw = _on_lane(town01, rng)
        ego = SceneEgo(0, x, y, yaw, 8.0, 4.5, 2.0, DEFAULT_EGO_DYNAMICS)
        rows = [_on_lane(town01, rng) for _ in range(3)]
        n = len(rows)
        arr = np.array(rows)
        near = arr[np.hypot(arr[:, 0] - x, arr[:, 1] - y) > 5.0]
        n = len(near)
        objects = SceneObjects(
            ids=np.arange(1, n + 1, dtype=np.int64),
            object_type=np.full(n, 2, dtype=np.int64),
            x_m=near[:, 0],
            y_m=near[:, 1],
            yaw_rad=near[:, 2],
            vx_mps=8.0 * np.cos(near[:, 2]),
            vy_mps=8.0 * np.sin(near[:, 2]),
            length_m=np.full(n, 4.5),
            width_m=np.full(n, 1.9),
            dynamics=(DEFAULT_VEHICLE_DYNAMICS,) * n,
        )
        scene = create_scene(town01, ego, objects, SceneSettings())
        assert scene.ego_on_map
        if scene.constellations:
            result, _ = check_frame(
                stack_constellations(scene.constellations), DEFAULT_EGO_DYNAMICS
            )
            assert (result.invalid == 0).all()
        kinds.update(c.constellation_type.name for c in scene.constellations)
    assert kinds["SameDirection"] > 0
    assert kinds["OppositeDirection"] > 0
    assert sum(v for k, v in kinds.items() if k.startswith("Intersection")) > 0
