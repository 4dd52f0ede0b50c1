"""RSS scene creation from a lane graph (ad-rss ``RssWorldModelCreation``), pure numpy/shapely.

``LaneGraph`` (plain arrays, built by the workbench from a lane map) -> ``prepare`` once per
map -> ``create_scene`` per frame -> ``rss.model`` constellations for ``rss.engine``.
See ``docs/rss_scene.md``. The per-object modules run compiled (mypyc) when a fresh build
exists (``rss.compiled``; results identical).
"""

from __future__ import annotations

from rss.compiled import activate

activate(__name__, __path__)  # before any submodule import

from rss.scene.create import create_scene  # noqa: E402
from rss.scene.inputs import Scene, SceneEgo, SceneObjects, conservative_stop_m  # noqa: E402
from rss.scene.lanegraph import LaneGraph, PreparedGraph, prepare  # noqa: E402
from rss.scene.matching import BoxArrays, Matches, match_boxes  # noqa: E402

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
