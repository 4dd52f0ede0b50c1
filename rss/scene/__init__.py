"""RSS scene creation from a lane graph (ad-rss ``RssWorldModelCreation``), pure numpy/shapely.

``LaneGraph`` (plain arrays, built by the workbench from a lane map) -> ``prepare`` once per
map (``PreparedGraph``: frozen data) -> ``create_scene`` per frame, with one ``SceneMemo``
per map owned by the caller -> ``rss.model`` constellations for ``rss.engine``.
See ``docs/rss_scene.md``. The per-object modules run compiled (mypyc) when the
application switched the compiled build on before importing them (``rss.compiled``;
results identical).
"""

from __future__ import annotations

from rss.scene.create import create_scene
from rss.scene.inputs import Scene, SceneEgo, SceneObjects, conservative_stop_m
from rss.scene.lanegraph import LaneGraph
from rss.scene.match_records import BoxArrays, Matches
from rss.scene.matching import match_boxes
from rss.scene.memo import SceneMemo
from rss.scene.prepared import PreparedGraph, prepare

__all__ = [
    "BoxArrays",
    "LaneGraph",
    "Matches",
    "PreparedGraph",
    "Scene",
    "SceneEgo",
    "SceneMemo",
    "SceneObjects",
    "conservative_stop_m",
    "create_scene",
    "match_boxes",
    "prepare",
]
