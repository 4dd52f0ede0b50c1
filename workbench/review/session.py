"""A review session: walk a drive's incidents worst first and record verdicts (no UI).

The terminal UI (:mod:`workbench.review.app`) is a thin shell over this. Every verdict, tag
and note is written to the label store at once (one transaction each), so a session killed
at any moment loses nothing it showed as saved; undo takes back this session's writes, last
first; a new session resumes at the worst incident nobody has labelled yet.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

from workbench.annotations.attach import label_of, labels_for

if TYPE_CHECKING:
    from collections.abc import Sequence

    from workbench.annotations import Label, LabelStore
    from workbench.incidents import Incident, IncidentReport

__all__ = ["Pending", "ReviewSession"]


@dataclass(slots=True)
class Pending:
    """Tags and a note typed for an incident before it has a verdict."""

    tags: tuple[str, ...] = ()
    note: str = ""


class ReviewSession:
    """The incidents of one drive (worst first), their labels, a cursor and an undo stack."""

    def __init__(self, report: IncidentReport, store: LabelStore, reviewer: str) -> None:
        """Load the drive's labels and put the cursor on the first unlabelled incident."""
        self.report = report
        self.store = store
        self.reviewer = reviewer
        self.incidents: Sequence[Incident] = report.incidents
        self.labels: dict[str, Label] = labels_for(report, store.labels(report.drive_hash))
        self._pending: dict[str, Pending] = {}
        self._undo: list[tuple[int, str]] = []
        self.index = self.resume_index()

    def resume_index(self) -> int:
        """The first incident (worst first) without a label; the last one if all have one."""
        for k, incident in enumerate(self.incidents):
            if incident.id not in self.labels:
                return k
        return max(len(self.incidents) - 1, 0)

    @property
    def current(self) -> Incident | None:
        """The incident under the cursor (``None``: the drive has none)."""
        return self.incidents[self.index] if self.incidents else None

    @property
    def reviewed(self) -> int:
        """Incidents of this drive with a label."""
        return sum(i.id in self.labels for i in self.incidents)

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
        event = self.store.put(
            self.report.drive_hash,
            incident.id,
            verdict,
            tags=tags,
            note=note,
            reviewer=self.reviewer,
            settings=self.report.settings,
            log_name=self.report.log.name,
        )
        self._undo.append((event, incident.id))
        label = self.store.label(self.report.drive_hash, incident.id)
        assert label is not None
        self.labels[incident.id] = label
        self._pending.pop(incident.id, None)
        return label

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
        """Take back this session's last write; the cursor goes to its incident."""
        if not self._undo:
            return None
        event, incident_id = self._undo.pop()
        after = self.store.undo(event)
        self.index = next(k for k, i in enumerate(self.incidents) if i.id == incident_id)
        if after is None:  # its label from before, if any (also one of a legacy id)
            before = label_of(self.incidents[self.index], self.store.labels(self.report.drive_hash))
            if before is None:
                self.labels.pop(incident_id, None)
            else:
                self.labels[incident_id] = before
        else:
            self.labels[incident_id] = after
        return self.current
