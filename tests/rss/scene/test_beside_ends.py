"""Compatibility mode: speeds of two vehicles beside each other on opposite neighbour lanes.

ad-map's connecting route between two vehicles whose regions on opposite neighbour lanes
overlap longitudinally runs from the ego's front (or rear) to the object's far (or near)
end, and ad-rss resolves each vehicle's speeds along the road direction at those ends
(``rss.scene.corridor.admap_beside_ends``). The expected speeds are ad-rss-map-integration
5.0's world-model values on these Town01 drive frames (measured with the oracle
interpreter, ``RssWorldModelCreation.appendConstellations``).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import pytest

from loaders.maps.opendrive import read_opendrive
from rss.model import ConstellationType
from rss.params import RestrictSpeedLimitMode, SceneSettings
from rss.scene import SceneMemo, create_scene, prepare
from tests.rss.scene.drive_crosscheck import frame_inputs
from tests.rss.scene.town01_drives import drives as make_drives
from workbench.engines.rss.adapter import lane_graph_from_map

if TYPE_CHECKING:
    from pathlib import Path

    from rss.scene import PreparedGraph

pytestmark = pytest.mark.external

DEFAULT = SceneSettings(restrict_speed_limit_mode=RestrictSpeedLimitMode.NONE)
COMPAT = SceneSettings(
    restrict_speed_limit_mode=RestrictSpeedLimitMode.NONE, reproduce_adrss_5_0_defects=True
)


@pytest.fixture(scope="module")
def town01(external_dir: Path) -> PreparedGraph:
    return prepare(lane_graph_from_map(read_opendrive(external_dir / "maps" / "Town01.xodr")))


def _speeds(
    prep: PreparedGraph, where: tuple[int, int], obj: int, settings: SceneSettings
) -> list[tuple[float, float, float, float]]:
    """``(ego lon, ego lat, object lon, object lat)`` [m/s] of each OppositeDirection
    constellation with ``obj`` at seed-1 ``(drive, frame)``."""
    drive, frame = where
    ego, objects = frame_inputs(make_drives(prep, 1, drive + 1, 6.0)[drive]["frames"][frame])
    scene = create_scene(prep, ego, objects, settings, memo=SceneMemo())
    return sorted(
        (
            c.ego.speed.lon_max_mps,
            c.ego.speed.lat_max_mps,
            c.other.speed.lon_max_mps,
            c.other.speed.lat_max_mps,
        )
        for c in scene.constellations
        if c.other.object_id == obj and c.constellation_type == ConstellationType.OppositeDirection
    )


def test_route_from_the_ego_front_to_the_object_far_end(town01: PreparedGraph) -> None:
    # drive 1 frame 4: the ego on 13_0_1 beside a car oncoming on 13_0_-1 that reaches
    # past its front; ad-map's route runs from the ego's front to the car's far end
    (got,) = _speeds(town01, (1, 4), 5, COMPAT)
    assert got == pytest.approx((7.52676, 1.04698, 8.11472, -3.41258), abs=1e-4)
    # the default mode: its own constellation (road direction at each vehicle) and
    # ad-map's beside it, merged into their worst case by the engine
    found = _speeds(town01, (1, 4), 5, DEFAULT)
    assert len(found) == 2
    own = next(c for c in found if c != pytest.approx(got, abs=1e-4))
    assert own[1] != pytest.approx(got[1], abs=0.1)
    assert any(c == pytest.approx(got, abs=1e-4) for c in found)


def test_route_from_the_ego_rear_where_its_front_is_past_the_object(
    town01: PreparedGraph,
) -> None:
    # drive 7 frame 12: the ego on 20_0_1 passing a car standing on 20_0_-1; its front is beyond the
    # car's far end, so the route starts at the ego's rear (ad-rss: ego lat -2.005 m/s)
    (got,) = _speeds(town01, (7, 12), 4, COMPAT)
    assert got == pytest.approx((8.9026, -2.005, 0.0, 0.0), abs=1e-4)


def test_one_route_per_region_of_an_ego_straddling_two_lanes(town01: PreparedGraph) -> None:
    # drive 4 frame 1: the ego on 20_0_1 and on 15_0_-1 before it; ad-map's second route
    # starts at the end of 15_0_1 and ends at the car's near end (ad-rss merges the two)
    first, second = _speeds(town01, (4, 1), 2, COMPAT)
    assert first == pytest.approx((12.9696, 0.740408, 13.0548, -4.64966), abs=1e-4)
    assert second == pytest.approx((12.9907, 0.0, 13.4991, 3.13375), abs=1e-4)
    found = _speeds(town01, (4, 1), 2, DEFAULT)
    assert len(found) == 3
    for want in (first, second):
        assert any(c == pytest.approx(want, abs=1e-4) for c in found)
