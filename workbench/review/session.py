"""A review session: walk a drive's events (or incidents) worst first and record verdicts (no UI).

By default the session walks *events* (:mod:`workbench.incidents.events`: the overlapping
incidents of every engine on one object): each row is an event, shown by its most severe
incident (``current``), and a verdict, tag or note on it is written to each of its incidents
(the label store stays keyed by incident id). ``by_event=False`` walks the incidents one by
one. The terminal UI (:mod:`workbench.review.app`) is a thin shell over this. Every verdict, tag
and note is written to the label store at once (one transaction each), so a session killed
at any moment loses nothing it showed as saved; undo takes back this session's writes, last
first; a new session resumes at the worst incident nobody has labelled yet.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

from workbench.annotations.attach import label_of, labels_for
from workbench.incidents.events import group_events
from workbench.replay.incidents import short_labels

if TYPE_CHECKING:
    from collections.abc import Iterable, Sequence

    from workbench.annotations import Label, LabelStore
    from workbench.incidents import Incident, IncidentReport
    from workbench.replay.short_labels import ShortLabels

__all__ = ["Pending", "ReviewSession", "resume_row"]


def resume_row(done: Iterable[bool]) -> int:
    """Where a queue resumes: its first row not fully labelled; the last row if all are.

    Args:
        done: Per row, worst first, whether it is fully labelled.

    Returns:
        The row's index (0 for an empty queue).
    """
    last = 0
    for k, labelled in enumerate(done):
        if not labelled:
            return k
        last = k
    return last


@dataclass(slots=True)
class Pending:
    """Tags and a note typed for an incident before it has a verdict."""

    tags: tuple[str, ...] = ()
    note: str = ""


class ReviewSession:
    """The events (or incidents) of one drive, worst first, their labels, a cursor and an undo.

    Attributes:
        incidents: One row per event (its most severe incident), or per incident.
        event_ids: The event id of each row's incident (``by_event``), else empty.
    """

    def __init__(
        self,
        report: IncidentReport,
        store: LabelStore,
        reviewer: str,
        *,
        by_event: bool = True,
        labels: ShortLabels | None = None,
    ) -> None:
        """Load the drive's labels and put the cursor on the first row not fully labelled.

        ``labels``: the drive's short-label table when a replay numbered the objects already
        (its viewer labels them so); by default the incidents' objects by first incident.
        """
        self.report = report
        self.store = store
        self.reviewer = reviewer
        self.by_event = by_event
        self._members: dict[str, tuple[Incident, ...]] = {}
        self.event_ids: dict[str, str] = {}
        if by_event:
            events = group_events(report.incidents)
            self.incidents: Sequence[Incident] = [e.lead for e in events]
            self._members = {e.lead.id: e.incidents for e in events}
            self.event_ids = {e.lead.id: e.id for e in events}
        else:
            self.incidents = report.incidents
        #: Short label per object (``#1``), the drive's one table: the TUI's object column
        #: and every label the viewer draws (scene highlights and engines) use it.
        self.short_labels = labels if labels is not None else short_labels(report.incidents)
        self.labels: dict[str, Label] = labels_for(report, store.labels(report.drive_hash))
        self._pending: dict[str, Pending] = {}
        self._undo: list[list[tuple[int, str]]] = []
        self.index = self.resume_index()

    @property
    def unit(self) -> str:
        """What a row is: ``event`` or ``incident``."""
        return "event" if self.by_event else "incident"

    def members(self, incident: Incident) -> tuple[Incident, ...]:
        """The incidents a verdict on this row labels (its event's; itself by incident)."""
        return self._members.get(incident.id, (incident,))

    def evidence(self, incident: Incident) -> list[str]:
        """One line per other incident of the row's event (its engine's evidence)."""
        event = self.event_ids.get(incident.id)
        others = [m for m in self.members(incident) if m.id != incident.id]
        if event is None:
            return []
        lines = [f"event {event}: {len(others) + 1} incident(s)"]
        for other in others:
            margin = other.severity.record()["worst_margin"]
            lines.append(
                f"  also {other.id}: {other.engine} {other.cause}, frames "
                f"{other.start_frame}-{other.end_frame}, margin {margin}"
            )
        return lines

    def done(self, incident: Incident) -> bool:
        """Whether every incident of the row has a label."""
        return all(m.id in self.labels for m in self.members(incident))

    def session_of(self, incident: Incident) -> ReviewSession:  # noqa: ARG002 - one drive
        """The drive's session a row belongs to (this one: a fleet's is per drive)."""
        return self

    @property
    def writes(self) -> int:
        """Writes this session can still take back (its undo depth)."""
        return len(self._undo)

    def resume_index(self) -> int:
        """The first row (worst first) not fully labelled; the last one if all are."""
        return resume_row(self.done(incident) for incident in self.incidents)

    @property
    def current(self) -> Incident | None:
        """The incident under the cursor (``None``: the drive has none)."""
        return self.incidents[self.index] if self.incidents else None

    @property
    def reviewed(self) -> int:
        """Rows (events or incidents) of this drive whose incidents all have a label."""
        return sum(self.done(i) for i in self.incidents)

    def move(self, step: int) -> Incident | None:
        """Move the cursor by ``step`` (clamped); returns the new current incident."""
        if self.incidents:
            self.index = min(max(self.index + step, 0), len(self.incidents) - 1)
        return self.current

    def go(self, index: int) -> Incident | None:
        """Put the cursor on incident ``index`` (clamped)."""
        return self.move(index - self.index)

    def tags_and_note(self, incident: Incident) -> tuple[tuple[str, ...], str]:
        """What the incident has (its label's, or what was typed before a verdict)."""
        label = self.labels.get(incident.id)
        if label is not None:
            return label.tags, label.note
        pending = self._pending.get(incident.id, Pending())
        return pending.tags, pending.note

    def _write(self, incident: Incident, verdict: str, tags: Sequence[str], note: str) -> Label:
        """Label the row's incident and every other incident of its event (one undo step)."""
        step = []
        for member in self.members(incident):
            written = self.store.put(
                self.report.drive_hash,
                member.id,
                verdict,
                tags=tags,
                note=note,
                reviewer=self.reviewer,
                settings=self.report.settings,
                log_name=self.report.log.name,
            )
            step.append((written, member.id))
            label = self.store.label(self.report.drive_hash, member.id)
            assert label is not None
            self.labels[member.id] = label
        self._undo.append(step)
        self._pending.pop(incident.id, None)
        return self.labels[incident.id]

    def give(self, verdict: str) -> Label | None:
        """Record ``verdict`` on the current incident (keeping its tags and note)."""
        incident = self.current
        if incident is None:
            return None
        tags, note = self.tags_and_note(incident)
        return self._write(incident, verdict, tags, note)

    def add_tag(self, tag: str) -> None:
        """Add a tag to the current incident (saved at once if it has a verdict)."""
        incident = self.current
        if incident is None or not tag.strip():
            return
        tags, note = self.tags_and_note(incident)
        tags = tuple(sorted({*tags, tag.strip()}))
        self._change(incident, tags, note)

    def set_note(self, note: str) -> None:
        """Replace the current incident's note (saved at once if it has a verdict)."""
        incident = self.current
        if incident is None:
            return
        tags, _ = self.tags_and_note(incident)
        self._change(incident, tags, note.strip())

    def _change(self, incident: Incident, tags: tuple[str, ...], note: str) -> None:
        label = self.labels.get(incident.id)
        if label is None:
            self._pending[incident.id] = Pending(tags, note)
        else:
            self._write(incident, label.verdict, tags, note)

    def undo(self) -> Incident | None:
        """Take back this session's last write (all its incidents); the cursor goes to its row."""
        if not self._undo:
            return None
        step = self._undo.pop()
        for written, incident_id in reversed(step):
            self._take_back(written, incident_id)
        first = step[0][1]
        self.index = next(
            k for k, i in enumerate(self.incidents) if any(m.id == first for m in self.members(i))
        )
        return self.current

    def _take_back(self, written: int, incident_id: str) -> None:
        after = self.store.undo(written)
        if after is not None:
            self.labels[incident_id] = after
            return
        incident = next(m for i in self.incidents for m in self.members(i) if m.id == incident_id)
        before = label_of(incident, self.store.labels(self.report.drive_hash))
        if before is None:  # its label from before, if any (also one of a legacy id)
            self.labels.pop(incident_id, None)
        else:
            self.labels[incident_id] = before
