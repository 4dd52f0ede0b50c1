"""Events: one per danger, grouping the incidents of every engine on one object.

Incidents on the same object whose windows overlap (``[start_ns, end_ns]``, closed; chains
of overlaps too) are one *event*, the unit a reviewer looks at first; it carries every
engine's incident, so every engine's evidence. An incident naming no object is an event of
its own. The event id is derived from its incidents' ids only, so the same incidents give
the same event id; labels stay keyed by incident id (a verdict on an event labels each of
its incidents).
"""

from __future__ import annotations

import hashlib
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from workbench.incidents.order import severity_key

if TYPE_CHECKING:
    from collections.abc import Iterable

    from workbench.incidents.model import Incident

__all__ = ["Event", "event_id", "group_events"]


def event_id(incidents: Iterable[Incident]) -> str:
    """Stable id ``event-<first start frame>-<hash of the sorted incident ids>``."""
    members = list(incidents)
    start = min(i.start_frame for i in members)
    key = "\0".join(sorted(i.id for i in members))
    return f"event-{start:06d}-{hashlib.sha256(key.encode()).hexdigest()[:10]}"


@dataclass(frozen=True, slots=True)
class Event:
    """One danger: the overlapping incidents of every engine on one object.

    Attributes:
        id: Stable id (:func:`event_id`).
        incidents: Its incidents, most severe first (:func:`~.order.severity_key`).
    """

    id: str
    incidents: tuple[Incident, ...]

    @property
    def lead(self) -> Incident:
        """The most severe incident: the event's place in the order."""
        return self.incidents[0]

    @property
    def objects(self) -> tuple[str, ...]:
        """The object (shared by its incidents)."""
        return self.lead.objects

    @property
    def engines(self) -> tuple[str, ...]:
        """Engines with an incident in it, in order of severity."""
        return tuple(dict.fromkeys(i.engine for i in self.incidents))

    @property
    def start_ns(self) -> int:
        """Earliest incident start."""
        return min(i.start_ns for i in self.incidents)

    @property
    def end_ns(self) -> int:
        """Latest incident end."""
        return max(i.end_ns for i in self.incidents)

    @property
    def start_frame(self) -> int:
        """Earliest incident start frame."""
        return min(i.start_frame for i in self.incidents)

    @property
    def end_frame(self) -> int:
        """Latest incident end frame."""
        return max(i.end_frame for i in self.incidents)

    def record(self) -> dict[str, Any]:
        """JSON-ready: the span, engines and incident ids (most severe first)."""
        return {
            "id": self.id,
            "objects": list(self.objects),
            "engines": list(self.engines),
            "start_frame": self.start_frame,
            "end_frame": self.end_frame,
            "start_ns": self.start_ns,
            "end_ns": self.end_ns,
            "incidents": [i.id for i in self.incidents],
        }


def _make(members: list[Incident]) -> Event:
    members.sort(key=severity_key)
    return Event(event_id(members), tuple(members))


def group_events(incidents: Iterable[Incident]) -> list[Event]:
    """The incidents' events, most severe first (by each event's most severe incident)."""
    by_object: dict[tuple[str, ...], list[Incident]] = {}
    alone: list[Event] = []
    for incident in incidents:
        if incident.objects:
            by_object.setdefault(incident.objects, []).append(incident)
        else:
            alone.append(_make([incident]))
    events = alone
    for found in by_object.values():
        found.sort(key=lambda i: (i.start_ns, i.end_ns, i.id))
        group = [found[0]]
        end_ns = found[0].end_ns
        for incident in found[1:]:
            if incident.start_ns <= end_ns:
                group.append(incident)
                end_ns = max(end_ns, incident.end_ns)
            else:
                events.append(_make(group))
                group, end_ns = [incident], incident.end_ns
        events.append(_make(group))
    events.sort(key=lambda e: (severity_key(e.lead), e.id))
    return events
