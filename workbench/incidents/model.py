"""Incident records: a run of unsafe frames of one engine, object and cause, with its severity."""

from __future__ import annotations

import hashlib
import math
from dataclasses import dataclass, field
from typing import Any

from loaders.timebase import ns_to_s
from workbench.incidents.order import rank

__all__ = ["Fact", "Incident", "IncidentSettings", "Severity", "incident_id"]

#: A severity fact's value.
Fact = float | int | str | bool | None


@dataclass(frozen=True, slots=True)
class IncidentSettings:
    """How unsafe frames become incidents.

    Attributes:
        min_duration_s: Incidents shorter than this (last minus first unsafe frame time)
            are dropped; ``0`` keeps single frames.
        merge_gap_s: Safe stretches of at most this long (from the first safe frame to the
            next unsafe one) are bridged; ``0`` ends an incident at any safe frame.
    """

    min_duration_s: float = 0.0
    merge_gap_s: float = 0.0

    def __post_init__(self) -> None:
        """Reject negative or non-finite settings."""
        for name in ("min_duration_s", "merge_gap_s"):
            value = getattr(self, name)
            if not math.isfinite(value) or value < 0:
                raise ValueError(f"{name} must be a finite number >= 0, not {value}")


@dataclass(frozen=True, slots=True)
class Severity:
    """What says how bad an incident is.

    Attributes:
        worst_margin: The smallest margin of the engine's verdicts on the incident's own
            object over the incident (the engine's unit: RSS the distance ratio,
            unstructured 0.0 when unsafe, reach sets the earliest collision offset [s]);
            smaller is worse, but never compared across engines (the order is
            :func:`workbench.incidents.order.severity_key`).
        unsafe_frames: Frames rated unsafe within the incident.
        duration_s: Last minus first unsafe frame time [s].
        facts: Further facts by name: the physical facts of the own object
            (:mod:`workbench.incidents.kinematics`) and those of the collectors of
            :mod:`workbench.incidents.facts` (e.g. responsibility, compliance).
    """

    worst_margin: float
    unsafe_frames: int
    duration_s: float
    facts: dict[str, Fact] = field(default_factory=dict)

    def record(self) -> dict[str, Any]:
        """JSON-ready: the facts by name (a non-finite margin becomes ``None``)."""
        margin = self.worst_margin if math.isfinite(self.worst_margin) else None
        return {
            "worst_margin": margin,
            "unsafe_frames": self.unsafe_frames,
            "duration_s": self.duration_s,
            **self.facts,
        }


def incident_id(
    drive_hash: str, engine: str, objects: tuple[str, ...], cause: str, start: int
) -> str:
    """Stable id ``<engine>-<start frame>-<hash>``.

    The hash covers the drive's content hash, engine, objects, cause and start frame.
    """
    key = "\0".join((drive_hash, engine, "\x1f".join(objects), cause, str(start)))
    return f"{engine}-{start:06d}-{hashlib.sha256(key.encode()).hexdigest()[:10]}"


@dataclass(frozen=True, slots=True)
class Incident:
    """A run of unsafe frames of one engine, object and cause (RSS: per object).

    Attributes:
        id: Stable id (:func:`incident_id`): the same drive and settings give the same ids.
        engine: Engine name.
        objects: The object involved (one id; empty when the verdict named none).
        cause: The verdicts' cause (rule or response; RSS: the union of its frames').
        start_frame: First unsafe frame.
        end_frame: Last unsafe frame (inclusive).
        start_ns: Time of the first unsafe frame.
        end_ns: Time of the last unsafe frame.
        severity: Severity facts.
        legacy_ids: Ids the pieces of this incident had before its engine's incidents were
            one per object (``EngineSpec.join_causes``): a new piece per change of cause.
            Used to find labels written then; not in the pinned JSON.
        data_suspect: Reasons why the incident's facts rest on implausible data (a
            data-quality finding of its objects or the ego overlapping its frames,
            :mod:`workbench.quality.suspect`); empty = clean. Suspect incidents rank after
            clean ones.
        worst_frame: The frame the review viewer shows: the engine's worst (e.g. RSS: the
            smallest distance ratio; else the smallest margin); ``None``: ``start_frame``.
            Not in the pinned JSON.
    """

    id: str
    engine: str
    objects: tuple[str, ...]
    cause: str
    start_frame: int
    end_frame: int
    start_ns: int
    end_ns: int
    severity: Severity
    legacy_ids: tuple[str, ...] = ()
    data_suspect: tuple[str, ...] = ()
    worst_frame: int | None = None

    @property
    def duration_s(self) -> float:
        """Last minus first unsafe frame time [s]."""
        return ns_to_s(self.end_ns - self.start_ns)

    def record(self) -> dict[str, Any]:
        """The pinned JSON object of ``workbench incidents --out FILE.json``."""
        return {
            "id": self.id,
            "engine": self.engine,
            "objects": list(self.objects),
            "cause": self.cause,
            "start_frame": self.start_frame,
            "end_frame": self.end_frame,
            "start_ns": self.start_ns,
            "end_ns": self.end_ns,
            "duration_s": self.duration_s,
            "severity": {**self.severity.record(), "severity_rank": rank(self)},
            "data_suspect": list(self.data_suspect),
        }
