"""A malformed constellation is named in the frame's verdict and record; the frame goes on."""

from __future__ import annotations

import dataclasses
from pathlib import Path
from typing import TYPE_CHECKING, Any

import rss.evaluate
from loaders import open_drive
from rss.scene import create_scene
from tests.workbench.engines.helpers import record
from workbench.engines.rss.runner import RssRunner

if TYPE_CHECKING:
    import pytest

SAMPLE = Path(__file__).resolve().parents[4] / "sample_logs" / "highway_cut_in.mcap"


def test_rejected_constellation_is_reported_by_object_and_reason(monkeypatch: pytest.MonkeyPatch):
    drive = open_drive(SAMPLE)
    frames = [f for _, f in zip(range(5), drive.frames(), strict=False)]
    lane_map = drive.lane_map
    drive.close()
    good = RssRunner(lane_map).step_many(frames)
    original = create_scene

    def lane_twice(*args: Any, **kwargs: Any) -> Any:
        scene = original(*args, **kwargs)
        if not scene.constellations:
            return scene
        first = scene.constellations[0]
        seg = first.ego_road[0]
        twice = dataclasses.replace(seg, lanes=(seg.lanes[0], *seg.lanes))
        broken = dataclasses.replace(first, ego_road=(twice, *first.ego_road[1:]))
        return dataclasses.replace(scene, constellations=(broken, *scene.constellations[1:]))

    monkeypatch.setattr(rss.evaluate, "create_scene", lane_twice)
    got = RssRunner(lane_map).step_many(frames)
    checked = 0
    for verdict, reference in zip(got, good, strict=True):
        if not reference.labels:
            continue
        name = reference.labels[0]
        line = record(verdict)
        assert list(line["rejected_constellations"]) == [name]
        assert "lane" in line["rejected_constellations"][name]
        assert name in line["invalid_objects"]
        assert verdict.labels == reference.labels[1:]
        assert "rejected_constellations" not in record(reference)
        checked += 1
    assert checked > 0
