"""Further route roots: the lanes the ego occupies besides its anchor that no link joins.

ad-map routes from every region the ego occupies. On Town01 the ego straddles two
overlapping junction lanes; cars reached only from the other lane had no connecting
route (drive cross-check, docs/rss_scene.md "Further route roots"). The expected types
are ad-rss-map-integration 5.0's answers on these frames (the drive oracle, cached by
``tests/rss/scene/test_crosscheck_drives.py``).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import pytest

from loaders.maps.opendrive import read_opendrive
from rss.model import ConstellationType
from rss.params import RestrictSpeedLimitMode, SceneSettings
from rss.scene import SceneMemo, create_scene, prepare
from rss.scene.create import more_roots, scene_boxes
from rss.scene.matching import match_boxes
from tests.rss.scene.drive_crosscheck import frame_inputs, our_drive
from tests.rss.scene.town01_drives import drives as make_drives
from workbench.engines.rss.adapter import lane_graph_from_map

if TYPE_CHECKING:
    from pathlib import Path

    from rss.scene import PreparedGraph

pytestmark = pytest.mark.external

SETTINGS = SceneSettings(restrict_speed_limit_mode=RestrictSpeedLimitMode.NONE)


@pytest.fixture(scope="module")
def town01(external_dir: Path) -> PreparedGraph:
    return prepare(lane_graph_from_map(read_opendrive(external_dir / "maps" / "Town01.xodr")))


def _types(prep: PreparedGraph, where: tuple[int, float, int, int], obj: int) -> set[str]:
    """Constellation types with ``obj`` at ``(seed, min gap, drive, frame)``."""
    seed, gap, drive, frame = where
    ego, objects = frame_inputs(make_drives(prep, seed, drive + 1, gap)[drive]["frames"][frame])
    scene = create_scene(prep, ego, objects, SETTINGS, memo=SceneMemo())
    return {c.constellation_type.name for c in scene.constellations if c.other.object_id == obj}


def test_car_behind_the_other_overlapping_lane_follows(town01: PreparedGraph) -> None:
    # seed 1 drive 6 frame 22: the anchor switched to 201_0_-1; the car behind on 18_0_-1
    # is a predecessor of the overlapping 218_0_-1 only (ad-rss: SameDirection)
    ids = list(town01.graph.ids)
    ego, objects = frame_inputs(make_drives(town01, 1, 7, 6.0)[6]["frames"][22])
    matches = match_boxes(town01, scene_boxes(ego, objects))
    assert ids[matches.anchors[0]] == "201_0_-1"
    assert [ids[lane] for lane, _, _ in more_roots(town01, matches, ego)] == ["218_0_-1"]
    assert _types(town01, (1, 6.0, 6, 22), 5) == {ConstellationType.SameDirection.name}


def test_car_ahead_reached_from_the_other_lane_follows(town01: PreparedGraph) -> None:
    # seed 2 (gap 0) drive 7 frame 34: the car ahead on 10_0_1 is reached from the
    # overlapping 232_0_1 (ad-rss: SameDirection 8.75 m); it was a merging pair
    assert _types(town01, (2, 0.0, 7, 34), 2) == {ConstellationType.SameDirection.name}


def test_oncoming_car_beside_the_other_lane_is_opposite(town01: PreparedGraph) -> None:
    # seed 2 (gap 0) drive 18 frame 25: the oncoming car on 188_0_-1, the opposite
    # neighbour of 193_0_1 (ad-rss: OppositeDirection at distance 0); no constellation before
    assert _types(town01, (2, 0.0, 18, 25), 1) == {ConstellationType.OppositeDirection.name}


def test_routes_of_every_root_join_and_merge(town01: PreparedGraph) -> None:
    # seed 2 (gap 0) drive 14 frame 18: the ego straddles 179_0_1, 193_0_1, 188_0_-1 and
    # 184_0_1; the anchor's tree already reaches the oncoming car 6, but the route from
    # 193_0_1 is shorter and lies on the other side: ad-rss merges the two
    # OppositeDirection constellations to 40.44 m / lateral 0 m, dangerous (before: the
    # anchor's route only, 41.48 m / 1.61 m, safe)
    drive = {"frames": [make_drives(town01, 2, 15, 0.0)[14]["frames"][18]]}
    (frame,) = our_drive(town01, drive, SETTINGS)
    car = next(s for s in frame["situations"] if s["id"] == 6 and s["type"] == "OppositeDirection")
    assert car["lon_d"] == pytest.approx(40.44, abs=0.01)
    assert car["lat_d"] == pytest.approx(0.0, abs=1e-9)
    assert 6 in frame["dangerous"]


def test_oncoming_car_on_the_overlapping_junction_lane_is_opposite(town01: PreparedGraph) -> None:
    # seed 2 (gap 0) drive 18 frame 27: the car on 183_0_1, which ad-map links to the ego's
    # 184_0_1 as its neighbour (their borders meet at both ends; ad-rss: OppositeDirection
    # 0.00 m / 2.07 m, dangerous); no constellation before the reader linked them
    assert _types(town01, (2, 0.0, 18, 27), 1) == {ConstellationType.OppositeDirection.name}
