"""RSS facts of an incident: who must act, the worst severity, the compliance shortfall.

One collector per incident sees the incident's unsafe frames of its one object and keeps:

- ``responsible``: who had to act over the incident (``ego``, ``object`` or ``both``);
- ``distance_ratio_min``: the worst current / safe distance ratio;
- ``ttc_min_s``: the smallest longitudinal time to collision (``None``: never closing);
- ``required_decel_max_mps2``: the largest deceleration the situation demanded;
- ``shortfall_max_mps2``, ``shortfall_party``, ``response_due_ns``: the largest amount by
  which a party that had to act accelerated above its restriction once its response was due,
  which party, and when its response was due (``None``: every due response was proper);
- ``profile``: the RSS parameter profile the frames were checked with (``RssVerdict.profile``).

The ratio and the along-road TTC and deceleration are RSS's own facts; incidents are ordered
by the physical facts every engine's incidents have (:mod:`workbench.incidents.order`).
"""

from __future__ import annotations

import math
from typing import Any

from rss.structured.responsibility import Responsible
from workbench.engines.rss.verdict import RssVerdict

__all__ = ["RssIncidentFacts"]


class RssIncidentFacts:
    """Collects the RSS facts of one incident (``workbench.incidents.FactCollector``)."""

    def __init__(self) -> None:
        """Start empty."""
        self._parties = Responsible.NONE
        self._ratio = math.inf
        self._ttc = math.inf
        self._decel = 0.0
        self._shortfall: float | None = None
        self._party: Responsible | None = None
        self._due: int | None = None
        self._seen = False
        self._profile = ""
        self._worst_frame: int | None = None

    def add(self, frame: int, t_ns: int, verdict: object, object_id: str) -> None:
        """One unsafe frame of the incident (its object: ``object_id``).

        Verdicts that are not :class:`RssVerdict` (summaries) carry no facts and are skipped.
        """
        del t_ns
        if not isinstance(verdict, RssVerdict):
            return
        self._seen = True
        self._profile = self._profile or verdict.profile
        who = verdict.responsibility().get(object_id, Responsible.NONE)
        self._parties = Responsible(self._parties | who)
        facts = verdict.severity().get(object_id)
        if facts is not None:
            if self._worst_frame is None or facts.distance_ratio < self._ratio:
                self._worst_frame = frame
            self._ratio = min(self._ratio, facts.distance_ratio)
            self._ttc = min(self._ttc, facts.ttc_s)
            self._decel = max(self._decel, facts.required_decel_mps2)
        for label, duty in verdict.obligations:
            short = duty.shortfall_mps2
            if label == object_id and short is not None and short > (self._shortfall or 0.0):
                self._shortfall, self._party, self._due = short, duty.party, duty.due_ns

    def worst_frame(self) -> int | None:
        """The frame of the smallest current / safe distance ratio (``None``: no RSS facts)."""
        return self._worst_frame

    def facts(self) -> dict[str, Any]:
        """The facts by name (JSON-ready: no infinities); none without an RSS verdict."""
        if not self._seen:
            return {}
        ratio = None if math.isinf(self._ratio) else round(self._ratio, 6)
        ttc = None if math.isinf(self._ttc) else round(self._ttc, 6)
        return {
            "responsible": str(self._parties) if self._parties else None,
            "distance_ratio_min": ratio,
            "ttc_min_s": ttc,
            "required_decel_max_mps2": round(self._decel, 6),
            "shortfall_max_mps2": None if self._shortfall is None else round(self._shortfall, 6),
            "shortfall_party": None if self._party is None else str(self._party),
            "response_due_ns": self._due,
            "profile": self._profile,
        }
