"""The small-frame path on real urban scene frames (CARLA Town01, from ``shared/external``).

The scene bench's drives (``bench.bench_scene``: 50 vehicles within 120 m of the ego,
constant velocity) give frames of ~40-60 constellations, many of them several intersection
routes of one object. Each frame, one call at a time as ``RssRunner.step`` makes it, must
take the row path (``check_frame_small`` does not hand it to the batched engine) and give
every field of the result and the memory as ``check_frames`` does for ``F = 1``.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
import pytest

from bench.bench_scene import _drives
from loaders.maps.opendrive import read_opendrive
from rss.model import ConstellationType
from rss.params import DEFAULT_EGO_DYNAMICS, SceneSettings
from rss.scene import SceneMemo, create_scene, prepare
from rss.structured.engine import check_frame, check_frames
from rss.structured.small import check_frame_small
from rss.structured.small_output import recall
from rss.structured.small_result import SmallMemory
from rss.structured.stacking import stack_constellations
from tests.rss.structured.test_small import _assert_same
from workbench.engines.rss.adapter import lane_graph_from_map

if TYPE_CHECKING:
    from pathlib import Path

    from rss.scene import PreparedGraph
    from rss.structured.memory import RssMemory


@pytest.fixture(scope="module")
def town01(external_dir: Path) -> PreparedGraph:
    path = external_dir / "maps" / "Town01.xodr"
    if not path.is_file():
        pytest.fail(f"{path} missing from the external test data")
    return prepare(lane_graph_from_map(read_opendrive(path)))


def test_town01_scene_frames_take_the_row_path(town01: PreparedGraph) -> None:
    """Every frame of 3 drives x 8 frames: row path taken, equal to the batched engine."""
    memo = SceneMemo()
    frames = duplicated = 0
    for drive in _drives(town01, 3, 8):
        ours_memory: RssMemory | None = None
        batched_memory: RssMemory | None = None
        for ego, objects in drive:
            scene = create_scene(town01, ego, objects, SceneSettings(), memo=memo)
            if not scene.constellations:
                ours_memory = batched_memory = None
                continue
            batch = stack_constellations(scene.constellations)
            before = {}
            if isinstance(ours_memory, SmallMemory):
                before = ours_memory.before
            elif ours_memory is not None and ours_memory.size:
                before = recall(ours_memory)
            assert check_frame_small(batch, DEFAULT_EGO_DYNAMICS, before) is not None
            ours, ours_memory = check_frame(batch, DEFAULT_EGO_DYNAMICS, ours_memory)
            batched, batched_memory = check_frames(
                batch, np.zeros(batch.size, dtype=np.int64), 1, DEFAULT_EGO_DYNAMICS, batched_memory
            )
            _assert_same(ours, batched)
            _assert_same(ours_memory, batched_memory)
            keys = [
                (c.other.object_id, c.constellation_type)
                for c in scene.constellations
                if c.constellation_type >= ConstellationType.IntersectionEgoHasPriority
            ]
            frames += 1
            duplicated += len(keys) > len(set(keys))
    assert frames >= 20  # the drives do give scene frames
    assert duplicated > 0  # and some hold one object's intersection type twice
