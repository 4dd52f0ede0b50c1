"""Incidents whose facts rest on implausible data: ``Incident.data_suspect``.

An incident is suspect when its own objects or the ego have a finding whose frames overlap
the incident's (the facts — gap, speeds, time to collision, compliance — were computed from
those states). It is flagged with one reason per object and kind (the worst overlapping
finding), never dropped; the incident order ranks suspect incidents after clean ones.
"""

from __future__ import annotations

import dataclasses
from typing import TYPE_CHECKING

from workbench.quality.checks import Kind
from workbench.quality.tracks import EGO_ID

if TYPE_CHECKING:
    from collections.abc import Iterable, Sequence

    from workbench.incidents.model import Incident
    from workbench.quality.checks import Finding

__all__ = ["flag_suspects", "suspect_reasons"]

_KIND_ORDER = {k: n for n, k in enumerate(Kind)}


def suspect_reasons(incident: Incident, findings: Iterable[Finding]) -> tuple[str, ...]:
    """Why an incident's facts rest on implausible data (empty: clean).

    One reason (:meth:`Finding.reason`) per object and kind: the worst finding of the
    incident's objects or the ego that overlaps its frames; the ego's first.
    """
    parties = {EGO_ID, *incident.objects}
    worst: dict[tuple[str, Kind], Finding] = {}
    for f in findings:
        if f.object_id not in parties:
            continue
        if f.end_frame < incident.start_frame or f.start_frame > incident.end_frame:
            continue
        key = (f.object_id, f.kind)
        old = worst.get(key)
        if old is None or f.excess > old.excess:
            worst[key] = f
    keys = sorted(worst, key=lambda k: (k[0] != EGO_ID, k[0], _KIND_ORDER[k[1]]))
    return tuple(worst[k].reason() for k in keys)


def flag_suspects(incidents: Sequence[Incident], findings: Sequence[Finding]) -> list[Incident]:
    """The incidents (same order) with ``data_suspect`` set from the findings."""
    return [dataclasses.replace(i, data_suspect=suspect_reasons(i, findings)) for i in incidents]
