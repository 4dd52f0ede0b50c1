"""The scene bench's reference timing (ad-rss map integration 5.0) on 2 frames, 3 objects.

Needs ``RSS_MAP_ORACLE_PYTHON`` (the ad-rss-map-integration 5.0 interpreter, §8.4; ``make
oracle-adrss-map`` sets it) and Town01; skipped otherwise. Checks the output's structure
and that ad-rss finds constellations for vehicles on the ego's lane; no timing assertions.
"""

import dataclasses
import os
import sys
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from bench.scene_reference import (
    reference_ms_per_frame,
    reference_unavailable,
    scene_frame,
)
from loaders.maps.opendrive import read_opendrive
from rss.arrays import FloatArray
from rss.params import DEFAULT_EGO_DYNAMICS, DEFAULT_VEHICLE_DYNAMICS
from rss.scene import SceneEgo, SceneObjects
from workbench.engines.rss.adapter import lane_graph_from_map

PHASES = {"matching", "append", "world_model", "extraction", "checking", "resolving"}


def _on_longest_lane(town: Path, arc_m: FloatArray) -> tuple[FloatArray, FloatArray, FloatArray]:
    """Poses ``(x, y, yaw)`` at arc lengths ``arc_m`` along Town01's longest lane."""
    graph = lane_graph_from_map(read_opendrive(town))
    lengths = [float(np.hypot(*np.diff(c, axis=0).T).sum()) for c in graph.centre_m]
    centre = graph.centre_m[int(np.argmax(lengths))]
    s = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(centre, axis=0).T))])
    k = np.searchsorted(s, arc_m)
    d = centre[k + 1] - centre[k]
    return centre[k, 0], centre[k, 1], np.arctan2(d[:, 1], d[:, 0])


def _frames(town: Path) -> list[dict[str, Any]]:
    x, y, yaw = _on_longest_lane(town, np.array([40.0, 55.0, 70.0, 20.0]))
    ego = SceneEgo(0, float(x[0]), float(y[0]), float(yaw[0]), 8.0, 4.5, 2.0, DEFAULT_EGO_DYNAMICS)
    speed = np.array([5.0, 10.0, 12.0])
    objects = SceneObjects(
        ids=np.arange(1, 4),
        object_type=np.full(3, 2),
        x_m=x[1:],
        y_m=y[1:],
        yaw_rad=yaw[1:],
        vx_mps=speed * np.cos(yaw[1:]),
        vy_mps=speed * np.sin(yaw[1:]),
        length_m=np.full(3, 4.5),
        width_m=np.full(3, 1.9),
        dynamics=(DEFAULT_VEHICLE_DYNAMICS,) * 3,
    )
    moved = dataclasses.replace(objects, x_m=objects.x_m + 0.1 * objects.vx_mps)
    return [scene_frame(ego, objects), scene_frame(ego, moved)]


def test_frame_format_is_plain_json(external_dir):
    frames = _frames(external_dir / "maps" / "Town01.xodr")
    assert [len(f["objects"]) for f in frames] == [3, 3]
    assert frames[0]["ego"]["response_time"] == 1.0
    assert frames[0]["objects"][1]["v"] == pytest.approx(10.0)
    assert frames[1]["objects"][2]["x"] != frames[0]["objects"][2]["x"]


def test_reference_timing_structure(external_dir):
    if not os.environ.get("RSS_MAP_ORACLE_PYTHON"):
        pytest.skip(
            "RSS_MAP_ORACLE_PYTHON (ad-rss-map-integration 5.0 interpreter) not set; "
            "`make test` runs this module with its side venv (make oracle-adrss-map)"
        )
    town = external_dir / "maps" / "Town01.xodr"
    assert reference_unavailable(town) is None
    result = reference_ms_per_frame(_frames(town), town)
    assert result is not None
    assert result["frames"] == 2
    assert set(result["ms_per_frame"]) == PHASES
    assert all(ms >= 0.0 for ms in result["ms_per_frame"].values())
    assert result["failed_frames"] == 0
    assert result["relevant_per_frame"] > 0
    assert result["constellations_per_frame"] >= result["relevant_per_frame"]
    assert result["situations_per_frame"] > 0
    assert sum(result["types_per_frame"].values()) == result["constellations_per_frame"]


def test_reference_unavailable_says_why(tmp_path, monkeypatch):
    osm = tmp_path / "map.osm"
    osm.write_text("<osm/>")
    monkeypatch.setenv("RSS_MAP_ORACLE_PYTHON", str(tmp_path / "no-python"))
    assert "missing" in (reference_unavailable(osm) or "")
    assert reference_ms_per_frame([], osm) is None
    monkeypatch.setenv("RSS_MAP_ORACLE_PYTHON", sys.executable)
    assert "OpenDRIVE" in (reference_unavailable(osm) or "")
    assert reference_ms_per_frame([], osm) is None
