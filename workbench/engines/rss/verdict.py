"""The structured RSS verdict of one frame: typed and frozen; record, layout and sinks read it."""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from rss.profiles import LIBRARY_PROFILE
from rss.structured.responsibility import Responsible

if TYPE_CHECKING:
    from numpy.typing import NDArray

    from rss import FrameResult
    from workbench.engines.rss.causes import RssCause

__all__ = ["ObjectSeverity", "Obligation", "RssVerdict"]


@dataclass(frozen=True, slots=True)
class Obligation:
    """One party's proper response towards one object at one frame.

    Attributes:
        party: ``Responsible.EGO`` or ``Responsible.OBJECT``.
        since_ns: First frame of the current run in which the party had to act.
        due_ns: ``since_ns`` + the party's response time.
        required_max_mps2: Its longitudinal acceleration must stay at or below this
            (negative: brake); ``None`` when only a lateral response is due.
        measured_mps2: Its measured longitudinal acceleration (``None``: too few samples).
        shortfall_mps2: ``max(0, measured - required)`` once due; ``None`` before, without
            a longitudinal requirement or without a measurement.
    """

    party: Responsible
    since_ns: int
    due_ns: int
    required_max_mps2: float | None
    measured_mps2: float | None
    shortfall_mps2: float | None


@dataclass(frozen=True, slots=True)
class ObjectSeverity:
    """Severity facts of one object in one frame (worst over its constellations).

    Attributes:
        distance_ratio: Smallest current / safe distance of the dimension closer to safe.
        ttc_s: Smallest longitudinal time to collision [s] (``inf``: not closing).
        required_decel_mps2: Largest deceleration that removes the closing speed [m/s²].
    """

    distance_ratio: float
    ttc_s: float
    required_decel_mps2: float


@dataclass(frozen=True, slots=True)
class RssVerdict:
    """Structured RSS on one frame: ``C`` constellations, or none.

    Attributes:
        is_safe: No dangerous constellation.
        culprits: Labels of the dangerous objects, sorted.
        cause: The proper responses demanded when unsafe (typed; its text ``"RSS lon
            BrakeMin, lat-left BrakeMin"`` names the non-``None`` ones of longitudinal,
            lateral left, lateral right), else ``""``.
        margin: When unsafe the smallest distance ratio of the dangerous constellations
            (current / safe distance of the dimension closer to safe, in ``[0, 1)``;
            docs/rss.md, "Severity"), else ``inf``.
        invalid_objects: Ids of objects that could not be checked (not placeable, bad
            values), sorted.
        labels: ``(C,)`` actor id (or ``road_boundary_left/right``) of the other object of
            each constellation.
        constellation_type: ``(C,)`` :class:`rss.model.ConstellationType` codes.
        object_id: ``(C,)`` engine ids of the other objects (the record's order).
        result: The engine's result for this frame (``F = 1``); ``None`` without
            constellations.
        road_areas: Outline rings of each constellation's road area in the map frame [m]
            (``(C,)`` entries of closed ``(K, 2)`` rings; empty tuple: not computed).
        rejected: ``(object id, reason)`` of each malformed constellation left out of the
            frame (also in ``invalid_objects``).
        responsible: ``(C,)`` :class:`rss.structured.responsibility.Responsible` codes: who
            must act in each constellation (``None`` without constellations).
        obligations: ``(object label, Obligation)`` of every party that must act, with its
            proper-response compliance (:mod:`workbench.engines.rss.compliance`).
        profile: The parameter profile (``RssParams.profile_label``) the frame was checked
            with.
    """

    is_safe: bool
    culprits: tuple[str, ...] = ()
    cause: RssCause | str = ""
    margin: float = float("inf")
    invalid_objects: tuple[str, ...] = ()
    labels: tuple[str, ...] = ()
    constellation_type: NDArray[np.int64] | None = None
    object_id: NDArray[np.int64] | None = None
    result: FrameResult | None = None
    road_areas: tuple[tuple[NDArray[np.float64], ...], ...] = ()
    rejected: tuple[tuple[str, str], ...] = ()
    responsible: NDArray[np.int64] | None = None
    obligations: tuple[tuple[str, Obligation], ...] = ()
    profile: str = LIBRARY_PROFILE

    def severity(self) -> dict[str, ObjectSeverity]:
        """Severity facts per object dangerous from either side, sorted by label."""
        result = self.result
        if result is None or result.severity is None or result.responsibility is None:
            return {}
        facts = result.severity
        either = result.dangerous | result.responsibility.object_dangerous
        out: dict[str, ObjectSeverity] = {}
        for k in np.flatnonzero(either).tolist():
            label = self.labels[k]
            new = ObjectSeverity(
                float(facts.distance_ratio[k]),
                float(facts.ttc_s[k]),
                float(facts.required_decel_mps2[k]),
            )
            old = out.get(label)
            if old is not None:
                new = ObjectSeverity(
                    min(old.distance_ratio, new.distance_ratio),
                    min(old.ttc_s, new.ttc_s),
                    max(old.required_decel_mps2, new.required_decel_mps2),
                )
            out[label] = new
        return dict(sorted(out.items()))

    def responsibility(self) -> dict[str, Responsible]:
        """Who must act per object (``EGO``, ``OBJECT`` or ``BOTH``), sorted by label.

        Every object one of whose constellations is dangerous from either side is listed.
        """
        if self.responsible is None:
            return {}
        codes: dict[str, int] = {}
        for label, code in zip(self.labels, self.responsible.tolist(), strict=True):
            if code:
                codes[label] = codes.get(label, 0) | int(code)
        return {label: Responsible(code) for label, code in sorted(codes.items())}

    def object_margin(self, object_id: str) -> float:
        """The margin of one object's constellations: its smallest distance ratio.

        The frame's ``margin`` when the object has no severity facts (``inf`` when safe).
        """
        facts = self.severity().get(object_id)
        return self.margin if facts is None else facts.distance_ratio

    @property
    def constellations(self) -> int:
        """Number of constellations checked."""
        return len(self.labels)
