"""The Rerun scene of a drive: pure layout of frames into columns, a thin sink, a blueprint."""

from workbench.replay.blueprint import replay_blueprint
from workbench.replay.layout import ChunkLayout, MapLayout, layout_chunk, layout_map
from workbench.replay.sink import RerunSink

__all__ = [
    "ChunkLayout",
    "MapLayout",
    "RerunSink",
    "layout_chunk",
    "layout_map",
    "replay_blueprint",
]
