"""The review loop's terminal UI (textual): incidents worst first, one key per verdict.

::

    ┌ drive.mcap: 3 of 10 reviewed ─────────────────────────────────────────────┐
    │ verdict  id                     engine  object  cause          start  dur │
    │ >        rss-000119-b09b019ca5  rss     1       RSS BrakeMin   5.95   14.1│
    │ ...                                                                       │
    ├───────────────────────────────────────────────────────────────────────────┤
    │ facts of the incident under the cursor: frames, times, margin, tags, note │
    ├───────────────────────────────────────────────────────────────────────────┤
    │ c confirmed  f false positive  u follow-up  t tag  n note  z undo  q quit │
    └───────────────────────────────────────────────────────────────────────────┘

Moving the cursor moves the viewer (:mod:`workbench.review.viewer`) to that incident.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, ClassVar

from textual.app import App, ComposeResult
from textual.binding import Binding, BindingType
from textual.widgets import DataTable, Footer, Header, Input, Static

from loaders.timebase import ns_to_s
from workbench.review.facts_text import NONE, facts_text, number_text
from workbench.review.viewer import NoViewer, worst_frame

if TYPE_CHECKING:
    from workbench.incidents import Incident
    from workbench.review.fleet import FleetSession
    from workbench.review.session import ReviewSession
    from workbench.review.viewer import ViewerLink

__all__ = ["ReviewApp"]

_SHOWN = {"confirmed": "confirmed", "false_positive": "false pos", "follow_up": "follow-up"}


class ReviewApp(App[None]):
    """Walk a drive's incidents and record verdicts, tags and notes."""

    CSS = """
    #incidents { height: 1fr; }
    #facts { height: auto; max-height: 12; border-top: solid $accent; padding: 0 1; }
    #prompt { display: none; }
    #prompt.open { display: block; }
    """
    BINDINGS: ClassVar[list[BindingType]] = [
        Binding("c", "verdict('confirmed')", "confirmed"),
        Binding("f", "verdict('false_positive')", "false positive"),
        Binding("u", "verdict('follow_up')", "follow-up"),
        Binding("t", "ask('tag')", "tag"),
        Binding("n", "ask('note')", "note"),
        Binding("z", "undo", "undo"),
        Binding("w", "what_if", "what-if profile"),
        Binding("i", "full_ids", "full ids"),
        Binding("j", "step(1)", "next"),
        Binding("k", "step(-1)", "prev"),
        Binding("q", "quit", "quit"),
    ]

    def __init__(
        self, session: ReviewSession | FleetSession, viewer: ViewerLink | None = None
    ) -> None:
        """Review ``session``'s incidents, moving ``viewer`` along."""
        super().__init__()
        self.session = session
        self.viewer = viewer or NoViewer()
        self._asking: str | None = None
        self._what_if_index = -1
        self._full_ids = False

    def compose(self) -> ComposeResult:
        """Title, table, facts, prompt, key help."""
        yield Header()
        yield DataTable(id="incidents", cursor_type="row", zebra_stripes=True)
        yield Static(id="facts", markup=False)
        yield Input(id="prompt")
        yield Footer()

    def on_mount(self) -> None:
        """Fill the table and go to where the last session stopped."""
        table = self.query_one(DataTable)
        table.add_column("verdict", width=max(map(len, _SHOWN.values())))
        table.add_columns("id", "engine", "object", "cause", "start s", "dur s", "margin")
        for incident in self.session.incidents:
            t0 = self.session.session_of(incident).report.start_ns
            margin = incident.severity.worst_margin
            table.add_row(
                self._verdict_cell(incident),
                incident.id,
                incident.engine,
                self._objects(incident, full=False),
                incident.cause,
                f"{ns_to_s(incident.start_ns - t0):.2f}",
                f"{incident.duration_s:.2f}",
                number_text(margin) if math.isfinite(margin) else NONE,
                key=incident.id,
            )
        table.focus()
        self._go(self.session.index)

    def _objects(self, incident: Incident, *, full: bool) -> str:
        """The incident's objects by short label (``#1``), with the full ids when ``full``."""
        if not incident.objects:
            return NONE
        short = self.session.session_of(incident).short_labels
        return " ".join(
            f"{short.get(o, o)} = {o}" if full else short.get(o, o) for o in incident.objects
        )

    def _verdict_cell(self, incident: Incident) -> str:
        label = self.session.labels.get(incident.id)
        return _SHOWN[label.verdict] if label else "·"

    def _refresh_title(self) -> None:
        session = self.session
        self.title = (
            f"{session.report.log.name}: {session.reviewed} of {len(session.incidents)} reviewed"
        )
        self.sub_title = f"reviewer {session.reviewer}"

    def _facts(self, incident: Incident | None) -> str:
        if incident is None:
            return "no incidents in this drive with these settings"
        tags, note = self.session.tags_and_note(incident)
        label = self.session.labels.get(incident.id)
        own = self.session.session_of(incident)
        t0 = own.report.start_ns
        drive = [] if own is self.session else [f"drive {own.report.log.name}"]
        facts = facts_text(incident.severity.record(), t0_ns=t0)
        objects = self._objects(incident, full=self._full_ids)
        return "\n".join(
            [
                *drive,
                f"{incident.id}  [{label.verdict if label else 'unreviewed'}]"
                + (f" by {label.reviewer}" if label else ""),
                f"{incident.engine}: {incident.cause}; object {objects}"
                + ("" if self._full_ids or not incident.objects else "  (i: full ids)"),
                (
                    f"frames {incident.start_frame}-{incident.end_frame}"
                    f" (worst {worst_frame(incident)}), "
                    f"{ns_to_s(incident.start_ns - t0):.2f} s"
                    f" to {ns_to_s(incident.end_ns - t0):.2f} s"
                ),
                f"severity: {facts}",
                *self.session.evidence(incident),
                f"tags: {', '.join(tags) or NONE}   note: {note or NONE}",
            ]
        )

    def _go(self, index: int) -> None:
        incident = self.session.go(index)
        table = self.query_one(DataTable)
        if incident is not None and table.cursor_row != self.session.index:
            table.move_cursor(row=self.session.index)
        self._show(incident)

    def _show(self, incident: Incident | None) -> None:
        self._refresh_title()
        self.query_one("#facts", Static).update(self._facts(incident))
        if incident is not None:
            self.viewer.show(incident)

    def _redraw_row(self, incident: Incident) -> None:
        table = self.query_one(DataTable)
        table.update_cell(incident.id, table.ordered_columns[0].key, self._verdict_cell(incident))
        label = self.session.labels.get(incident.id)
        self.viewer.mark(incident, label.verdict if label else None)

    def on_data_table_row_highlighted(self, event: DataTable.RowHighlighted) -> None:
        """The cursor moved: follow it."""
        if event.cursor_row != self.session.index:
            self.session.go(event.cursor_row)
            self._show(self.session.current)

    def action_step(self, step: int) -> None:
        """Next / previous incident."""
        self._go(self.session.index + step)

    def action_verdict(self, verdict: str) -> None:
        """Record a verdict and go on to the next incident."""
        incident = self.session.current
        if incident is None:
            return
        self.session.give(verdict)
        self._redraw_row(incident)
        self._go(self.session.index + 1)
        self._show(self.session.current)

    def action_full_ids(self) -> None:
        """Show or hide the full object ids in the facts panel."""
        self._full_ids = not self._full_ids
        self.query_one("#facts", Static).update(self._facts(self.session.current))

    def action_undo(self) -> None:
        """Take back this session's last write."""
        incident = self.session.undo()
        if incident is None:
            self.notify("nothing to undo in this session")
            return
        self._redraw_row(incident)
        self._go(self.session.index)

    def action_what_if(self) -> None:
        """Re-evaluate the incident under its engine's next what-if variant; say the outcome."""
        from workbench.incidents.whatif import variants, what_if  # noqa: PLC0415

        incident, request = self.session.current, self.session.report.request
        if incident is None or request is None:
            return
        names = variants(request, incident)
        if not names:
            self.notify(f"no what-if for engine {incident.engine}")
            return
        self._what_if_index = (self._what_if_index + 1) % len(names)
        outcome = what_if(request, incident, names[self._what_if_index])
        self.query_one("#facts", Static).update(self._facts(incident) + "\n" + outcome.line())
        self.notify(outcome.line())

    def action_ask(self, what: str) -> None:
        """Open the prompt for a tag or a note."""
        if self.session.current is None:
            return
        prompt = self.query_one("#prompt", Input)
        self._asking = what
        _, note = self.session.tags_and_note(self.session.current)
        prompt.value = note if what == "note" else ""
        prompt.placeholder = f"{what} (Enter saves, Escape cancels)"
        prompt.add_class("open")
        prompt.focus()

    def _close_prompt(self) -> None:
        prompt = self.query_one("#prompt", Input)
        prompt.remove_class("open")
        self._asking = None
        self.query_one(DataTable).focus()

    def on_input_submitted(self, event: Input.Submitted) -> None:
        """Save the tag or note typed."""
        if self._asking == "tag":
            self.session.add_tag(event.value)
        elif self._asking == "note":
            self.session.set_note(event.value)
        incident = self.session.current
        self._close_prompt()
        if incident is not None:
            self._redraw_row(incident)
            self._show(incident)

    def key_escape(self) -> None:
        """Cancel the prompt."""
        if self._asking is not None:
            self._close_prompt()
