"""``--rss-profile auto``: highway on fast roads, the reference in town and without a map."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from loaders.maps.model import Lane, LaneKind, LaneMap
from loaders.open import open_drive
from workbench.engines.rss.auto_profile import auto_profile

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
        ("urban_intersection", "adrss-5.0"),  # 50 / 30 km/h
        ("pedestrian_crossing", "adrss-5.0"),
        ("parking_lot", "adrss-5.0"),
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
    assert auto_profile(_map([69.0 / 3.6, 50.0 / 3.6])) == "adrss-5.0"
    assert auto_profile(_map([float("nan")] * 3)) == "highway"  # a bare carriageway
    walk = [LaneKind.ROAD, LaneKind.SIDEWALK]
    assert auto_profile(_map([float("nan")] * 2, walk)) == "adrss-5.0"
