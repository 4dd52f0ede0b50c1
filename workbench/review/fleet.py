"""One review queue across the drives of a batch: every drive's rows, worst first together.

A :class:`FleetSession` holds one :class:`~workbench.review.session.ReviewSession` per drive
(each keeps its drive's labels, events and undo; verdicts go to the same label store keyed by
the drive's content hash) and walks their rows as one list in the severity order
(:func:`workbench.incidents.order.severity_key`), ties broken by drive, start and id. The
terminal UI drives it as it drives a single drive's session. A :class:`FleetViewer` opens a
drive in the viewer when the first of its rows comes up (a pass that only draws: the
incidents are the batch's) and closes the previous one.
"""

from __future__ import annotations

import contextlib
from collections import ChainMap
from typing import TYPE_CHECKING

from workbench.incidents.order import severity_key
from workbench.review.session import resume_row

if TYPE_CHECKING:
    from collections.abc import Callable, Sequence
    from contextlib import AbstractContextManager

    from workbench.annotations import Label
    from workbench.incidents import Incident, IncidentReport
    from workbench.replay.short_labels import ShortLabels
    from workbench.review.session import ReviewSession
    from workbench.review.viewer import ViewerLink

__all__ = ["FleetSession", "FleetViewer"]


class FleetSession:
    """The rows of several drives' sessions as one queue, worst first, with one cursor.

    Attributes:
        sessions: One session per drive (their own cursors are moved to the fleet's row).
        incidents: Every drive's rows (events or incidents), worst first across drives.
        labels: Every drive's labels by incident id (live views of the sessions' own).
        index: The row under the cursor.
    """

    def __init__(self, sessions: Sequence[ReviewSession]) -> None:
        """Merge the sessions' rows; the cursor goes to the worst row nobody labelled yet.

        Raises:
            ValueError: No session.
        """
        if not sessions:
            raise ValueError("a review queue needs at least one drive")
        self.sessions = tuple(sessions)
        rows = [(s, i) for s in self.sessions for i in s.incidents]
        rows.sort(key=lambda r: (*severity_key(r[1])[:-2], str(r[0].report.log), *_tail(r[1])))
        self.incidents: Sequence[Incident] = [i for _, i in rows]
        self._owners = [s for s, _ in rows]
        self.labels: ChainMap[str, Label] = ChainMap(*(s.labels for s in self.sessions))
        self._undo: list[ReviewSession] = []
        self.index = self.resume_index()

    @property
    def reviewer(self) -> str:
        """Who the verdicts are recorded for."""
        return self.sessions[0].reviewer

    @property
    def unit(self) -> str:
        """What a row is: ``event`` or ``incident``."""
        return self.sessions[0].unit

    @property
    def report(self) -> IncidentReport:
        """The report of the drive under the cursor (the first drive's without rows)."""
        return self._owners[self.index].report if self.incidents else self.sessions[0].report

    @property
    def short_labels(self) -> ShortLabels:
        """The short labels of the drive under the cursor (the first drive's without rows)."""
        owner = self._owners[self.index] if self.incidents else self.sessions[0]
        return owner.short_labels

    def session_of(self, incident: Incident) -> ReviewSession:
        """The session of the drive a row comes from.

        Raises:
            KeyError: ``incident`` is no row of this queue.
        """
        for row, owner in zip(self.incidents, self._owners, strict=True):
            if row is incident:
                return owner
        raise KeyError(incident.id)

    def _owner(self) -> ReviewSession | None:
        """The current row's session, its own cursor put on that row."""
        if not self.incidents:
            return None
        owner = self._owners[self.index]
        owner.index = list(owner.incidents).index(self.incidents[self.index])
        return owner

    def done(self, incident: Incident) -> bool:
        """Whether every incident of the row has a label."""
        return self.session_of(incident).done(incident)

    def resume_index(self) -> int:
        """The first row (worst first) not fully labelled; the last one if all are."""
        pairs = zip(self.incidents, self._owners, strict=True)
        return resume_row(owner.done(incident) for incident, owner in pairs)

    @property
    def current(self) -> Incident | None:
        """The row under the cursor (``None``: no drive has one)."""
        return self.incidents[self.index] if self.incidents else None

    @property
    def reviewed(self) -> int:
        """Rows of every drive whose incidents all have a label."""
        return sum(s.reviewed for s in self.sessions)

    def move(self, step: int) -> Incident | None:
        """Move the cursor by ``step`` (clamped); returns the new current row."""
        if self.incidents:
            self.index = min(max(self.index + step, 0), len(self.incidents) - 1)
        return self.current

    def go(self, index: int) -> Incident | None:
        """Put the cursor on row ``index`` (clamped)."""
        return self.move(index - self.index)

    def evidence(self, incident: Incident) -> list[str]:
        """The row's other incidents, as its drive's session lists them."""
        return self.session_of(incident).evidence(incident)

    def tags_and_note(self, incident: Incident) -> tuple[tuple[str, ...], str]:
        """What the row has (its label's, or what was typed before a verdict)."""
        return self.session_of(incident).tags_and_note(incident)

    def _written(self, change: Callable[[ReviewSession], object]) -> None:
        owner = self._owner()
        if owner is None:
            return
        before = owner.writes
        change(owner)
        if owner.writes > before:
            self._undo.append(owner)

    def give(self, verdict: str) -> Label | None:
        """Record ``verdict`` on the current row (in its drive's labels)."""
        self._written(lambda s: s.give(verdict))
        incident = self.current
        return None if incident is None else self.labels.get(incident.id)

    def add_tag(self, tag: str) -> None:
        """Add a tag to the current row (saved at once if it has a verdict)."""
        self._written(lambda s: s.add_tag(tag))

    def set_note(self, note: str) -> None:
        """Replace the current row's note (saved at once if it has a verdict)."""
        self._written(lambda s: s.set_note(note))

    def undo(self) -> Incident | None:
        """Take back the queue's last write; the cursor goes to its row."""
        if not self._undo:
            return None
        owner = self._undo.pop()
        row = owner.undo()
        self.index = next(
            k
            for k, (i, s) in enumerate(zip(self.incidents, self._owners, strict=True))
            if i is row and s is owner
        )
        return self.current


def _tail(incident: Incident) -> tuple[int, str]:
    return incident.start_ns, incident.id


class FleetViewer:
    """A viewer link that opens each drive when the queue's cursor reaches one of its rows.

    ``open_drive`` streams the drive into the viewer and yields its link (closed when the
    cursor moves to another drive, or at :meth:`close`).
    """

    def __init__(
        self,
        fleet: FleetSession,
        open_drive: Callable[[ReviewSession], AbstractContextManager[ViewerLink]],
    ) -> None:
        """Nothing is opened before the first row is shown."""
        self._fleet = fleet
        self._open_drive = open_drive
        self._stack = contextlib.ExitStack()
        self._drive: ReviewSession | None = None
        self._link: ViewerLink | None = None

    def show(self, incident: Incident) -> None:
        """Open the row's drive if another one is open, then move the viewer to the row."""
        owner = self._fleet.session_of(incident)
        if owner is not self._drive or self._link is None:
            self.close()
            self._link = self._stack.enter_context(self._open_drive(owner))
            self._drive = owner
        self._link.show(incident)

    def mark(self, incident: Incident, verdict: str | None) -> None:
        """Draw the row's verdict, if its drive is the one open."""
        if self._link is not None and self._fleet.session_of(incident) is self._drive:
            self._link.mark(incident, verdict)

    def close(self) -> None:
        """Close the open drive's link and pass."""
        self._link = None
        self._drive = None
        self._stack.close()
        self._stack = contextlib.ExitStack()
