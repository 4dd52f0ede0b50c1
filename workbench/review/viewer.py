"""Moves a live Rerun viewer to the incident under review.

The review recording was sent by the replay (scene, engine lanes, incident lanes). A second
stream with the same application and recording id, connected to the same viewer, sends per
incident a blueprint whose time panel selects the incident's frames
(:func:`workbench.replay.blueprint.replay_blueprint`: its objects labelled, the others dimmed),
then moves the time cursor, paused, to the incident's worst frame (:class:`TimeCursor`: a
native viewer's ``ViewerControl``, or :mod:`workbench.viewer.web_cursor` for the web viewer),
and re-colours an incident's lane when its verdict changes.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Protocol

import numpy as np
import rerun as rr

from workbench.replay.blueprint import replay_blueprint
from workbench.replay.highlight import worst_frame
from workbench.replay.incidents import LANES_ORIGIN, UNREVIEWED
from workbench.replay.sink import FRAME_TIMELINE, time_index

if TYPE_CHECKING:
    from collections.abc import Mapping, Sequence

    from rerun.experimental import ViewerClient

    from workbench.incidents import Incident
    from workbench.replay.highlight import CulpritBoxes

__all__ = ["NoViewer", "RerunLink", "TimeCursor", "ViewerCursor", "ViewerLink", "worst_frame"]


class TimeCursor(Protocol):
    """Moves a viewer's time cursor."""

    def move(self, timeline: str, sequence: int) -> None:
        """Put the cursor at ``sequence`` on ``timeline``, paused."""
        ...


class ViewerCursor:
    """The time cursor of a native viewer (or a headless one), through its gRPC proxy."""

    def __init__(self, url: str) -> None:
        """Talk to the viewer at ``url`` (``rerun+http://HOST:PORT/proxy``) on first use."""
        self.url = url
        self._client: ViewerClient | None = None
        #: The last error of a move (the viewer was closed, ...); ``None`` after a good one.
        self.error: str | None = None

    def move(self, timeline: str, sequence: int) -> None:
        """Seek, paused; a viewer that is gone is remembered in :attr:`error`, not raised."""
        from rerun.experimental import ViewerClient  # noqa: PLC0415 - only with a viewer

        try:
            if self._client is None:
                self._client = ViewerClient.connect(self.url)
            self._client.set_time(timeline, sequence=sequence, play_state="paused")
        except (ConnectionError, RuntimeError, OSError, ValueError) as err:
            self.error = str(err).splitlines()[0] if str(err) else type(err).__name__
        else:
            self.error = None


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
        cursor: TimeCursor | None = None,
        positions: CulpritBoxes | None = None,
    ) -> None:
        """Connect to the viewer's gRPC proxy ``url`` (``rerun+http://HOST:PORT/proxy``).

        ``ego_at_m``: the ego's position per incident start frame; the camera starts behind
        it (else at ``ego_start_m``, the drive's first position). ``objects_at_m``: the
        culprits' positions per incident start frame; the camera frames the incident's objects
        with the ego. ``cursor``: moves the time cursor (default: the viewer at ``url``).
        ``positions``: the ego's and culprits' positions at unsafe frames (filled by the
        replay); when it has the incident's worst frame, the camera frames that moment.
        """
        self.recording = rr.RecordingStream(application_id, recording_id=recording_id)
        self.recording.connect_grpc(url)
        self._ego_start = ego_start_m
        self._ego_at = dict(ego_at_m or {})
        self._objects_at = dict(objects_at_m or {})
        self._engines = tuple(engines)
        self.cursor: TimeCursor = cursor or ViewerCursor(url)
        self._positions = positions
        self._last: Incident | None = None

    def show(self, incident: Incident) -> None:
        """Select the incident's frames and put the time cursor on its worst frame, paused."""
        selection = (incident.start_frame, incident.end_frame)
        ego = self._ego_at.get(incident.start_frame, self._ego_start)
        at_start = self._objects_at.get(incident.start_frame, {})
        focus = [at_start[o] for o in incident.objects if o in at_start]
        if self._positions is not None:
            ego_worst, focus_worst = self._positions.at(worst_frame(incident), incident.objects)
            if ego_worst is not None:
                ego, focus = ego_worst, focus_worst
        blueprint = replay_blueprint(
            ego, self._engines, selection=selection, focus_m=focus, incident=incident
        )
        self._last = incident
        self.cursor.move(FRAME_TIMELINE, worst_frame(incident))
        self.recording.send_blueprint(blueprint, make_active=True)
        self.recording.flush()

    def show_again(self) -> None:
        """Re-send the blueprint of the incident shown last (a viewer that loaded late)."""
        if self._last is not None:
            self.show(self._last)

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
