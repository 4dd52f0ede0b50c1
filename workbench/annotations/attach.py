"""Which stored labels belong to which incident; the rest named, never dropped.

:func:`label_of` gives an incident its label: the one stored under its id, else the
latest one stored under one of its ``legacy_ids`` (an RSS incident of a workbench version
that split incidents at every change of cause).

An incident id depends on the drive and on every setting that decides the incidents
(engines, RSS profile, reach rules, files, merging; :meth:`IncidentRequest.record`), and on
what the engines compute. Labels written under other settings, or by a workbench version
whose engines found other incidents, stay in the store but match no incident of the
current run. The commands that read labels (``review``, ``labels export``, ``export``) say
so in one line, with the settings that differ.
"""

from __future__ import annotations

from collections import Counter
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from collections.abc import Mapping

    from workbench.annotations.store import Label
    from workbench.incidents import Incident, IncidentReport

__all__ = ["elsewhere_note", "label_of", "labels_elsewhere", "labels_for"]

#: Differing settings named in the note, most frequent first.
_NAMED = 3


def label_of(incident: Incident, labels: Mapping[str, Label]) -> Label | None:
    """The incident's label: its own, else the latest label of its legacy ids, else ``None``."""
    own = labels.get(incident.id)
    if own is not None:
        return own
    older = [labels[i] for i in incident.legacy_ids if i in labels]
    return max(older, key=lambda x: (x.labelled_ns, x.event_id), default=None)


def labels_for(report: IncidentReport, labels: Mapping[str, Label]) -> dict[str, Label]:
    """Each labelled incident's :func:`label_of` by id (``labels``: the drive's, by id)."""
    found = {i.id: label_of(i, labels) for i in report.incidents}
    return {key: label for key, label in found.items() if label is not None}


def labels_elsewhere(report: IncidentReport, labels: Mapping[str, Label]) -> list[Label]:
    """The drive's stored labels of no incident (nor of a legacy id of one), by incident id."""
    known = {i for incident in report.incidents for i in (incident.id, *incident.legacy_ids)}
    return [label for key, label in sorted(labels.items()) if key not in known]


def _value(value: Any) -> str:
    if isinstance(value, list):
        return ",".join(map(str, value))
    if isinstance(value, str) and len(value) == 64:  # noqa: PLR2004 - a SHA-256 hex digest
        return value[:8]
    return str(value)


def elsewhere_note(report: IncidentReport, labels: Mapping[str, Label]) -> str | None:
    """One line about the labels of other settings, or ``None`` when every label matches."""
    away = labels_elsewhere(report, labels)
    if not away:
        return None
    differing: Counter[str] = Counter()
    for label in away:
        for key, value in label.settings.items():
            now = report.settings.get(key)
            if value != now:
                differing[f"{key} {_value(value)} (now {_value(now)})"] += 1
    if differing:
        made = "made with " + "; ".join(d for d, _ in differing.most_common(_NAMED))
    else:
        made = "made with the same settings (the engines found other incidents then)"
    return (
        f"{len(away)} label(s) of this drive are for incidents these settings do not find, "
        f"{made}; they stay in the store"
    )
