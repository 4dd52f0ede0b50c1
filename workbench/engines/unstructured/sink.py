"""Sends unstructured RSS results (``unstructured_layout``) to Rerun; thin, like ``reach_sink``.

Entity paths::

    world/rss/unstructured/ego_sets            Mesh3D, the ego's continue-forward + brake sets
    world/rss/unstructured/ego_sets/outline    LineStrips3D, outline of the ego's brake set
    world/rss/unstructured/agent_sets          Mesh3D, every checked agent's sets
    world/rss/unstructured/agent_sets/outline  LineStrips3D, outlines of their brake sets
    world/rss/unstructured/heading_ranges      LineStrips3D, drive-away heading fan (blue)
    rss/unstructured/state                     StateChange safe / continue-forward /
                                               drive-away / brake (state lane)

Meshes go columnar too: ``Mesh3D.columns`` per component, the vertex columns partitioned by
vertices per frame and the triangle column by triangles per frame (one mesh per frame).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
import rerun as rr

from workbench.engines.unstructured.layout import COLORS, Category, layout_unstructured
from workbench.replay.short_labels import ShortLabels
from workbench.replay.sink import send_strips, state_configuration, time_index

if TYPE_CHECKING:
    from collections.abc import Sequence

    from numpy.typing import NDArray

    from loaders.records import Frame
    from workbench.engines.unstructured.layout import MeshColumns, UnstructuredColumns
    from workbench.engines.unstructured.verdict import UnstructuredVerdict
    from workbench.replay.layout import ChunkLayout

__all__ = ["ROOT", "STATE_PATH", "UnstructuredSink"]

#: Parent of the scene entities.
ROOT = "world/rss/unstructured"
#: The state lane.
STATE_PATH = "rss/unstructured/state"
#: White albedo with the fill alpha: the viewer takes mesh transparency from it.
_ALBEDO = 0xFFFFFF70
_RADII_M = {"outline": 0.06, "heading_ranges": 0.05}


class UnstructuredSink:
    """Sends unstructured columns on the ``frame`` and ``log_time`` timelines."""

    def __init__(self, recording: rr.RecordingStream, labels: ShortLabels | None = None) -> None:
        """Remember the stream and send the static state configuration.

        ``labels``: the drive's short labels, kept for the interface: this engine draws no
        object label (every agent's sets are one mesh and outline batch per frame).
        """
        self.recording = recording
        self.labels = labels if labels is not None else ShortLabels()
        lane = {c.label: COLORS[c] for c in Category}
        recording.log(STATE_PATH, state_configuration(lane), static=True)

    def _mesh(self, path: str, index: list[rr.TimeColumn], cols: MeshColumns) -> None:
        vertices = rr.Mesh3D.columns(vertex_positions=cols.vertices_m, vertex_colors=cols.colors)
        triangles = rr.Mesh3D.columns(triangle_indices=cols.triangles)
        n = len(cols.vertex_counts)
        albedo = rr.Mesh3D.columns(albedo_factor=np.full(n, _ALBEDO, dtype=np.uint32))
        self.recording.send_columns(
            path,
            indexes=index,
            columns=[
                *vertices.partition(cols.vertex_counts),
                *triangles.partition(cols.triangle_counts),
                *albedo,
            ],
        )

    def send_columns(
        self, frame: NDArray[np.int64], t_ns: NDArray[np.int64], cols: UnstructuredColumns
    ) -> None:
        """Send one chunk of unstructured results."""
        index = time_index(frame, t_ns)
        self._mesh(f"{ROOT}/ego_sets", index, cols.ego_sets)
        self._mesh(f"{ROOT}/agent_sets", index, cols.agent_sets)
        outline = _RADII_M["outline"]
        send_strips(self.recording, f"{ROOT}/ego_sets/outline", index, cols.ego_outlines, outline)
        send_strips(
            self.recording, f"{ROOT}/agent_sets/outline", index, cols.agent_outlines, outline
        )
        fan = _RADII_M["heading_ranges"]
        send_strips(self.recording, f"{ROOT}/heading_ranges", index, cols.fan, fan)
        self.recording.send_columns(
            STATE_PATH, indexes=index, columns=rr.StateChange.columns(state=cols.states)
        )

    def send_chunk(
        self,
        frames: Sequence[Frame],
        layout: ChunkLayout,
        verdicts: Sequence[UnstructuredVerdict],
    ) -> None:
        """Lay out and send the verdicts of a chunk of frames."""
        del frames  # the sets carry their own positions
        details = [v.detail for v in verdicts]
        self.send_columns(layout.frame, layout.t_ns, layout_unstructured(details))
