"""RSS scene creation from a lane graph (ad-rss ``RssWorldModelCreation``), pure numpy/shapely.

``LaneGraph`` (plain arrays, built by the workbench from a lane map) -> ``prepare`` once per
map -> ``create_scene`` per frame -> ``rss.model`` constellations for ``rss.engine``.
See ``docs/rss_scene.md``.
"""

from __future__ import annotations

from rss.scene.create import create_scene
from rss.scene.inputs import Scene, SceneEgo, SceneObjects, conservative_stop_m
from rss.scene.lanegraph import LaneGraph, PreparedGraph, prepare
from rss.scene.matching import BoxArrays, Matches, match_boxes

__all__ = [
    "BoxArrays",
    "LaneGraph",
    "Matches",
    "PreparedGraph",
    "Scene",
    "SceneEgo",
    "SceneObjects",
    "conservative_stop_m",
    "create_scene",
    "match_boxes",
    "prepare",
]
