"""The one drive runner: chunks of frames with every engine's typed verdicts (see ``run``)."""

from workbench.driver.gc_policy import ENGINE_GC_THRESHOLD, engine_gc
from workbench.driver.run import CHUNK_FRAMES, Chunk, DriveRun, EgoSize, evaluate_chunk

__all__ = [
    "CHUNK_FRAMES",
    "ENGINE_GC_THRESHOLD",
    "Chunk",
    "DriveRun",
    "EgoSize",
    "engine_gc",
    "evaluate_chunk",
]
