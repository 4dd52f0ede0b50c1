"""``--rss-profile auto``: highway on fast roads, urban in town, the reference without a map."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from loaders.maps.model import Lane, LaneKind, LaneMap
from loaders.open import open_drive
from workbench.engines.rss.auto_profile import auto_profile
from workbench.engines.rss.options import RssOptions, load_params

SAMPLES = Path(__file__).resolve().parents[4] / "sample_logs"


def _map(limits: list[float], kinds: list[LaneKind] | None = None) -> LaneMap:
    line = np.array([[0.0, 0.0], [10.0, 0.0]])
    kinds = kinds or [LaneKind.ROAD] * len(limits)
    lanes = {
        str(k): Lane(str(k), line, line, line, kind=kind, speed_limit_mps=limit)
        for k, (limit, kind) in enumerate(zip(limits, kinds, strict=True))
    }
    return LaneMap(lanes=lanes, source="test", format="test")


@pytest.mark.parametrize(
    ("name", "expected"),
    [
        ("highway_cut_in", "highway"),  # 130 km/h (docs/samples.md)
        ("hard_braking_lead", "highway"),  # 80 km/h
        ("wrong_way_oncoming", "highway"),  # 100 km/h
        ("urban_intersection", "urban"),  # 50 / 30 km/h
        ("pedestrian_crossing", "urban"),
        ("parking_lot", "urban"),
    ],
)
def test_samples(name: str, expected: str) -> None:
    drive = open_drive(SAMPLES / f"{name}.mcap")
    try:
        assert auto_profile(drive.lane_map) == expected
    finally:
        drive.close()


def test_threshold_and_maps_without_limits() -> None:
    assert auto_profile(None) == "adrss-5.0"
    assert auto_profile(_map([70.0 / 3.6])) == "highway"
    assert auto_profile(_map([69.0 / 3.6, 50.0 / 3.6])) == "urban"
    assert auto_profile(_map([float("nan")] * 3)) == "highway"  # a bare carriageway
    walk = [LaneKind.ROAD, LaneKind.SIDEWALK]
    assert auto_profile(_map([float("nan")] * 2, walk)) == "urban"


@pytest.mark.parametrize(
    ("name", "expected"),
    [
        ("USA_Lanker-2_23_T-1", "urban"),  # Lankershim Blvd: signalised junctions
        ("USA_Peach-4_8_T-1", "urban"),  # Peachtree St
        ("USA_US101-23_1_T-1", "highway"),  # US-101: a bare carriageway
    ],
)
def test_real_ngsim_maps(external_dir: Path, name: str, expected: str) -> None:
    """The real lanelet maps: town streets get ``urban``, the freeway ``highway``."""
    drive = open_drive(external_dir / "commonroad_ngsim" / f"{name}.xml")
    try:
        assert auto_profile(drive.lane_map) == expected
        params = load_params(RssOptions(), drive.lane_map)
    finally:
        drive.close()
    assert params.profile == expected
    assert params.standstill_speed_mps > 0.0  # both review profiles: the standstill rule
