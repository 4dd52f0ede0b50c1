"""A car that reaches the ego from behind while the ego's route reaches it ahead (issue 27).

Junction-route drive 8 of seed 4 (``town01_drives.drives(prep, 4, n, junction_routes=True)``,
``n`` > 8), car 2: the ego's route reaches the car ahead, about 82 m through a junction,
and the car's own route reaches the ego from behind (135 m by ad-map's measure: a road
segment is as long as its shortest lane). ad-map searches the routes from the object to
the ego apart from those from the ego to the object, so ad-rss 5.0 builds both
``SameDirection`` constellations and merges them into one with longitudinal distance 0:
dangerous in frames 33-37. Our route tree reached the car's lanes ahead only
(docs/rss_scene.md, "Routes behind the ego"); the compatibility mode now adds the routes
behind the ego (``FrameContext.behind_tree``).

The reference's verdicts (ad-rss-map-integration 5.0, ``tools/drive_crosscheck.py --seed 4
--n 10 --junction-routes``): the dangerous objects of frames 31-39.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import pytest

from loaders.maps.opendrive import read_opendrive
from rss.params import RestrictSpeedLimitMode, SceneSettings
from rss.scene import prepare
from tests.rss.scene.drive_crosscheck import our_drive
from tests.rss.scene.town01_drives import drives
from workbench.engines.rss.adapter import lane_graph_from_map

if TYPE_CHECKING:
    from pathlib import Path

#: ad-rss-map-integration 5.0's dangerous objects per frame of the drive.
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


@pytest.mark.parametrize("frames", [(31, 40)])
def test_car_behind_and_ahead_is_merged_as_ad_rss_does(
    external_dir: Path, frames: tuple[int, int]
) -> None:
    """The compatibility mode's dangerous objects are the reference's in every frame."""
    prep = prepare(lane_graph_from_map(read_opendrive(external_dir / "maps" / "Town01.xodr")))
    drive = drives(prep, 4, 9, junction_routes=True)[8]
    drive = {**drive, "frames": drive["frames"][frames[0] : frames[1]]}
    settings = SceneSettings(
        restrict_speed_limit_mode=RestrictSpeedLimitMode.NONE, reproduce_adrss_5_0_defects=True
    )
    mine = our_drive(prep, drive, settings)
    got = {frames[0] + k: answer["dangerous"] for k, answer in enumerate(mine)}
    assert got == REFERENCE_DANGEROUS
    merged = [s for s in mine[35 - frames[0]]["situations"] if s["id"] == 2]
    assert merged
    assert all(s["type"] == "SameDirection" for s in merged)
    assert min(s["lon_d"] for s in merged) == pytest.approx(0.0, abs=1e-6)
