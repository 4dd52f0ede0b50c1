"""A car that reaches the ego from behind while the ego's route reaches it ahead (issue 27).

Junction-route drive 8 of seed 4 (``town01_drives.drives(prep, 4, n, junction_routes=True)``,
``n`` > 8), car 2: the ego's route reaches the car ahead, about 82 m through a junction,
and the car's own route reaches the ego from behind (135 m by ad-map's measure: a road
segment is as long as its shortest lane). ad-map searches the routes from the object to
the ego apart from those from the ego to the object, so ad-rss 5.0 builds both
``SameDirection`` constellations and merges them into one with longitudinal distance 0:
dangerous in frames 33-37. Our route tree reached the car's lanes ahead only
(docs/rss_scene.md, "Routes behind the ego"); both modes now add the routes behind the
ego (``FrameContext.behind_tree``). Also of the same drives: the default mode's worst case
with ad-rss' swapped route headings (drive 5) and the compatibility mode's route length
between the two regions (drive 1; docs/rss_scene.md, "Default mode: no reference danger
missed").

The reference's verdicts (ad-rss-map-integration 5.0, ``tools/drive_crosscheck.py --seed 4
--n 10 --junction-routes``): the dangerous objects of the frames checked.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import pytest

from loaders.maps.opendrive import read_opendrive
from rss.params import RestrictSpeedLimitMode, SceneSettings
from rss.scene import PreparedGraph, prepare
from tests.rss.scene.drive_crosscheck import our_drive
from tests.rss.scene.town01_drives import drives
from workbench.engines.rss.adapter import lane_graph_from_map

if TYPE_CHECKING:
    from pathlib import Path

#: ad-rss-map-integration 5.0's dangerous objects per frame of drive 8.
REFERENCE_DANGEROUS = {
    31: [],
    32: [],
    33: [2],
    34: [2],
    35: [2],
    36: [2],
    37: [2],
    38: [],
    39: [],
}

#: The reference's dangerous objects in frames 22-29 of drive 5 (car 3 follows the ego).
REFERENCE_DRIVE_5 = {22: [3], 23: [3], 24: [3], 25: [3], 26: [3], 27: [], 28: [], 29: []}
#: The reference's dangerous objects in frames 21-24 of drive 1 (car 3 behind and ahead).
REFERENCE_DRIVE_1 = {21: [], 22: [], 23: [3], 24: [3]}


@pytest.fixture(scope="module")
def town01(external_dir: Path) -> PreparedGraph:
    """The prepared Town01 graph."""
    return prepare(lane_graph_from_map(read_opendrive(external_dir / "maps" / "Town01.xodr")))


def dangerous_objects(
    prep: PreparedGraph, index: int, frames: tuple[int, int], *, compat: bool
) -> tuple[dict[int, list[int]], list[dict[str, Any]]]:
    """Our dangerous objects per frame of junction-route drive ``index`` of seed 4."""
    drive = drives(prep, 4, max(index + 1, 9), junction_routes=True)[index]
    drive = {**drive, "frames": drive["frames"][frames[0] : frames[1]]}
    settings = SceneSettings(
        restrict_speed_limit_mode=RestrictSpeedLimitMode.NONE, reproduce_adrss_5_0_defects=compat
    )
    mine = our_drive(prep, drive, settings)
    return {frames[0] + k: answer["dangerous"] for k, answer in enumerate(mine)}, mine


@pytest.mark.parametrize("compat", [True, False])
def test_car_behind_and_ahead_is_merged_as_ad_rss_does(
    town01: PreparedGraph, *, compat: bool
) -> None:
    """Both modes: the dangerous objects are the reference's in every frame.

    The default mode searches the routes behind the ego as the compatibility mode does
    (ad-map's measure of a road segment: the routes reach the car within the relevance
    distance only by it; along the car's own lanes the route is 148 m, beyond it), so it
    never calls the frames safe that ad-rss calls dangerous by the two routes' worst case.
    """
    frames = (31, 40)
    got, mine = dangerous_objects(town01, 8, frames, compat=compat)
    assert got == REFERENCE_DANGEROUS
    merged = [s for s in mine[35 - frames[0]]["situations"] if s["id"] == 2]
    assert len(merged) >= 2
    assert all(s["type"] == "SameDirection" for s in merged)
    assert min(s["lon_d"] for s in merged) == pytest.approx(0.0, abs=1e-6)


def test_follower_is_dangerous_where_ad_rss_swaps_its_headings(town01: PreparedGraph) -> None:
    """Default mode, junction-route drive 5 of seed 4: car 3 follows the ego out of a
    junction (``SameDirection`` 3.03 m in frame 26 on both sides).

    ad-rss 5.0 resolves the two vehicles' speeds along each other's route headings and
    calls frame 26 dangerous; the vehicles' own headings make it safe. The default mode
    adds the swapped constellation to the own one and the engine merges them into their
    worst case: dangerous as for the reference, in every frame.
    """
    got, mine = dangerous_objects(town01, 5, (22, 30), compat=False)
    assert got == REFERENCE_DRIVE_5
    car = [s for s in mine[26 - 22]["situations"] if s["id"] == 3]
    assert len(car) >= 2
    assert all(s["lon_d"] == pytest.approx(3.03, abs=0.01) for s in car)


def test_route_length_is_measured_between_the_regions(town01: PreparedGraph) -> None:
    """Compatibility mode, junction-route drive 1 of seed 4: car 3 reaches the ego from
    behind, from the ego's region on 3390149 (the ego straddles three lanes).

    ad-map's route between the two regions is 120.43 m in frame 22 (beyond the 120.36 m
    relevance distance) and 119.91 m in frame 23; from the box centres less half their
    lengths it was 120.27 m, relevant one frame early (merged with the route ahead:
    dangerous for us only). Measured between the regions' ends, frames 21-24 are the
    reference's; the default mode keeps the shorter measure (dangerous from frame 22).
    """
    got, _ = dangerous_objects(town01, 1, (21, 25), compat=True)
    assert got == REFERENCE_DRIVE_1
    default, _ = dangerous_objects(town01, 1, (21, 25), compat=False)
    assert all(set(want) <= set(default[k]) for k, want in REFERENCE_DRIVE_1.items())
