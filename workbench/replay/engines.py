"""Runs the engines on each replayed chunk and sends their results beside the scene.

Only the light part of each verdict (no geometry) is kept for violation detection, so
memory stays flat however long the drive is.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from workbench.evaluate.pipeline import FrameResult, evaluate_frames
from workbench.replay.reach_layout import layout_reach
from workbench.replay.reach_sink import ReachSink
from workbench.replay.rss_layout import layout_rss
from workbench.replay.rss_sink import RssSink
from workbench.replay.unstructured_layout import layout_unstructured
from workbench.replay.unstructured_sink import UnstructuredSink

if TYPE_CHECKING:
    from collections.abc import Sequence

    import rerun as rr

    from loaders.records import Frame
    from workbench.evaluate.pipeline import EngineRunner
    from workbench.replay.layout import ChunkLayout

__all__ = ["EngineResultSink"]


class EngineResultSink:
    """Evaluates chunks with the engines and logs what each engine has a view for."""

    def __init__(self, recording: rr.RecordingStream, engines: Sequence[EngineRunner]) -> None:
        """Set up per-engine sinks for the engines that will run."""
        self._engines = list(engines)
        names = {e.name for e in self._engines}
        self._reach = ReachSink(recording) if "reachsets" in names else None
        self._unstructured = UnstructuredSink(recording) if "unstructured" in names else None
        self._rss = RssSink(recording) if "rss" in names else None
        self.results: list[FrameResult] = []
        self.unsafe_frames: dict[str, int] = dict.fromkeys(sorted(names), 0)

    def send_chunk(self, frames: Sequence[Frame], layout: ChunkLayout) -> None:
        """Evaluate one chunk of frames and send the results."""
        if not self._engines:
            return
        results = [res for _, res in evaluate_frames(frames, self._engines)]
        for res in results:
            self.results.append(res.without_detail())
            for name, out in res.outputs.items():
                self.unsafe_frames[name] += not out.is_safe
        if self._reach is not None:
            details = [res.outputs["reachsets"].detail for res in results]
            self._reach.send_chunk(layout.frame, layout.t_ns, layout_reach(frames, details))
        if self._rss is not None:
            outputs = [res.outputs["rss"] for res in results]
            self._rss.send_chunk(layout.frame, layout.t_ns, layout_rss(frames, outputs))
        if self._unstructured is not None:
            found = [res.outputs["unstructured"].detail for res in results]
            self._unstructured.send_chunk(layout.frame, layout.t_ns, layout_unstructured(found))
