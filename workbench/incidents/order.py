"""The one severity order of incidents and events (docs/review.md, "Severity order").

Every list of incidents (the ``incidents`` table and files, ``review``, clip export,
OpenLABEL) is in this order. It rests on the physical facts of the incident's own object
(:mod:`workbench.incidents.kinematics`), which mean the same whatever engine found the
incident; the engines' own margins (RSS distance ratio, reach-set time offset) are facts of
their incidents but never compared across engines. Most severe first:

1. clean before suspect: incidents whose facts rest on implausible data (``data_suspect``)
   come after every clean one;
2. higher criticality: ``max(TTC_REF_S / ttc, decel / DECEL_REF_MPS2)`` of the frames'
   time to collision along the path and required deceleration, the largest held over two
   consecutive unsafe frames (:mod:`workbench.incidents.kinematics`), 0 when never on a
   collision course (>= 1: critical by the thresholds of the criticality-metrics
   catalogue, TTC <= 1.5 s or required deceleration >= 3.4 m/s²);
3. smaller gap between the footprints;
4. larger compliance shortfall (engines that judge compliance: RSS);
5. faster closing;
6. longer, then more unsafe frames;
7. earlier start, then id (a total order: the same incidents always list the same way).
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Protocol

if TYPE_CHECKING:
    from collections.abc import Mapping


class _Severity(Protocol):
    @property
    def facts(self) -> Mapping[str, object]: ...
    @property
    def unsafe_frames(self) -> int: ...


class Incident(Protocol):
    """What the order reads of an incident (``workbench.incidents.model.Incident``)."""

    @property
    def id(self) -> str: ...
    @property
    def start_ns(self) -> int: ...
    @property
    def duration_s(self) -> float: ...
    @property
    def data_suspect(self) -> tuple[str, ...]: ...
    @property
    def severity(self) -> _Severity: ...


__all__ = [
    "DECEL_REF_MPS2",
    "MAX_CRITICALITY",
    "TTC_REF_S",
    "SeverityKey",
    "criticality",
    "rank",
    "severity_key",
]

#: Time to collision at and below which an approach is critical [s].
TTC_REF_S = 1.5
#: Required deceleration at and above which an approach is critical [m/s²].
DECEL_REF_MPS2 = 3.4
#: Criticality of touching footprints (time to collision 0): the scale's finite top.
MAX_CRITICALITY = 100.0


def _number(value: object) -> float | None:
    if isinstance(value, bool) or not isinstance(value, int | float):
        return None
    return float(value) if math.isfinite(value) else None


def criticality(ttc_s: float | None, decel_mps2: float | None) -> float:
    """``max(TTC_REF_S / ttc, decel / DECEL_REF_MPS2)``, in ``[0, MAX_CRITICALITY]``."""
    by_ttc = 0.0
    if ttc_s is not None:
        by_ttc = MAX_CRITICALITY if ttc_s <= 0 else TTC_REF_S / ttc_s
    by_decel = 0.0 if decel_mps2 is None else decel_mps2 / DECEL_REF_MPS2
    return min(max(by_ttc, by_decel), MAX_CRITICALITY)


def rank(incident: Incident) -> dict[str, float | None]:
    """The facts the order compares, by name (JSON-ready: finite or ``None``)."""
    facts = incident.severity.facts
    return {
        "suspect": float(bool(incident.data_suspect)),
        "criticality": _number(facts.get("criticality")) or 0.0,
        "gap_min_m": _number(facts.get("gap_min_m")),
        "shortfall_max_mps2": _number(facts.get("shortfall_max_mps2")),
        "closing_speed_max_mps": _number(facts.get("closing_speed_max_mps")),
        "duration_s": incident.duration_s,
        "unsafe_frames": float(incident.severity.unsafe_frames),
    }


#: :func:`severity_key`'s type.
SeverityKey = tuple[float, float, float, float, float, float, float, int, str]


def severity_key(incident: Incident) -> SeverityKey:
    """Sort key, most severe first (``sorted(incidents, key=severity_key)``)."""
    facts = rank(incident)
    gap = facts["gap_min_m"]
    return (
        facts["suspect"] or 0.0,
        -(facts["criticality"] or 0.0),
        math.inf if gap is None else gap,
        -(facts["shortfall_max_mps2"] or 0.0),
        -(facts["closing_speed_max_mps"] or 0.0),
        -incident.duration_s,
        -incident.severity.unsafe_frames,
        incident.start_ns,
        incident.id,
    )
