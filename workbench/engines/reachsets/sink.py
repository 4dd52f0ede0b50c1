"""Sends reach-set results (``reach_layout``) to Rerun; thin, like ``sink``.

Entity paths::

    world/reach/sets          LineStrips3D, every object's set at every step, time-coloured
    world/reach/occupancy     LineStrips3D, ego footprints along the plan, time-coloured
    world/reach/patches       LineStrips3D, regions deleted by rule patches (cyan)
    world/reach/collisions    Points3D on objects whose set hits the ego, labelled with the
                              object's short label @ t (``#1 @ 2.8 s``); the full id per
                              point in its ``object_id`` component
    reach/state               StateChange safe / unsafe (state lane)
    plots/reach/first_collision_s   Scalars, earliest collision offset (unsafe frames)

DESIGN.md sketches one entity per object and step (``reach/<object>/step_<k>``); we send one
batched entity per kind instead (one columnar call per chunk, colour = step) because
thousands of small entities make the viewer slow (Rerun issue #7115).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
import rerun as rr

from workbench.engines.reachsets.layout import layout_reach
from workbench.replay.short_labels import ShortLabels
from workbench.replay.sink import object_id_columns, send_strips, state_configuration, time_index

if TYPE_CHECKING:
    from collections.abc import Sequence

    from numpy.typing import NDArray

    from loaders.records import Frame
    from workbench.engines.reachsets.layout import ReachColumns
    from workbench.engines.reachsets.verdict import ReachVerdict
    from workbench.replay.layout import ChunkLayout

__all__ = ["STATE_COLORS", "ReachSink"]

#: Line radius of the reach-set, occupancy and patch outlines.
STRIP_RADIUS_M = 0.08
#: State-lane colours of the verdict.
STATE_COLORS = {"safe": 0x4CAF50FF, "unsafe": 0xEF5350FF}


class ReachSink:
    """Sends reach-set columns on the ``frame`` and ``log_time`` timelines."""

    def __init__(self, recording: rr.RecordingStream, labels: ShortLabels | None = None) -> None:
        """Remember the stream and send the static state configuration.

        ``labels``: the drive's short labels the hit labels use; a fresh table by default.
        """
        self.recording = recording
        self.labels = labels if labels is not None else ShortLabels()
        recording.log("reach/state", state_configuration(STATE_COLORS), static=True)

    def send_columns(
        self, frame: NDArray[np.int64], t_ns: NDArray[np.int64], cols: ReachColumns
    ) -> None:
        """Send one chunk of reach-set results."""
        rec = self.recording
        index = time_index(frame, t_ns)
        send_strips(rec, "world/reach/sets", index, cols.sets, STRIP_RADIUS_M)
        send_strips(rec, "world/reach/occupancy", index, cols.occupancy, STRIP_RADIUS_M)
        send_strips(rec, "world/reach/patches", index, cols.patches, STRIP_RADIUS_M)
        rec.send_columns(
            "world/reach/collisions",
            indexes=index,
            columns=[
                *rr.Points3D.columns(
                    positions=cols.hit_points_m,
                    labels=cols.hit_labels,
                    colors=np.full(len(cols.hit_labels), STATE_COLORS["unsafe"], dtype=np.uint32),
                    radii=np.full(len(cols.hit_labels), 0.8, dtype=np.float32),
                ).partition(cols.hit_counts),
                *object_id_columns(cols.hit_object_ids, cols.hit_counts),
            ],
        )
        states = np.where(cols.is_safe, "safe", "unsafe")
        rec.send_columns("reach/state", indexes=index, columns=rr.StateChange.columns(state=states))
        unsafe = np.isfinite(cols.first_collision_s)
        if unsafe.any():
            rec.send_columns(
                "plots/reach/first_collision_s",
                indexes=time_index(frame[unsafe], t_ns[unsafe]),
                columns=rr.Scalars.columns(scalars=cols.first_collision_s[unsafe]),
            )

    def send_chunk(
        self, frames: Sequence[Frame], layout: ChunkLayout, verdicts: Sequence[ReachVerdict]
    ) -> None:
        """Lay out and send the verdicts of a chunk of frames."""
        results = [v.result for v in verdicts]
        self.send_columns(layout.frame, layout.t_ns, layout_reach(frames, results, self.labels))
