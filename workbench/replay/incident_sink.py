"""Sends a drive's incidents (``incidents.layout_incidents``) to Rerun; thin, like ``sink``."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np
import rerun as rr

from workbench.replay import style
from workbench.replay.incidents import INCIDENT_LOG, INCIDENT_STATES, layout_incidents
from workbench.replay.sink import time_index

if TYPE_CHECKING:
    from collections.abc import Mapping, Sequence

    from workbench.incidents import Incident
    from workbench.replay.highlight import Highlight

__all__ = ["send_incidents"]


def send_incidents(
    recording: rr.RecordingStream,
    incidents: Sequence[Incident],
    verdicts: Mapping[str, str],
    frame_times: Sequence[tuple[int, int]],
    settings: Mapping[str, Any] | None = None,
    *,
    highlights: Sequence[Highlight] = (),
) -> None:
    """Send the incident lanes, the markers, the objects' highlights and the settings."""
    layout = layout_incidents(incidents, verdicts, frame_times, escape=rr.escape_entity_path_part)
    config = rr.StateConfiguration(
        values=list(INCIDENT_STATES),
        colors=np.array(list(INCIDENT_STATES.values()), dtype=np.uint32),
        visible=[value != "clear" for value in INCIDENT_STATES],
    )
    for lane in layout.lanes:
        recording.log(lane.path, config, static=True)
        recording.send_columns(
            lane.path,
            indexes=time_index(lane.frames, lane.t_ns),
            columns=rr.StateChange.columns(state=np.array(lane.states, dtype=str)),
        )
    if layout.marker_texts:
        recording.send_columns(
            INCIDENT_LOG,
            indexes=time_index(layout.marker_frames, layout.marker_t_ns),
            columns=rr.TextLog.columns(
                text=np.array(layout.marker_texts, dtype=str),
                level=np.array(layout.marker_levels, dtype=str),
            ),
        )
    for light in highlights:
        recording.send_columns(
            light.path,
            indexes=time_index(light.frames, light.t_ns),
            columns=rr.Boxes3D.columns(
                centers=light.centre_m,
                half_sizes=light.half_size_m,
                quaternions=light.quaternion_xyzw,
                labels=light.labels,
                colors=np.full(len(light.labels), style.INCIDENT_OBJECT_COLOR, dtype=np.uint32),
            ).partition(light.counts),
        )
    values: dict[str, Any] = {
        "count": len(incidents),
        "reviewed": sum(i.id in verdicts for i in incidents),
        **{k: str(v) for k, v in (settings or {}).items()},
    }
    recording.send_property("incidents", rr.AnyValues(**values))
