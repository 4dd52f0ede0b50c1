"""The clips' ``.rrd`` recordings, cut from one pass over the drive.

Engines carry memory from frame to frame (RSS: each pair's last safe state, held for as long
as the danger lasts; the unstructured and reach-set engines: their own), and the loaders do
not number a window's frames alike (a message log counts from 0 within the window, CommonRoad
keeps the drive's numbers). A clip replayed from a cold engine state, or from a lead-in of a
fixed length, can therefore find its incident at another frame or with another cause, and
so under another id. Here the drive is evaluated once, from its first frame to the end of
the last clip, exactly as the incidents were found: each chunk's frames inside a clip's
window go to that clip's recording (:class:`ClipRecording`), so every clip's engines are
warm from the drive's start and its frames are numbered as in the drive. The clip's own
incident is matched to the drive's by engine, objects and overlapping frames
(:func:`clip_incident`), never by id alone.
"""

from __future__ import annotations

import contextlib
from typing import TYPE_CHECKING

from workbench.outputs import part_path
from workbench.replay.blueprint import replay_blueprint
from workbench.replay.incidents import short_labels
from workbench.viewer.drive_pass import FeedSettings, RecordingFeed, recording_id
from workbench.viewer.outputs import Destination

if TYPE_CHECKING:
    from collections.abc import Sequence
    from pathlib import Path

    from loaders.drive import Drive
    from workbench.driver.run import Chunk
    from workbench.engines.base import EngineSpec
    from workbench.export.plan import ClipPlan
    from workbench.incidents import Incident, IncidentReport, IncidentSettings

__all__ = ["ClipRecording", "clip_incident", "incident_focus_m", "within"]


def incident_focus_m(
    report: IncidentReport, plan: ClipPlan
) -> tuple[tuple[float, float], list[tuple[float, float]]] | None:
    """Ego and incident objects' positions ``(x, y)`` [m] at the incident's first frame.

    ``None`` for a window without incident, or when the detector recorded no position.
    """
    incident = plan.incident
    if incident is None or incident.start_frame not in report.ego_at_start_m:
        return None
    objects = report.objects_at_start_m.get(incident.start_frame, {})
    ego = report.ego_at_start_m[incident.start_frame]
    return ego, [xy for oid, xy in sorted(objects.items()) if oid in incident.objects]


def within(chunk: Chunk, start_ns: int, end_ns: int) -> Chunk | None:
    """The chunk's frames in ``[start_ns, end_ns)`` with their verdicts (``None``: none)."""
    keep = [k for k, f in enumerate(chunk.frames) if start_ns <= f.t_ns < end_ns]
    if not keep:
        return None
    if len(keep) == len(chunk.frames):
        return chunk
    return chunk.part(keep[0], keep[-1] + 1)


def clip_incident(found: Sequence[Incident], incident: Incident) -> Incident | None:
    """The clip's incident that is the drive's ``incident``, if any.

    Same engine, same objects and overlapping frames; of several, the most overlapping one
    (ties: the nearest start).
    """

    def overlap(other: Incident) -> int:
        return min(other.end_frame, incident.end_frame) - max(
            other.start_frame, incident.start_frame
        )

    same = [
        other
        for other in found
        if other.engine == incident.engine
        and set(other.objects) == set(incident.objects)
        and overlap(other) >= 0
    ]
    if not same:
        return None
    return max(same, key=lambda o: (overlap(o), -abs(o.start_frame - incident.start_frame)))


class ClipRecording:
    """One clip's ``.rrd``, written as ``<name>.part`` while the pass crosses its window.

    Attributes:
        plan: The clip.
        path: Where the recording ends up.
        feed: The clip's consumers (scene, engines, its incidents and culprits' boxes).
    """

    def __init__(
        self,
        plan: ClipPlan,
        path: Path,
        drive: Drive,
        *,
        report: IncidentReport,
        engines: Sequence[EngineSpec],
        incident_settings: IncidentSettings,
    ) -> None:
        """Set up the clip's recording; its file is opened at the first frame of its window."""
        self.plan = plan
        self.path = path
        self._part = part_path(path)
        self._report = report
        self._end_ns = plan.end_ns + 1
        self.feed = RecordingFeed(
            drive,
            engines,
            recording_id(drive, plan.start_ns, self._end_ns),
            drive_hash=report.drive_hash,
            settings=FeedSettings(incident_settings, labels=short_labels(report.incidents)),
        )
        self._file = contextlib.ExitStack()
        self._opened = False

    def add_chunk(self, chunk: Chunk) -> None:
        """Send the chunk's frames inside the clip's window (opening its file at the first)."""
        part = within(chunk, self.plan.start_ns, self._end_ns)
        if part is None:
            return
        if not self._opened:
            self._open(part)
        self.feed.add_chunk(part)

    def _open(self, first: Chunk) -> None:
        plan, ego = self.plan, first.frames[0].ego
        selection = plan.frames or (0, 0)
        if plan.incident is not None:
            selection = (plan.incident.start_frame, plan.incident.end_frame)
        ego_at, objects_at = incident_focus_m(self._report, plan) or ((ego.x_m, ego.y_m), ())
        blueprint = replay_blueprint(
            ego_at, engines=self.feed.engine_names, selection=selection, focus_m=objects_at
        )
        destination = Destination(out=self._part)
        self._file.enter_context(destination.attach(self.feed.recording, blueprint))
        self._opened = True

    def finish(self) -> bool:
        """Send the clip's incidents, close and rename its file; ``False``: no frame in it.

        The drive's label of the clip's incident colours the clip's incident that matches it
        (:func:`clip_incident`).
        """
        if not self._opened:
            return False
        feed, plan = self.feed, self.plan
        feed.sink.close()
        found = feed.found()
        verdicts = {}
        if plan.incident is not None and plan.label is not None:
            same = clip_incident(found, plan.incident)
            if same is not None:
                verdicts[same.id] = plan.label.verdict
        feed.send_incidents(found, verdicts)
        feed.recording.disconnect()
        self._file.close()
        self._part.replace(self.path)
        return True

    def abandon(self) -> None:
        """Close the file of a failed export and remove it."""
        with contextlib.suppress(Exception):
            self._file.close()
        self._part.unlink(missing_ok=True)
