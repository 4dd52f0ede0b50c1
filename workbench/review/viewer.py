"""Moves a live Rerun viewer to the incident under review.

The review recording was sent by the replay (scene, engine lanes, incident lanes). A second
stream with the same application and recording id, connected to the same viewer, sends per
incident a blueprint whose time panel selects and loops over the incident's frames
(:func:`workbench.replay.blueprint.replay_blueprint`), and re-colours an incident's lane
when its verdict changes.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Protocol

import numpy as np
import rerun as rr

from workbench.replay.blueprint import replay_blueprint
from workbench.replay.incidents import LANES_ORIGIN, UNREVIEWED
from workbench.replay.sink import time_index

if TYPE_CHECKING:
    from collections.abc import Mapping, Sequence

    from workbench.incidents import Incident

__all__ = ["NoViewer", "RerunLink", "ViewerLink"]


class ViewerLink(Protocol):
    """What the review loop asks of a viewer."""

    def show(self, incident: Incident) -> None:
        """Select the incident's window in the viewer."""
        ...

    def mark(self, incident: Incident, verdict: str | None) -> None:
        """Show the incident's new review state."""
        ...


class NoViewer:
    """Review without a viewer."""

    def show(self, incident: Incident) -> None:
        """Nothing to move."""

    def mark(self, incident: Incident, verdict: str | None) -> None:
        """Nothing to show."""


class RerunLink:
    """A stream into the review recording of a running viewer."""

    def __init__(
        self,
        url: str,
        *,
        application_id: str,
        recording_id: str,
        ego_start_m: tuple[float, float] | None,
        engines: Sequence[str],
        ego_at_m: Mapping[int, tuple[float, float]] | None = None,
        objects_at_m: Mapping[int, Mapping[str, tuple[float, float]]] | None = None,
    ) -> None:
        """Connect to the viewer's gRPC proxy ``url`` (``rerun+http://HOST:PORT/proxy``).

        ``ego_at_m``: the ego's position per incident start frame; the camera starts behind
        it (else at ``ego_start_m``, the drive's first position). ``objects_at_m``: the
        culprits' positions per incident start frame; the camera frames the incident's objects
        with the ego.
        """
        self.recording = rr.RecordingStream(application_id, recording_id=recording_id)
        self.recording.connect_grpc(url)
        self._ego_start = ego_start_m
        self._ego_at = dict(ego_at_m or {})
        self._objects_at = dict(objects_at_m or {})
        self._engines = tuple(engines)

    def show(self, incident: Incident) -> None:
        """Send a blueprint selecting the incident's frames."""
        selection = (incident.start_frame, incident.end_frame)
        ego = self._ego_at.get(incident.start_frame, self._ego_start)
        at_start = self._objects_at.get(incident.start_frame, {})
        focus = [at_start[o] for o in incident.objects if o in at_start]
        blueprint = replay_blueprint(ego, self._engines, selection=selection, focus_m=focus)
        self.recording.send_blueprint(blueprint, make_active=True)

    def mark(self, incident: Incident, verdict: str | None) -> None:
        """Re-send the first state of the incident's lane."""
        path = f"{LANES_ORIGIN}/{incident.engine}/{rr.escape_entity_path_part(incident.id)}"
        self.recording.send_columns(
            path,
            indexes=time_index(
                np.array([incident.start_frame], dtype=np.int64),
                np.array([incident.start_ns], dtype=np.int64),
            ),
            columns=rr.StateChange.columns(state=np.array([verdict or UNREVIEWED], dtype=str)),
        )

    def close(self) -> None:
        """Flush and disconnect."""
        self.recording.flush()
        self.recording.disconnect()
