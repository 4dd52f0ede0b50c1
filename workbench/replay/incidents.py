"""What a replay shows of a drive's incidents (pure: no Rerun import).

::

    incidents/lanes/<engine>/<incident id>   state lane: its review state over its frames
    incidents/log                            one labelled marker (text log line) per incident
                                             at its first frame: id, cause, object, verdict

A lane turns ``unreviewed`` / ``confirmed`` / ``false_positive`` / ``follow_up`` at the
incident's first frame and ``clear`` (not drawn) at the first frame after its last one.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from workbench.annotations.schema import ReviewVerdict
from workbench.replay.short_labels import ShortLabels

if TYPE_CHECKING:
    from collections.abc import Callable, Mapping, Sequence

    from numpy.typing import NDArray

    from workbench.incidents import Incident

__all__ = [
    "INCIDENT_LOG",
    "INCIDENT_STATES",
    "LANES_ORIGIN",
    "UNREVIEWED",
    "IncidentLane",
    "IncidentLayout",
    "layout_incidents",
    "marker_text",
    "short_labels",
]

#: Origin of the incident state lanes (the viewer's "incidents" tab).
LANES_ORIGIN = "incidents/lanes"
#: Entity of the incident markers.
INCIDENT_LOG = "incidents/log"
#: State of an incident nobody has labelled yet.
UNREVIEWED = "unreviewed"
_CLEAR = "clear"
#: Lane states and their packed RGBA colours (``clear`` is hidden).
INCIDENT_STATES: dict[str, int] = {
    UNREVIEWED: 0xFFA726FF,
    ReviewVerdict.CONFIRMED.value: 0xE53935FF,
    ReviewVerdict.FALSE_POSITIVE.value: 0x9E9E9EFF,
    ReviewVerdict.FOLLOW_UP.value: 0x42A5F5FF,
    _CLEAR: 0x00000000,
}


@dataclass(frozen=True, slots=True)
class IncidentLane:
    """One incident's state lane: ``K`` (1 or 2) state changes."""

    path: str
    frames: NDArray[np.int64]
    t_ns: NDArray[np.int64]
    states: tuple[str, ...]


@dataclass(frozen=True, slots=True)
class IncidentLayout:
    """Every lane and the markers (``M`` incidents, by first frame)."""

    lanes: tuple[IncidentLane, ...]
    marker_frames: NDArray[np.int64]
    marker_t_ns: NDArray[np.int64]
    marker_texts: tuple[str, ...]
    marker_levels: tuple[str, ...]


def short_labels(incidents: Sequence[Incident]) -> ShortLabels:
    """A short label per object of a drive's incidents: ``#1``, ``#2``, ... by first incident.

    Objects are numbered in the order their first incident starts (ties: by id), so the
    review table, its facts and the viewer's labels name an object alike (ids of
    ``derived_object_msgs`` fill 32 columns); :class:`ShortLabels` numbers further objects
    (bystanders the engines label) after them.
    """
    ordered = sorted(incidents, key=lambda i: (i.start_frame, i.id))
    return ShortLabels(obj for incident in ordered for obj in incident.objects)


def marker_text(incident: Incident, verdict: str | None) -> str:
    """The marker's label: ``[verdict] id  cause  object  margin``."""
    margin = incident.severity.worst_margin
    facts = f"margin {margin:.2f}" if math.isfinite(margin) else ""
    who = " ".join(incident.objects) or "-"
    return f"[{verdict or UNREVIEWED}] {incident.id}  {incident.cause}  object {who}  {facts}"


def layout_incidents(
    incidents: Sequence[Incident],
    verdicts: Mapping[str, str],
    frame_times: Sequence[tuple[int, int]],
    *,
    escape: Callable[[str], str] = str,
) -> IncidentLayout:
    """Lanes and markers of the incidents.

    Args:
        incidents: The drive's incidents (any order).
        verdicts: Review verdict per incident id (unlabelled ones absent).
        frame_times: ``(frame index, t_ns)`` of every frame, in order.
        escape: Escapes an id as one entity path part (the sink passes Rerun's).
    """
    times = dict(frame_times)
    order = [f for f, _ in frame_times]
    position = {f: k for k, f in enumerate(order)}
    lanes = []
    for incident in incidents:
        frames = [incident.start_frame]
        states = [verdicts.get(incident.id, UNREVIEWED)]
        after = position[incident.end_frame] + 1
        if after < len(order):
            frames.append(order[after])
            states.append(_CLEAR)
        lanes.append(
            IncidentLane(
                path=f"{LANES_ORIGIN}/{incident.engine}/{escape(incident.id)}",
                frames=np.array(frames, dtype=np.int64),
                t_ns=np.array([times[f] for f in frames], dtype=np.int64),
                states=tuple(states),
            )
        )
    by_start = sorted(incidents, key=lambda i: (i.start_frame, i.id))
    return IncidentLayout(
        lanes=tuple(lanes),
        marker_frames=np.array([i.start_frame for i in by_start], dtype=np.int64),
        marker_t_ns=np.array([i.start_ns for i in by_start], dtype=np.int64),
        marker_texts=tuple(marker_text(i, verdicts.get(i.id)) for i in by_start),
        marker_levels=tuple(
            "WARN" if verdicts.get(i.id) in {None, "follow_up"} else "INFO" for i in by_start
        ),
    )
