"""The Rerun sink of a drive run: scene columns plus every engine's view, in columnar batches.

Driver chunks are buffered and sent :data:`SEND_FRAMES` frames at a time (one columnar
``send_columns`` call per entity and batch): the static data (name, drive properties, map)
goes first, then per batch the scene (:mod:`workbench.replay.layout` / ``sink``) and each
engine's own sink (``EngineSpec.sink``). Only this batch of frames and verdicts is held.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from loaders.timebase import ns_to_s
from workbench.replay.layout import layout_chunk, layout_map
from workbench.replay.properties import drive_properties, recording_name, software_properties
from workbench.replay.short_labels import ShortLabels
from workbench.replay.sink import RerunSink

if TYPE_CHECKING:
    from collections.abc import Sequence

    import rerun as rr

    from loaders.drive import Drive
    from loaders.records import Frame
    from workbench.driver.run import Chunk
    from workbench.engines.base import EngineSink, EngineSpec, Verdict

__all__ = ["SEND_FRAMES", "RerunDriveSink"]

#: Frames per columnar batch sent to Rerun.
SEND_FRAMES = 500


class RerunDriveSink:
    """Sends a drive's scene and engine verdicts to one recording stream."""

    def __init__(
        self,
        recording: rr.RecordingStream,
        drive: Drive,
        engines: Sequence[EngineSpec],
        *,
        send_frames: int = SEND_FRAMES,
        labels: ShortLabels | None = None,
    ) -> None:
        """Set up; nothing is sent before the first batch (or :meth:`close`).

        Args:
            recording: The stream everything goes to.
            drive: The drive (its info and lane map are sent first).
            engines: The engines whose verdicts come with each chunk.
            send_frames: Frames per columnar batch.
            labels: The drive's short-label table every engine's labels use (the review
                numbers its incidents' objects first); a fresh one by default.
        """
        self.recording = recording
        self._send_frames = send_frames
        self._drive = drive
        self._specs = tuple(engines)
        self._names = tuple(spec.name for spec in self._specs)
        #: The drive's short labels: culprits numbered as they first turn up, then the other
        #: actors as they appear (scene, highlights and every engine use this one table).
        self.labels = labels if labels is not None else ShortLabels()
        self._scene = RerunSink(recording, self.labels)
        self._engines: dict[str, EngineSink] | None = None
        self._frames: list[Frame] = []
        self._verdicts: dict[str, list[Verdict]] = {n: [] for n in self._names}
        #: Frames sent so far.
        self.frames = 0
        #: Distinct actor ids over the frames sent.
        self.actor_ids: set[str] = set()
        self._t_first_ns: int | None = None
        self._t_last_ns = 0

    @property
    def duration_s(self) -> float:
        """Drive time covered by the frames sent."""
        first = self._t_first_ns if self._t_first_ns is not None else self._t_last_ns
        return ns_to_s(self._t_last_ns - first)

    def add_chunk(self, chunk: Chunk) -> None:
        """Buffer a driver chunk; send every full batch."""
        self._frames.extend(chunk.frames)
        for name in self._names:
            self._verdicts[name].extend(chunk.verdicts[name])
        while len(self._frames) >= self._send_frames:
            self._send(self._send_frames)

    def close(self) -> None:
        """Send what is buffered and flush the stream."""
        if self._frames or self._engines is None:
            self._send(len(self._frames))
        self._scene.flush()

    def _static(self, start_ns: int) -> dict[str, EngineSink]:
        info = self._drive.info
        lane_map = self._drive.lane_map
        self._scene.send_static(
            name=recording_name(info),
            start_ns=start_ns,
            properties={**drive_properties(info), **software_properties(self._names)},
            map_layout=layout_map(lane_map) if lane_map is not None else None,
        )
        return {spec.name: spec.sink(self.recording, self.labels) for spec in self._specs}

    def _number_culprits(self, n: int, verdicts: dict[str, list[Verdict]]) -> None:
        """Number each unsafe frame's culprits (frame order, ties by id) before any bystander.

        Without a review's table the objects are then numbered about as their incidents start.
        """
        for k in range(n):
            unsafe = (verdicts[name][k] for name in self._names)
            culprits = {c for verdict in unsafe if not verdict.is_safe for c in verdict.culprits}
            for culprit in sorted(culprits):
                self.labels.label(culprit)

    def _send(self, n: int) -> None:
        frames, self._frames = self._frames[:n], self._frames[n:]
        verdicts = {}
        for name in self._names:
            verdicts[name], self._verdicts[name] = (
                self._verdicts[name][:n],
                self._verdicts[name][n:],
            )
        if not frames:
            self._engines = self._static(self._drive.info.start_ns)
            return
        layout = layout_chunk(frames)
        if self._engines is None:
            self._engines = self._static(int(layout.t_ns[0]))
            self._t_first_ns = int(layout.t_ns[0])
        self._number_culprits(len(frames), verdicts)
        self._scene.send_chunk(layout)
        for name, sink in self._engines.items():
            sink.send_chunk(frames, layout, verdicts[name])
        self._t_last_ns = int(layout.t_ns[-1])
        self.frames += len(layout)
        self.actor_ids.update(layout.actors.ids_seen)
